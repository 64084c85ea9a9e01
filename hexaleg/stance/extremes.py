"""The result of a flexibility analysis: twelve extremes, six ranges (eq 28) and FB (eq 29)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from hexaleg._typing import FlexibilityMode
from hexaleg.design import HexapodDesign
from hexaleg.stance.constraints import AXES, TRANSLATIONS, Cause


class FlexibilityWarning(UserWarning):
    """An optimizer did not converge; the result keeps the best feasible value found."""


@dataclass(frozen=True)
class Extreme:
    """How far the body goes in one direction.

    Attributes:
        axis: One of :data:`AXES`.
        sign: +1 or −1.
        value: Signed displacement from the nominal pose at the extreme [m or rad].
        limited_by: The constraint that stops it.

    """

    axis: str
    sign: int
    value: float
    limited_by: Cause

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (value in m or rad)."""
        return {
            "axis": self.axis,
            "sign": self.sign,
            "value": self.value,
            "limited_by": self.limited_by.to_dict(),
            "description": str(self.limited_by),
        }


@dataclass(frozen=True)
class FlexibilityResult:
    """The twelve extremes, the six ranges (eq 28) and FB (eq 29) of one design.

    Attributes:
        design: The design analysed.
        legs: Stance legs.
        mode: ``"axis"`` (axis-locked) or ``"free"`` (free-coupled).
        extremes: One per direction of :data:`DIRECTIONS`.
        converged: False if an optimizer (free mode) failed somewhere.
        iterations: Optimizer iterations summed over the twelve directions (0 for axis mode).

    """

    design: HexapodDesign
    legs: tuple[str, ...]
    mode: FlexibilityMode
    extremes: tuple[Extreme, ...]
    converged: bool = True
    iterations: int = 0

    def extreme(self, axis: str, sign: int) -> Extreme:
        """The extreme in direction (axis, sign)."""
        return next(e for e in self.extremes if e.axis == axis and e.sign == sign)

    @property
    def ranges(self) -> dict[str, float]:
        """S_x, S_y, S_z [m] and φ_x, φ_y, φ_z [rad] (eq 28), keyed x y z roll pitch yaw."""
        return {a: self.extreme(a, 1).value - self.extreme(a, -1).value for a in AXES}

    @property
    def fb(self) -> float:
        """Flexibility index FB (eq 29), angles in degrees as the paper defines it [-]."""
        return flexibility_index(self.ranges, self.design.leg_length)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: fb, ranges, extremes and every design field used."""
        return {
            "fb": self.fb,
            "mode": self.mode,
            "stance": list(self.legs),
            "converged": self.converged,
            "ranges": self.ranges,
            "extremes": [e.to_dict() for e in self.extremes],
            "units": {"x y z": "m", "roll pitch yaw": "rad", "fb": "1"},
            "design": self.design.as_dict(),
        }


def flexibility_index(ranges: dict[str, float], leg_length: float) -> float:
    """FB = (1/6)·[(S_x+S_y+S_z)/(2L) + (φ_x+φ_y+φ_z)/180°] (eq 29).

    Args:
        ranges: S_x, S_y, S_z [m] and φ_x, φ_y, φ_z [rad], keyed as :data:`AXES`.
        leg_length: L = l1 + l2 + l3 [m].

    """
    translation = sum(ranges[a] for a in TRANSLATIONS) / (2 * leg_length)
    rotation = sum(math.degrees(ranges[a]) for a in AXES[3:]) / 180.0
    return (translation + rotation) / 6.0
