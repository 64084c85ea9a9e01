"""``--best-posture`` of ``loads``, ``gait`` and ``flexibility``: stand at ``posture``'s answer.

Light to import (the search is imported when the option is used), so that these commands'
parsers stay quick.
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from hexaleg.cli.options import UsageError, inputs_from_args
from hexaleg.cli.robot_table import load_robot_table
from hexaleg.design import HexapodDesign

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


def posed_inputs_from_args(args: argparse.Namespace) -> tuple[HexapodDesign, Requirements]:
    """The design and requirements the options describe; with ``--best-posture``, posed.

    The design stands at ``hexaleg posture``'s answer with ``--best-posture``, as the options
    give it otherwise (:func:`~hexaleg.cli.options.inputs_from_args`).

    Raises:
        UsageError: ``--best-posture`` with ``--urdf`` (an imported robot stands as its
            file does) or with ``--nominal-angles``.

    """
    design, in_file = inputs_from_args(args)
    if not getattr(args, "best_posture", False):
        return design, in_file
    path = getattr(args, "design", None)
    if getattr(args, "urdf", None) is not None or (
        path is not None and load_robot_table(path) is not None
    ):
        raise UsageError("--best-posture on an imported robot: it stands as its file does")
    if getattr(args, "nominal_angles", None) is not None:
        raise UsageError("--best-posture chooses the nominal angles: drop --nominal-angles")
    from hexaleg.study.posture import DEFAULT_OBJECTIVE, best_posture  # SciPy, pymoo: heavy

    return best_posture(design, in_file, DEFAULT_OBJECTIVE).best.design, in_file
