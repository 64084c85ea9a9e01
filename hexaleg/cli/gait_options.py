"""The gait's options, over the gait the robot walks: gait and simulate."""

from __future__ import annotations

import argparse

from hexaleg._typing import GaitPattern, choices
from hexaleg.cli.options import UsageError, bounded_int
from hexaleg.gait.spec import SAMPLES_RANGE, Gait

DEFAULT = Gait()
"""The defaults each option's help names (hexaleg's template's gait)."""


def add_gait_options(parser: argparse.ArgumentParser) -> None:
    """The gait's options (gait, simulate): pattern, period, stride, step height, heading..."""
    group = parser.add_argument_group(
        "gait (defaults: the --design file's [gait] table, else chosen for the default robot)"
    )
    group.add_argument(
        "--pattern",
        choices=choices(GaitPattern),
        help="which legs swing together: three, two or one at a time (default tripod)",
    )
    for flag, metavar, what in (
        ("--period", "S", "period T [s]"),
        ("--stride", "M", "stride S, how far a standing foot moves relative to the body [m]"),
        ("--step-height", "M", "step height H, the swinging foot's top above the ground [m]"),
        ("--heading", "RAD", "direction of travel ψ in the body frame [rad] (0: ahead)"),
    ):
        name = flag[2:].replace("-", "_")
        group.add_argument(
            flag, type=float, metavar=metavar, help=f"{what} (default {getattr(DEFAULT, name):g})"
        )
    group.add_argument(
        "--speed",
        type=float,
        metavar="M/S",
        help="body speed v [m/s]: sets the period from the stride, T = S/(β·v)",
    )
    group.add_argument(
        "--samples",
        type=bounded_int(*SAMPLES_RANGE),
        metavar="N",
        help=f"samples per period, {SAMPLES_RANGE[0]}..{SAMPLES_RANGE[1]} "
        f"(default {DEFAULT.samples})",
    )


def gait_from_args(args: argparse.Namespace, base: Gait) -> Gait:
    """The gait the options describe (validated), over ``base``: the gait the robot walks.

    ``base``: the ``--design`` file's ``[gait]`` over the robot's own default gait (a robot
    file's is sized to it: :attr:`~hexaleg.cli.inputs.Inputs.gait`).

    The options given override the table's keys, as they would the defaults: the table's
    ``speed`` has set its period, so ``--stride`` alone keeps that period.
    """
    if args.speed is not None and args.period is not None:
        raise UsageError("--speed sets the period: give --speed or --period, not both")
    changes = {
        name: getattr(args, name)
        for name in ("pattern", "period", "stride", "step_height", "heading", "samples")
        if getattr(args, name) is not None
    }
    gait = base.replace(**changes)
    return gait if args.speed is None else gait.with_speed(args.speed)
