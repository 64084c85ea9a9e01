"""The payload and feet options of the commands that load the robot: loads, gait, simulate."""

from __future__ import annotations

import argparse

from hexaleg._checks import require_in_range
from hexaleg._typing import Distribution, choices
from hexaleg.statics.forces import DEFAULT_FRICTION, FRICTION_RANGE, PAYLOAD_REACH, Payload


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
