"""Joints over their ratings: where a computed torque or speed exceeds what the motor is rated for.

Every command that computes or measures torques (``loads``, ``gait``, ``simulate``) flags
each joint whose peak |τ| [N·m] (or, in a gait, |q̇| [rad/s]) exceeds the design's
``rated_torques`` (or ``rated_speeds``), naming the leg, the joint, the peak and where
it occurs.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

from hexaleg._checks import require_in_range
from hexaleg._typing import ArrayF
from hexaleg.limits import LEG_JOINTS

SAFETY_FACTOR_RANGE = (1.0, 100.0)
"""Safety factors F [-] the analyses take: 1 (the ratings as given) up to 100."""


def check_safety_factor(safety_factor: float) -> float:
    """``safety_factor`` as a float if it lies in :data:`SAFETY_FACTOR_RANGE`; else an error."""
    return require_in_range("safety_factor", safety_factor, *SAFETY_FACTOR_RANGE, "-")


Quantity = Literal["torque", "speed", "peak_torque", "continuous_torque", "voltage"]
"""What is compared with its rating: joint torque [N·m] or joint speed [rad/s]; with
actuators (:mod:`hexaleg.electrical`) also the peak torque, the RMS torque against the
continuous torque [N·m] and the voltage the motor needs against its supply [V]."""

UNITS: dict[str, str] = {
    "torque": "N·m",
    "speed": "rad/s",
    "peak_torque": "N·m",
    "continuous_torque": "N·m",
    "voltage": "V",
}

LABELS: dict[str, str] = {
    "torque": "torque",
    "speed": "speed",
    "peak_torque": "peak torque",
    "continuous_torque": "RMS torque",
    "voltage": "voltage needed",
}
"""How each quantity is named in a sentence."""

DERATED: tuple[Quantity, ...] = ("torque", "speed", "peak_torque")
"""The quantities a safety factor F divides the rating of: peak torque and speed (the RMS
torque and the voltage are held to their ratings as given)."""


@dataclass(frozen=True)
class OverRating:
    """One joint whose torque or speed exceeds its rating.

    Attributes:
        leg: Leg name.
        joint: ``"root"``, ``"hip"`` or ``"knee"``.
        quantity: ``"torque"`` [N·m] or ``"speed"`` [rad/s]; with actuators also
            ``"peak_torque"``, ``"continuous_torque"`` [N·m] or ``"voltage"`` [V].
        peak: The largest |τ| or |q̇| of that joint [N·m or rad/s]; for
            ``"continuous_torque"`` its RMS τ, for ``"voltage"`` the largest voltage needed.
        rated: What it is held to [N·m, rad/s or V]: its rating, divided by the safety
            factor for a peak torque or a speed.
        at: Where the peak occurs: a pose (``"nominal"``, ``"x+"``) or a time (``"t = 0.42 s"``).
        safety_factor: The safety factor F the rating was divided by [-] (1: as given).

    """

    leg: str
    joint: str
    quantity: Quantity
    peak: float
    rated: float
    at: str
    safety_factor: float = 1.0

    def __str__(self) -> str:
        unit, label = UNITS[self.quantity], LABELS[self.quantity]
        peak = f"{self.peak:.2f} {unit}" if math.isfinite(self.peak) else "without bound"
        held = f"its rating {self.rated:g} {unit}"
        if self.safety_factor != 1.0:
            rating, factor = self.rated * self.safety_factor, self.safety_factor
            held = f"its rating {rating:g} {unit} / F {factor:g} = {self.rated:.4g} {unit}"
        return f"{self.leg} {self.joint} {label} {peak} over {held} ({self.at})"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (N·m, rad/s or V)."""
        return {
            "leg": self.leg,
            "joint": self.joint,
            "quantity": self.quantity,
            "peak": self.peak,
            "rated": self.rated,
            "at": self.at,
            "safety_factor": self.safety_factor,
            "description": str(self),
        }


def furthest_first(flags: Sequence[OverRating]) -> list[OverRating]:
    """Joints over their ratings, the furthest over (peak / rating) first."""
    return sorted(flags, key=lambda flag: flag.peak / flag.rated, reverse=True)


def at_times(times: npt.ArrayLike) -> list[str]:
    """Each time [s] as a place where a peak occurs: ``"t = 0.420 s"``."""
    return [f"t = {t:.3f} s" for t in np.asarray(times, dtype=float)]


def over_rating(
    legs: Sequence[str],
    values: npt.ArrayLike,
    rated: npt.ArrayLike | None,
    places: Sequence[str],
    quantity: Quantity = "torque",
    safety_factor: float = 1.0,
) -> tuple[OverRating, ...]:
    """Each (leg, joint) whose largest |value| over ``places`` exceeds its rating / F.

    Args:
        legs: Leg names (N,).
        values: Torques or speeds (K, N, 3) at K places [N·m or rad/s].
        rated: Ratings (root, hip, knee) (3,) [N·m or rad/s]; ``None``: not given, so
            none is known to be exceeded (the results that need them say so).
        places: What each of the K places is called (``"nominal"``, ``"t = 0.42 s"``).
        quantity: ``"torque"`` or ``"speed"``.
        safety_factor: F [-]: each rating is held at rating / F.

    Returns:
        One entry per joint over its rating, in leg then joint order.

    """
    if rated is None:
        return ()
    magnitude = np.abs(np.asarray(values, dtype=float))  # (K, N, 3)
    worst = magnitude.argmax(axis=0)  # (N, 3)
    where = [[places[k] for k in row] for row in worst]
    return over_rating_at(legs, magnitude.max(axis=0), rated, where, quantity, safety_factor)


def over_rating_at(
    legs: Sequence[str],
    peaks: npt.ArrayLike,
    rated: npt.ArrayLike | None,
    where: Sequence[Sequence[str]],
    quantity: Quantity = "torque",
    safety_factor: float = 1.0,
) -> tuple[OverRating, ...]:
    """Each (leg, joint) whose peak |value| exceeds its rating / F, the peaks already found.

    Args:
        legs: Leg names (N,).
        peaks: Each joint's largest |value| (N, 3) [N·m or rad/s].
        rated: Ratings (root, hip, knee) (3,) [N·m or rad/s]; ``None``: not given.
        where: Where each joint's peak occurs (N lists of 3).
        quantity: ``"torque"`` or ``"speed"``.
        safety_factor: F [-]: each rating is held at rating / F.

    """
    if rated is None:
        return ()
    peaks = np.asarray(peaks, dtype=float)
    held = np.asarray(rated, dtype=float) / safety_factor
    return tuple(
        OverRating(
            leg, joint, quantity, float(peaks[i, j]), float(held[j]), where[i][j], safety_factor
        )
        for i, leg in enumerate(legs)
        for j, joint in enumerate(LEG_JOINTS)
        if peaks[i, j] > held[j]
    )


def rating_use(values: npt.ArrayLike, rated: npt.ArrayLike | None) -> ArrayF:
    """|value| / rating (..., 3) [-] of each joint (root, hip, knee), for colouring.

    Without ratings (``None``: not given) each joint type's |value| over its own largest:
    the colours then say where the torque peaks, not how near a rating it is.
    """
    magnitude = np.abs(np.asarray(values, dtype=float))
    if rated is None:
        peaks = magnitude.reshape(-1, 3).max(axis=0)
        return magnitude / np.where(peaks > 0, peaks, 1.0)
    return magnitude / np.asarray(rated, dtype=float)
