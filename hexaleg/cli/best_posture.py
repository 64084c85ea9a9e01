"""``--best-posture`` of ``loads``, ``gait`` and ``flexibility``: stand at ``posture``'s answer.

Light to import (the search is imported when the option is used), so that these commands'
parsers stay quick. The option is read where the design options resolve
(:func:`~hexaleg.cli.inputs.inputs_from_args`), before the tubes are sized: they are sized
for the posture stood.
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from hexaleg.cli.options import UsageError
from hexaleg.robot.robot import POSTURE_FIELD, Robot

if TYPE_CHECKING:
    from hexaleg.evaluation.requirements import Requirements


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


def pose_if_asked(args: argparse.Namespace, robot: Robot, requirements: Requirements) -> Robot:
    """``robot`` at ``hexaleg posture``'s answer with ``--best-posture``; else ``robot``.

    Args:
        args: The parsed options.
        robot: The robot the design options describe.
        requirements: The ``--design`` file's requirements, walking its gait.

    Raises:
        UsageError: ``--best-posture`` on a robot file (it stands as its file does) or with
            ``--nominal-angles``.

    """
    if not getattr(args, "best_posture", False):
        return robot
    require_posable(robot, "--best-posture")
    if getattr(args, "nominal_angles", None) is not None:
        raise UsageError("--best-posture chooses the nominal angles: drop --nominal-angles")
    from hexaleg.study.posture import DEFAULT_OBJECTIVE, best_posture  # SciPy: heavy

    best = best_posture(robot, requirements, DEFAULT_OBJECTIVE).best.design
    return robot.at(nominal_angles=best.nominal_angles)
