"""``hexaleg posture``: the best nominal posture of your lengths, printed as ``decide`` prints."""

from __future__ import annotations

import argparse
import math
from typing import Any

from hexaleg.cli.best_posture import require_posable
from hexaleg.cli.decide import render
from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import add_design_options
from hexaleg.cli.output import print_json
from hexaleg.cli.requirement_options import add_requirement_options, requirements_from_args
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.goal import Objective
from hexaleg.evaluation.metrics import objectives
from hexaleg.study.decide import DecideResult
from hexaleg.study.posture import DEFAULT_OBJECTIVE, best_posture, posture_figures

DESCRIPTION = (
    "The best nominal posture of your lengths: the hip and knee angles (theta2, theta3 within "
    "the stance limits; theta1 = 0) that make the objective best (default: the walking "
    "payload capacity) among the postures meeting every requirement, by DIRECT then "
    "Nelder-Mead over the stance limits (about 200 designs), your posture a candidate. "
    "Printed as decide prints its best: the angles, the objective, each requirement's value, "
    "margin and what binds, every joint over its rating, with the body height and the "
    "foothold radius (each foot's horizontal distance from its leg's root); your posture "
    "beside it. loads, gait and flexibility take --best-posture for this answer."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_requirement_options(parser)
    add_objective_options(parser)
    parser.add_argument("--json", action="store_true", help="print one JSON object")


def add_objective_options(parser: argparse.ArgumentParser) -> None:
    """``--maximize`` or ``--minimize`` (default: maximize the walking payload capacity)."""
    group = parser.add_argument_group("objective").add_mutually_exclusive_group()
    group.add_argument(
        "--maximize",
        choices=objectives("maximize"),
        help=f"what to make largest (default {DEFAULT_OBJECTIVE.name})",
    )
    group.add_argument("--minimize", choices=objectives("minimize"), help="what to make smallest")


def objective_from_args(args: argparse.Namespace) -> Objective:
    """The objective ``--maximize`` or ``--minimize`` names (default: the walking payload)."""
    if getattr(args, "minimize", None):
        return Objective(args.minimize, "minimize")
    if getattr(args, "maximize", None):
        return Objective(args.maximize)
    return DEFAULT_OBJECTIVE


def run(args: argparse.Namespace) -> int:
    """Search the posture; print the answer as a table or JSON."""
    inputs = inputs_from_args(args)
    robot = inputs.robot
    require_posable(robot, "posture")
    requirements = requirements_from_args(args, inputs.requirements)
    result = best_posture(robot, requirements, objective_from_args(args))
    if args.json:
        print_json(answer_dict(result))
    else:
        print(render_posture(result))
    return 0


def answer_dict(result: DecideResult) -> dict[str, Any]:
    """``decide``'s JSON, with each design's posture, body height and foothold radius."""
    out = result.to_dict()
    for key, checked in (("best", result.best), ("yours", result.yours)):
        out[key] |= posture_figures(checked.design)
        cause = checked.evaluation.causes[result.objective.spec]
        out[key]["objective"]["limited_by"] = None if cause is None else cause.to_dict()
    return out


def render_posture(result: DecideResult) -> str:
    """``decide``'s text, each design's block followed by its posture in words."""
    lines = render(result).splitlines()
    for title, checked in (("Best design", result.best), ("Your design", result.yours)):
        at = next(i for i, line in enumerate(lines) if line.startswith(title))
        cause = checked.evaluation.causes[result.objective.spec]
        limited = [] if cause is None else [f"  {result.objective.spec.label} limited by {cause}"]
        lines[at + 1 : at + 1] = ["  " + posture_line(checked.design), *limited]
    return "\n".join(lines)


def posture_line(design: HexapodDesign) -> str:
    """``posture θ = (0, -0.418, -1.553) rad (0°, -24°, -89°), body height …, foothold …``."""
    figures = posture_figures(design)
    angles = figures["nominal_angles"]
    radians = ", ".join(f"{a:.10g}" for a in angles)
    degrees = ", ".join(f"{math.degrees(a):.3g}°" for a in angles)
    return (
        f"posture θ = ({radians}) rad ({degrees}), body height "
        f"{figures['nominal_height']:.4g} m, foothold radius {figures['foothold_radius']:.4g} m"
    )
