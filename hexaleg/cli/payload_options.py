"""The payload, feet and margin options of the commands that load the robot (loads, gait…)."""

from __future__ import annotations

import argparse

from hexaleg._checks import require_in_range
from hexaleg._typing import Distribution, choices
from hexaleg.evaluation.requirement_specs import MOTOR_SAFETY_FACTOR
from hexaleg.evaluation.requirements import Requirements
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


def add_safety_factor_option(parser: argparse.ArgumentParser) -> None:
    """``--motor-safety-factor F``: peak torques and speeds within rating / F (loads, gait).

    The requirement's one declaration (:data:`~hexaleg.evaluation.requirement_specs.
    MOTOR_SAFETY_FACTOR`): its name, range and words, as ``decide`` offers it.
    """
    spec = MOTOR_SAFETY_FACTOR
    parser.add_argument(
        spec.option,
        type=float,
        metavar=spec.metavar[0],
        help=f"{spec.help}, in [{spec.bounds[0]:g}, {spec.bounds[1]:g}]; default: the design "
        "file's [requirements] value, else 1 (the ratings as given)",
    )


def safety_factor_from_args(args: argparse.Namespace, written: Requirements | None = None) -> float:
    """``--motor-safety-factor`` checked, else the design file's requirement, else 1 [-]."""
    given = getattr(args, MOTOR_SAFETY_FACTOR.name, None)
    if given is None:
        return 1.0 if written is None else written.motor_safety_factor
    spec = MOTOR_SAFETY_FACTOR
    return require_in_range(spec.option, given, *spec.bounds, spec.unit)


def rated_text(rating: float, safety_factor: float, unit: str) -> str:
    """A rating as a table prints it: ``150 N·m``, or ``150 / 1.5 = 100 N·m`` with F ≠ 1."""
    if safety_factor == 1:
        return f"{rating:g} {unit}"
    return f"{rating:g} / {safety_factor:g} = {rating / safety_factor:.4g} {unit}"
