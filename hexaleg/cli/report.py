"""``hexaleg report``: the main job — every analysis, figure and table, and a recommendation."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

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
    inputs_from_args,
    walked_by,
)
from hexaleg.cli.requirement_options import add_requirement_options, requirements_from_args
from hexaleg.cli.robot_options import add_robot_options, robot_designs
from hexaleg.evaluation.metrics import METRICS
from hexaleg.output.report import (
    REPORT_HTML,
    REPORT_MD,
    REPORT_PDF,
    ReportData,
    ReportOptions,
    build_report,
)
from hexaleg.output.report.decision import DecisionRecord
from hexaleg.output.report.flexibility import FlexibilityRecord
from hexaleg.output.report.options import MAX_SENSITIVITY_POINTS, MIN_L3_POINTS
from hexaleg.output.report.recommendation import RecommendationRecord
from hexaleg.output.report.robot import RobotRecord
from hexaleg.output.report.robot_study import RobotDecisionRecord

if TYPE_CHECKING:
    from hexaleg.study.decide import DecideResult

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

ROBOT_OPTIONS = True


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
    add_robot_options(parser)


def run(args: argparse.Namespace) -> int:
    """Build the report and print where it is and what it recommends."""
    design, in_file = inputs_from_args(args)  # a bad design is refused before any note
    sweep = field_sweep_from_args(args)
    robot = robot_designs(args, design)
    if robot is not None:
        _refuse_for_robot(args, sweep is not None)
        design, model = robot.point()
        in_file = walked_by(args, in_file, model)  # the robot's own default gait
    requirements = requirements_from_args(args, in_file)
    options = ReportOptions(
        l3_points=args.l3_points,
        sensitivity_points=args.sensitivity_points,
        workers=capped_workers(args.workers),
        l1_ratios=None if args.l1_ratios is None else tuple(args.l1_ratios),
        collisions=args.collisions,
        sweep=sweep,
        pdf=args.pdf,
        requirements=requirements if requirements.given else None,
        simulate=args.simulate,
        gait=requirements.walked,
        robot=robot,
    )
    data = build_report(args.output, design, options)
    out = Path(args.output)
    if robot is not None:
        return _print_robot(data, out, args.pdf)
    rec = data[RecommendationRecord].recommendation
    _print_written(out, args.pdf)
    print(
        f"recommended l1 : l2 : l3 = {rec.l1_ratio:.3f} : {rec.l2_ratio:.3f} : "
        f"{rec.l3_ratio:.3f} (tibia ratio band {rec.l3_band[0]:.3f}-{rec.l3_band[1]:.3f}); "
        f"this design: FB = {data[FlexibilityRecord].axis.fb:.4f}"
    )
    _print_answer(data[DecisionRecord].requirements, ".3f")
    return 0


def _print_written(out: Path, pdf: bool) -> None:
    """Where the report is."""
    written = [out / REPORT_MD, out / REPORT_HTML] + ([out / REPORT_PDF] if pdf else [])
    print(f"wrote {', '.join(map(str, written[:-1]))} and {written[-1]}")


def _print_answer(answer: DecideResult | None, digits: str) -> None:
    """The lengths that meet the requirements, if some were given (``digits``: the format)."""
    if answer is not None:
        lengths = ", ".join(f"{length:{digits}}" for length in answer.best.design.lengths)
        verdict = "meets" if answer.feasible else "comes closest to meeting"
        print(f"l = ({lengths}) m {verdict} your requirements")


def _refuse_for_robot(args: argparse.Namespace, swept: bool) -> None:
    """Refuse, with ``--urdf``, the options of sections an imported robot's report leaves out."""
    given = [
        flag
        for flag, on in (
            ("--collisions", args.collisions),
            ("--simulate", args.simulate),
            ("--sweep", swept),
            ("--sensitivity-points", args.sensitivity_points != ReportOptions.sensitivity_points),
        )
        if on
    ]
    if given:
        raise UsageError(
            f"{given[0]} with --urdf: that section of the report is not run on an imported robot"
        )


def _print_robot(data: ReportData, out: Path, pdf: bool) -> int:
    """Where the imported robot's report is, its FB, and the answer to any requirements."""
    _print_written(out, pdf)
    record = data[RobotRecord]
    print(f"{record.source}: FB = {record.evaluation.metrics.value(METRICS.fb):.4f}")
    _print_answer(data[RobotDecisionRecord].answer, ".4g")
    return 0
