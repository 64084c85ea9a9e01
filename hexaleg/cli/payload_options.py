"""The payload, feet and margin options of the commands that load the robot (loads, gait…)."""

from __future__ import annotations

import argparse

from hexaleg._checks import require_in_range
from hexaleg._typing import Distribution, choices
from hexaleg.statics.forces import DEFAULT_FRICTION, FRICTION_RANGE, PAYLOAD_REACH, Payload
from hexaleg.statics.ratings import SAFETY_FACTOR_RANGE


def add_payload_options(parser: argparse.ArgumentParser) -> None:
    """``--payload``, ``--payload-at``, ``--friction`` and ``--distribution`` (loads, gait)."""
    parser.add_argument(
        "--payload", type=float, default=0.0, metavar="KG", help="payload mass [kg] (default 0)"
    )
    parser.add_argument(
        "--payload-at",
        type=float,
        nargs=3,
        metavar=("X", "Y", "Z"),
        help=f"payload position in the body frame, each coordinate in [-{PAYLOAD_REACH:g}, "
        f"{PAYLOAD_REACH:g}] [m] (default: the centre of the top face)",
    )
    parser.add_argument(
        "--friction",
        type=float,
        default=DEFAULT_FRICTION,
        metavar="MU",
        help="friction coefficient between feet and ground, in [{:g}, {:g}] [-] ".format(
            *FRICTION_RANGE
        )
        + f"(default {DEFAULT_FRICTION})",
    )
    parser.add_argument(
        "--distribution",
        choices=choices(Distribution),
        default="min-norm",
        help="how the feet share the load: least forces (default) or least torque/rating",
    )


def payload_from_args(args: argparse.Namespace) -> Payload:
    """The payload ``--payload`` and ``--payload-at`` describe (validated)."""
    if args.payload_at is None:
        return Payload(args.payload)
    return Payload(args.payload, payload_at_from_args(args.payload_at))


def payload_at_from_args(values: list[float]) -> tuple[float, float, float]:
    """``--payload-at X Y Z`` checked: each coordinate within ±:data:`PAYLOAD_REACH` [m]."""
    reach = PAYLOAD_REACH
    x, y, z = (require_in_range("--payload-at", v, -reach, reach, "m") for v in values)
    return (x, y, z)


def add_safety_factor_option(parser: argparse.ArgumentParser) -> None:
    """``--safety-factor F``: peak torques and speeds held within rating / F (loads, gait)."""
    parser.add_argument(
        "--safety-factor",
        type=float,
        default=1.0,
        metavar="F",
        help="hold every peak joint torque and speed within its rating / F, in "
        "[{:g}, {:g}] [-] (default 1: the ratings as given)".format(*SAFETY_FACTOR_RANGE),
    )


def safety_factor_from_args(args: argparse.Namespace) -> float:
    """``--safety-factor`` checked: a number in :data:`SAFETY_FACTOR_RANGE` [-]."""
    return require_in_range("--safety-factor", args.safety_factor, *SAFETY_FACTOR_RANGE, "-")


def rated_text(rating: float, safety_factor: float, unit: str) -> str:
    """A rating as a table prints it: ``150 N·m``, or ``150 / 1.5 = 100 N·m`` with F ≠ 1."""
    if safety_factor == 1:
        return f"{rating:g} {unit}"
    return f"{rating:g} / {safety_factor:g} = {rating / safety_factor:.4g} {unit}"
