"""``--best-posture`` of ``loads``, ``gait`` and ``flexibility``: stand at ``posture``'s answer.

The option is read where the design options resolve
(:func:`~hexaleg.cli.inputs.inputs_from_args`, through
:func:`~hexaleg.evaluation.inputs.resolve_inputs`' ``posing``), before the tubes are sized:
they are sized for the posture stood.
"""

from __future__ import annotations

import argparse

from hexaleg.cli.options import UsageError
from hexaleg.evaluation.inputs import Posing
from hexaleg.evaluation.requirements import Requirements
from hexaleg.robot.robot import POSTURE_FIELD, Robot
from hexaleg.study.posture import DEFAULT_OBJECTIVE, best_posture


def add_best_posture_option(parser: argparse.ArgumentParser) -> None:
    """``--best-posture``: stand the design at ``hexaleg posture``'s answer (loads, gait…)."""
    parser.add_argument(
        "--best-posture",
        action="store_true",
        help="stand the design at its best posture first: hexaleg posture's answer for the "
        "same design options and the --design file's requirements (maximizing the walking "
        "payload capacity); replaces --nominal-angles",
    )


def require_posable(robot: Robot, what: str) -> None:
    """Refuse, in one line, a robot whose posture is not searched (a robot file's is its own).

    Raises:
        UsageError: ``what`` (``--best-posture``, ``posture``) on such a robot.

    """
    if not robot.searches(POSTURE_FIELD):
        raise UsageError(f"{what} on an imported robot ({robot.name}): it stands as its file does")


def posing(args: argparse.Namespace) -> Posing | None:
    """How the robot stands with ``--best-posture`` (:func:`stand_best`); ``None`` without.

    Raises:
        UsageError: ``--best-posture`` with ``--nominal-angles``.

    """
    if not getattr(args, "best_posture", False):
        return None
    if getattr(args, "nominal_angles", None) is not None:
        raise UsageError("--best-posture chooses the nominal angles: drop --nominal-angles")
    return stand_best


def stand_best(robot: Robot, requirements: Requirements) -> Robot:
    """``robot`` at ``hexaleg posture``'s answer for ``requirements`` (its walking payload).

    Raises:
        UsageError: On a robot file (it stands as its file does).

    """
    require_posable(robot, "--best-posture")
    best = best_posture(robot, requirements, DEFAULT_OBJECTIVE).best.design
    return robot.at(nominal_angles=best.nominal_angles)
