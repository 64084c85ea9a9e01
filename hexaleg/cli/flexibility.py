"""``hexaleg flexibility``: the 12 body extremes with their causes, ranges and FB (paper §6)."""

from __future__ import annotations

import argparse
import math
import warnings

from hexaleg.cli.best_posture import add_best_posture_option, posing
from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import (
    add_collisions_option,
    add_design_options,
    add_mode_option,
    add_output_options,
    add_stance_option,
)
from hexaleg.cli.output import check_outputs, lengths_title, print_json, print_table, write_plots
from hexaleg.evaluation.sizing import sized_for
from hexaleg.output.figures import extremes_figure, save
from hexaleg.robot.robot import Robot
from hexaleg.stance.constraints import TRANSLATIONS
from hexaleg.stance.extremes import FlexibilityResult, FlexibilityWarning
from hexaleg.stance.flexibility import flexibility
from hexaleg.study.progress import progress_callback

DESCRIPTION = (
    "Body flexibility (paper §6): from the nominal stance the body moves along x, y, z "
    "[m] and rotates about them [rad], one coordinate at a time (--mode axis, the ADAMS "
    "semantics) or with the other five free (--mode free), until a foot leaves its "
    "reach, a joint hits its stance limit or the body touches the ground. Prints the "
    "12 extremes with their causes, the ranges (eq 28) and FB (eq 29). With --urdf, your "
    "robot: each leg its own general leg, the file's joint limits and, with --collisions, "
    "the file's collision geometry."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_mode_option(parser)
    add_stance_option(parser)
    add_collisions_option(parser)
    add_best_posture_option(parser)
    add_output_options(parser)


def run(args: argparse.Namespace) -> int:
    """Compute the extremes; print a table or JSON, and write the figure if asked."""
    # sized tubes are drawn and collide
    robot = inputs_from_args(args, posing=posing(args), sizing=sized_for).robot
    check_outputs({}, {"--plot": args.plot})  # before computing
    result = _extremes(args, robot)
    if args.plot is not None:
        write_plots(
            args.plot, lambda out: [save(extremes_figure(result), out / "flexibility_extremes.png")]
        )
    if args.json:
        summary = robot.named() | result.to_dict()
        for extreme, record in zip(result.extremes, summary["extremes"], strict=True):
            record |= robot.in_file_joints(extreme.joint_angles)
        print_json(summary)
        return 0
    title = robot.titled("Body flexibility") + f" ({result.mode}, stance {' '.join(result.legs)})"
    print_table(lengths_title(title, robot.design.lengths), _rows(result))
    return 0


def _extremes(args: argparse.Namespace, robot: Robot) -> FlexibilityResult:
    """The extremes the options ask for, a progress line per search step."""
    with warnings.catch_warnings(), progress_callback("search steps") as progress:
        warnings.simplefilter("ignore", FlexibilityWarning)  # in the output: "warnings"
        return flexibility(
            robot.design,
            args.mode,
            args.stance,
            robot.model,
            collisions=args.collisions,
            progress=progress,
        )


def _rows(result: FlexibilityResult) -> list[tuple[str, str]]:
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
