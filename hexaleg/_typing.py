"""Types shared across hexaleg: arrays, and the modes and names that select behaviour.

Each mode is declared once here as a ``Literal``; :func:`require_choice` is the one
place that checks a value against it and names the valid choices in the error.
"""

from __future__ import annotations

from typing import Any, Literal, get_args

import numpy as np
import numpy.typing as npt

from hexaleg.exceptions import ParameterError

ArrayF = npt.NDArray[np.float64]
"""A float64 NumPy array; shapes and units are given where it is used."""

Lengths = tuple[float, float, float]
"""Segment lengths (l1, l2, l3) [m]."""

FlexibilityMode = Literal["axis", "free"]
"""Axis-locked (one body coordinate moves, the other five held) or free-coupled."""

StanceSet = Literal["all", "tripod"]
"""Named stance-leg sets: all six legs, or the first tripod (lf, rm, lr)."""

Distribution = Literal["min-norm", "min-torque"]
"""How the stance feet share the load: least squares of the forces, or of the torques
relative to their ratings under friction and unilateral contact."""

CauseKind = Literal[
    "joint",
    "reach",
    "ground",
    "collision",
    "range",
    "torque",
    "speed",
    "continuous_torque",
    "voltage",
    "tip",
    "slide",
    "stability",
    "zmp",
    "search limit",
    "strength",
    "deflection",
]
"""What binds: a joint limit, a foothold out of reach, the ground, two of the robot's own
parts touching, nothing within the searched range (extremes, gaits); a joint's torque or
speed at its rating (payload capacity, gait speed); tipping over or sliding (slopes); the
centre of mass leaving the support polygon (payload capacity), or a gait's zero-moment point
leaving it (walking payload capacity); the search's own limit; a leg tube at its strength
or a foot at its deflection limit (the legs' structure)."""

Controller = Literal["servo", "torque"]
"""How a simulated robot's joints follow a plan: stiff position servos (hobby servos), or
torque control (the plan's torques, a low-gain PD correcting drift)."""

GaitPattern = Literal["tripod", "tetrapod", "wave"]
"""Which legs swing together: three (duty factor 1/2), two (2/3) or one at a time (5/6)."""


def choices(literal: Any) -> tuple[str, ...]:
    """The values a ``Literal`` type allows, in declaration order."""
    return tuple(get_args(literal))


def require_choice(name: str, value: Any, literal: Any) -> Any:
    """``value`` if ``literal`` allows it; else a :class:`ParameterError` naming the choices."""
    allowed = choices(literal)
    if not any(isinstance(value, type(a)) and value == a for a in allowed):  # arrays: no truth
        raise ParameterError(name, value, f"use one of {', '.join(repr(a) for a in allowed)}")
    return value
