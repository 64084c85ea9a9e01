"""The gait's options, over the gait the robot walks, and the ground it walks on: gait, simulate."""

from __future__ import annotations

import argparse
import math

from hexaleg._checks import require_in_range
from hexaleg._typing import GaitPattern, choices
from hexaleg.cli.options import UsageError, bounded_int
from hexaleg.gait.spec import SAMPLES_RANGE, Gait
from hexaleg.statics.ground import HEADING_RANGE, MAX_SLOPE, Ground

DEFAULT = Gait()
"""The defaults each option's help names (hexaleg's template's gait)."""

SLOPE_LIMIT = math.degrees(MAX_SLOPE)
"""The steepest ``--slope-deg`` either way [°]: 60."""


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


def add_ground_options(parser: argparse.ArgumentParser) -> None:
    """``--slope-deg`` and ``--slope-heading``: the plane the gait is walked on."""
    group = parser.add_argument_group("ground (default level; --friction is its μ)")
    group.add_argument(
        "--slope-deg",
        type=float,
        default=0.0,
        metavar="DEG",
        help=f"walk on a plane inclined DEG in [-{SLOPE_LIMIT:g}, {SLOPE_LIMIT:g}] [°]: "
        "positive rises along --slope-heading (uphill), negative falls (downhill)",
    )
    group.add_argument(
        "--slope-heading",
        type=float,
        metavar="RAD",
        help="direction in the body frame along which the ground rises [rad] (default: the "
        "gait's heading, so the walk is up or down the fall line; heading ± π/2 walks across)",
    )


def ground_from_args(args: argparse.Namespace) -> Ground:
    """The ground ``--slope-deg``, ``--slope-heading`` and ``--friction`` describe (checked)."""
    slope = require_in_range("--slope-deg", args.slope_deg, -SLOPE_LIMIT, SLOPE_LIMIT, "°")
    if args.slope_heading is not None:
        require_in_range("--slope-heading", args.slope_heading, *HEADING_RANGE, "rad")
    return Ground(math.radians(slope), args.slope_heading, args.friction)
