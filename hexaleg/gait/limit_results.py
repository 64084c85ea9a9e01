"""The max stride and max speed of a gait, as results, and the precision they promise."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from hexaleg.cause import Cause

__all__ = ["SPEED_TOLERANCE", "STRIDE_TOLERANCE", "SpeedLimit", "StrideLimit"]

STRIDE_TOLERANCE = 1e-9
"""Width of the max stride's final bracket [m]: the value is feasible, value + this is not."""
SPEED_TOLERANCE = 1e-6
"""Relative width of the final bracket of a min-torque max speed, on 1/T² [-]."""


@dataclass(frozen=True)
class StrideLimit:
    """The largest feasible stride.

    Attributes:
        value: S_max [m] (0 if even a stride of :data:`STRIDE_TOLERANCE` breaks a constraint).
        limited_by: The constraint that breaks just beyond it.

    """

    value: float
    limited_by: Cause

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: ``value`` [m] and what limits it."""
        return {"value": self.value, "limited_by": self.limited_by.to_dict()}


@dataclass(frozen=True)
class SpeedLimit:
    """The fastest the design walks the gait's pattern within its ratings.

    Attributes:
        value: v_max [m/s] (0 if no period works).
        stride: The stride it is reached at [m].
        period: The period it is reached at [s] (infinite if v_max = 0).
        limited_by: What binds there: a joint's torque or speed at its rating, or the
            constraint that makes the period infeasible.

    """

    value: float
    stride: float
    period: float
    limited_by: Cause

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: ``value`` [m/s] and what limits it."""
        return {"value": self.value, "limited_by": self.limited_by.to_dict()}
