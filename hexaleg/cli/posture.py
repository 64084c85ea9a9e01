"""``hexaleg posture``: the best nominal posture of your lengths, printed as ``decide`` prints."""

from __future__ import annotations

import argparse

from hexaleg.cli.best_posture import require_posable
from hexaleg.cli.decide import render
from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import add_design_options
from hexaleg.cli.output import print_json
from hexaleg.cli.requirement_options import add_requirement_options, requirements_from_args
from hexaleg.evaluation.goal import Objective
from hexaleg.evaluation.metrics import objectives
from hexaleg.study.posture import DEFAULT_OBJECTIVE, best_posture

DESCRIPTION = (
    "The best nominal posture of your lengths: the hip and knee angles (theta2, theta3 within "
    "the stance limits; theta1 = 0) that make the objective best (default: the walking "
    "payload capacity) among the postures meeting every requirement, by DIRECT then "
    "Nelder-Mead over the stance limits (about 200 designs), your posture a candidate. "
    "Answered on a 0.001 rad grid and printed as decide prints its best: the angles, the "
    "objective, each requirement's value, margin and what binds, every joint over its "
    "rating, with the body height and the foothold radius (each foot's horizontal distance "
    "from its leg's root); your posture beside it. loads, gait and flexibility take "
    "--best-posture for this answer."
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
    if args.json:  # decide's answer, each design's posture in it (hexaleg's legs)
        print_json(result.to_dict())
    else:
        print(render(result))
    return 0
