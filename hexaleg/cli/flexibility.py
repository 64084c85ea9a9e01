"""``hexaleg flexibility``: the 12 body extremes with their causes, ranges and FB (paper §6)."""

from __future__ import annotations

import argparse
import math
import warnings
from typing import TYPE_CHECKING

from hexaleg.cli.best_posture import add_best_posture_option, posed_inputs_from_args
from hexaleg.cli.options import (
    add_collisions_option,
    add_design_options,
    add_mode_option,
    add_output_options,
    add_stance_option,
)
from hexaleg.cli.output import check_outputs, lengths_title, print_json, print_table, write_plots
from hexaleg.cli.robot_options import add_robot_options, robot_model
from hexaleg.cli.structure_options import size_if_asked

if TYPE_CHECKING:
    from hexaleg.design import HexapodDesign
    from hexaleg.robot.imported_model import ImportedHexapodModel
    from hexaleg.robot.model import HexapodModel
    from hexaleg.stance.extremes import FlexibilityResult

DESCRIPTION = (
    "Body flexibility (paper §6): from the nominal stance the body moves along x, y, z "
    "[m] and rotates about them [rad], one coordinate at a time (--mode axis, the ADAMS "
    "semantics) or with the other five free (--mode free), until a foot leaves its "
    "reach, a joint hits its stance limit or the body touches the ground. Prints the "
    "12 extremes with their causes, the ranges (eq 28) and FB (eq 29). With --urdf, your "
    "robot: each leg its own general leg, the file's joint limits and, with --collisions, "
    "the file's collision geometry."
)

ROBOT_OPTIONS = True


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_mode_option(parser)
    add_stance_option(parser)
    add_collisions_option(parser)
    add_best_posture_option(parser)
    add_output_options(parser)
    add_robot_options(parser)


def run(args: argparse.Namespace) -> int:
    """Compute the extremes; print a table or JSON, and write the figure if asked."""
    from hexaleg.output.figures import extremes_figure, save

    design, requirements = posed_inputs_from_args(args)
    robot = robot_model(args, design)
    design = size_if_asked(design, requirements, robot is not None)[0]  # tubes drawn, collide
    if robot is not None:
        return _run_imported(args, robot)
    check_outputs({}, {"--plot": args.plot})  # before computing
    result = _extremes(args, design)
    if args.plot is not None:
        write_plots(
            args.plot, lambda out: [save(extremes_figure(result), out / "flexibility_extremes.png")]
        )
    if args.json:
        print_json(result.to_dict())
        return 0
    print_table(
        lengths_title(
            f"Body flexibility ({result.mode}, stance {' '.join(result.legs)})", design.lengths
        ),
        _rows(result),
    )
    return 0


def _run_imported(args: argparse.Namespace, model: ImportedHexapodModel) -> int:
    """The flexibility of an imported robot, in hexaleg's angles and the file's."""
    result = _extremes(args, model.design, model)
    source = str(model.robot.source)
    if args.json:
        summary = result.to_dict()
        for extreme, record in zip(result.extremes, summary["extremes"], strict=True):
            record["urdf_joint_angles"] = {
                leg: model.joint_values(leg, angles).tolist()
                for leg, angles in extreme.joint_angles.items()
            }
        print_json({"robot": source} | summary)
        return 0
    title = f"Body flexibility of {source} ({result.mode}, stance {' '.join(result.legs)})"
    print_table(lengths_title(title, model.design.lengths), _rows(result))
    return 0


def _extremes(
    args: argparse.Namespace, design: HexapodDesign, model: HexapodModel | None = None
) -> FlexibilityResult:
    """The extremes the options ask for, a progress line per search step."""
    from hexaleg.stance.extremes import FlexibilityWarning
    from hexaleg.stance.flexibility import flexibility
    from hexaleg.study.progress import progress_callback

    with warnings.catch_warnings(), progress_callback("search steps") as progress:
        warnings.simplefilter("ignore", FlexibilityWarning)  # in the output: "warnings"
        return flexibility(
            design, args.mode, args.stance, model, collisions=args.collisions, progress=progress
        )


def _rows(result: FlexibilityResult) -> list[tuple[str, str]]:
    from hexaleg.stance.constraints import TRANSLATIONS

    rows = [("FB (eq 29)", f"{result.fb:.6f}")]
    for axis, value in result.ranges.items():
        if axis in TRANSLATIONS:
            rows.append((f"range {axis} (eq 28)", f"{value:.6f} m"))
        else:
            rows.append((f"range {axis} (eq 28)", f"{value:.6f} rad ({math.degrees(value):.3f}°)"))
    for extreme in result.extremes:
        unit = "m" if extreme.axis in TRANSLATIONS else "rad"
        rows.append(
            (extreme.name, f"{extreme.value:+.6f} {unit}  limited by {extreme.description}")
        )
    if result.mode == "free":
        rows.append(("evidence", _evidence(result)))
    rows += [("warning", f"not shown to be the maximum: {doubt}") for doubt in result.doubts]
    return rows


def _evidence(result: FlexibilityResult) -> str:
    """One line on what supports the free extremes (per direction in the JSON)."""
    evidence = [e.evidence for e in result.extremes if e.evidence is not None]
    reachable = sum(e.reachable for e in evidence)
    agreeing = min((e.starts_agreeing for e in evidence), default=0)
    searches = max((e.searches for e in evidence), default=0)
    return (
        f"{reachable} of {len(evidence)} extremes reached from nominal by a feasible path; "
        f"each reached by at least {agreeing} of {searches} local searches"
    )
