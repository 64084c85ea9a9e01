"""The ground a robot stands or walks on: a plane inclined α, rising along φ, with friction μ.

The body stays parallel to the plane and the feet stand on it, so every analysis works in
the plane's own frame (z along its normal, the ground at z = 0) and only gravity turns:
in the body frame it is g·(−sin α cos φ, −sin α sin φ, −cos α)
(:func:`~hexaleg.gravity.slope_gravity`). A positive α rises along φ; a negative one
falls along it. φ defaults to the direction walked, so a positive slope is walked uphill,
a negative one downhill, and φ = ψ ± π/2 walks across it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from hexaleg._checks import require_in_range
from hexaleg._typing import ArrayF
from hexaleg.gravity import GRAVITY, slope_gravity
from hexaleg.statics.forces import DEFAULT_FRICTION, check_friction

__all__ = ["LEVEL", "MAX_SLOPE", "MAX_SLOPE_DEG", "Ground"]

MAX_SLOPE_DEG = 60.0
"""Steepest slope |α| walked [°], as options in degrees state it."""
MAX_SLOPE = math.radians(MAX_SLOPE_DEG)
"""Steepest slope |α| walked [rad]. Standing on it at all, with the weight shared evenly,
already needs μ ≥ tan 60° ≈ 1.73."""

HEADING_RANGE = (-2 * math.pi, 2 * math.pi)
"""Directions φ accepted [rad] (any turn, either way)."""


@dataclass(frozen=True)
class Ground:
    """A plane inclined ``slope`` rising along ``heading``, with friction ``friction``.

    Attributes:
        slope: Inclination α [rad] in [−60°, 60°]: positive rises along ``heading``.
        heading: Direction φ in the body frame along which the ground rises [rad];
            ``None``: the direction walked (the gait's heading ψ), or straight ahead
            standing.
        friction: Friction coefficient μ between the feet and the ground [-].

    """

    slope: float = 0.0
    heading: float | None = None
    friction: float = DEFAULT_FRICTION

    def __post_init__(self) -> None:
        slope = require_in_range("slope", self.slope, -MAX_SLOPE, MAX_SLOPE, "rad")
        object.__setattr__(self, "slope", slope)
        if self.heading is not None:
            heading = require_in_range("heading", self.heading, *HEADING_RANGE, "rad")
            object.__setattr__(self, "heading", heading)
        object.__setattr__(self, "friction", check_friction(self.friction))

    @property
    def level(self) -> bool:
        """Whether the ground is level (α = 0)."""
        return self.slope == 0.0

    def uphill(self, walking: float = 0.0) -> float:
        """φ [rad]: :attr:`heading`, or the direction walked ψ [rad] when it is unset."""
        return walking if self.heading is None else self.heading

    def gravity(self, walking: float = 0.0, g: float = GRAVITY) -> ArrayF:
        """Gravity in the body (plane) frame [m/s²], walking along ψ = ``walking`` [rad]."""
        return slope_gravity(self.slope, self.uphill(walking), g)

    def describe(self, walking: float = 0.0) -> str:
        """The ground in words: ``level ground`` or ``10° slope, uphill (rises along 0 rad)``."""
        if self.level:
            return f"level ground, μ = {self.friction:g}"
        return (
            f"{math.degrees(self.slope):g}° slope rising along {self.uphill(walking):.4g} rad, "
            f"walked {self.way(walking)}, μ = {self.friction:g}"
        )

    def way(self, walking: float = 0.0) -> str:
        """How the direction walked ψ = ``walking`` [rad] meets the slope, in words.

        ``uphill``, ``downhill``, ``across``, or ``+30° off the fall line``; ``level`` on
        level ground.
        """
        if self.level:
            return "level"
        off = math.degrees(math.remainder(self.uphill(walking) - walking, 2 * math.pi))  # [°]
        if abs(off) < 0.5:
            return "uphill" if self.slope > 0 else "downhill"
        if abs(abs(off) - 180) < 0.5:
            return "downhill" if self.slope > 0 else "uphill"
        if abs(abs(off) - 90) < 0.5:
            return "across"
        return f"{off:+.0f}° off the fall line"

    def to_dict(self, walking: float = 0.0) -> dict[str, Any]:
        """JSON-ready: ``slope`` [rad], ``slope_deg`` [°], ``heading`` (φ resolved) [rad], μ."""
        return {
            "slope": self.slope,
            "slope_deg": math.degrees(self.slope),
            "heading": self.uphill(walking),
            "friction": self.friction,
        }


LEVEL = Ground()
"""Level ground with the default friction coefficient."""
