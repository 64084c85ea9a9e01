"""``hexaleg report``: the main job — every analysis, figure and table, and a recommendation."""

from __future__ import annotations

import argparse
from pathlib import Path

from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import (
    UsageError,
    add_collisions_option,
    add_design_options,
    add_field_sweep_option,
    add_l1_ratios_option,
    add_sweep_options,
    bounded_int,
    capped_workers,
    field_sweep_from_args,
)
from hexaleg.cli.requirement_options import add_requirement_options, requirements_from_args
from hexaleg.evaluation.goal import Goal
from hexaleg.evaluation.sizing import sized_for
from hexaleg.output.report import (
    REPORT_HTML,
    REPORT_MD,
    REPORT_PDF,
    ReportOptions,
    build_report,
    headline,
    refused_options,
)
from hexaleg.output.report.options import MAX_SENSITIVITY_POINTS, MIN_L3_POINTS

DESCRIPTION = (
    "Run the workspace, manipulability and body-flexibility analyses on the design (the "
    "built-in default unless design options say otherwise) and the paper's sweeps, and "
    "write DIR/report.md, DIR/report.html (and DIR/report.pdf with --pdf), the figures (PNG "
    "and SVG), tables and raw data "
    "(CSV/JSON), the URDF and a static 3-D viewer. The folder is replaced only when the "
    "new report is complete. With --urdf, your robot: the sections that hold for its own "
    "file (its metrics, axis-locked flexibility, statics, a study of its segments, the 3-D "
    "view, the decision over its segments); the report says which it leaves out and why."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_sweep_options(parser, "hexaleg-report", least_l3_points=MIN_L3_POINTS)
    add_collisions_option(parser)
    add_l1_ratios_option(
        parser,
        "the paper's four, recommending among those ≥ 0.10; one value fixes the coxa",
    )
    parser.add_argument(
        "--sensitivity-points",
        type=bounded_int(2, MAX_SENSITIVITY_POINTS),
        default=ReportOptions.sensitivity_points,
        metavar="N",
        help=f"tibia ratios in the posture sensitivity table, 2..{MAX_SENSITIVITY_POINTS} "
        f"(default {ReportOptions.sensitivity_points})",
    )
    add_field_sweep_option(parser, "sensitivity table over one body field instead of the variants")
    add_requirement_options(parser)
    parser.add_argument(
        "--pdf",
        action="store_true",
        help="also write DIR/report.pdf: the same report as one PDF with vector figures "
        "(needs the [pdf] extra: WeasyPrint)",
    )
    parser.add_argument(
        "--simulate",
        action="store_true",
        help="also walk the design's gait ([gait], else the default) in MuJoCo: the "
        '"Simulated walk" section (needs the [sim] extra: MuJoCo)',
    )


def run(args: argparse.Namespace) -> int:
    """Build the report and print where it is and what it recommends."""
    inputs = inputs_from_args(args, sizing=sized_for)  # a bad design: refused before any note
    robot, in_file = inputs.robot, inputs.requirements  # in_file.walked: the robot's gait
    requirements = requirements_from_args(args, in_file)
    if requirements.given:  # what the design cannot measure, refused before any section
        Goal(requirements.resolved(robot.design)).measurable(robot.design)
    options = ReportOptions(
        l3_points=args.l3_points,
        sensitivity_points=args.sensitivity_points,
        workers=capped_workers(args.workers),
        l1_ratios=None if args.l1_ratios is None else tuple(args.l1_ratios),
        collisions=args.collisions,
        sweep=field_sweep_from_args(args),
        pdf=args.pdf,
        requirements=requirements if requirements.given else None,
        simulate=args.simulate,
        gait=requirements.walked,
        default_gait=inputs.default_gait,
    )
    refused = refused_options(robot, options)  # an option whose section is left out
    if refused:
        name, left = refused[0]
        raise UsageError(
            f"--{name.replace('_', '-')} with --urdf: that section of the report is not run "
            f"on an imported robot ({left.section}: {left.why})"
        )
    data = build_report(args.output, robot, options)
    out = Path(args.output)
    written = [out / REPORT_MD, out / REPORT_HTML] + ([out / REPORT_PDF] if args.pdf else [])
    print(f"wrote {', '.join(map(str, written[:-1]))} and {written[-1]}")
    for line in headline(data):
        print(line)
    return 0
