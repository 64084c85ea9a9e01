"""Joint-limit sets of the paper, each named.

A :class:`JointLimits` holds one closed interval per joint of a leg
(θ1 root, θ2 hip, θ3 knee) [rad], and optionally the coupled knee bound of
the paper's *improved workspace* (Table 4): θ3 ≥ −θ2 − π/2, i.e. the tibia
never tilts past pointing straight down.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._checks import require_finite, require_numbers
from hexaleg.exceptions import ParameterError

JOINT_NAMES: tuple[str, str, str] = ("theta1", "theta2", "theta3")
"""Joint-angle names in leg order: root (θ1), hip (θ2), knee (θ3)."""

BOUNDS = ("lower", "upper")
"""The two ends of a joint interval."""

LEG_JOINTS: tuple[str, str, str] = ("root", "hip", "knee")
"""Joint names of a leg, in the order of the paper's θ1, θ2, θ3."""


@dataclass(frozen=True)
class JointLimits:
    """Closed joint-angle intervals of one leg.

    Attributes:
        theta1: Root-joint interval (lower, upper) [rad].
        theta2: Hip-joint interval (lower, upper) [rad].
        theta3: Knee-joint interval (lower, upper) [rad].
        coupled_knee: If true, the knee also obeys θ3 ≥ −θ2 − π/2 (Table 4);
            ``theta3[0]`` is then the loosest knee bound over the hip range.
        name: Short label used in reports and error messages.

    """

    theta1: tuple[float, float]
    theta2: tuple[float, float]
    theta3: tuple[float, float]
    coupled_knee: bool = False
    name: str = "custom"

    def __post_init__(self) -> None:
        if not isinstance(self.name, str):
            raise ParameterError("JointLimits.name", self.name, "must be a string")
        if not isinstance(self.coupled_knee, bool):
            raise ParameterError(f"{self.name}.coupled_knee", self.coupled_knee, "true or false")
        for joint in JOINT_NAMES:
            field = f"{self.name}.{joint}"
            bounds = require_numbers(field, getattr(self, joint), BOUNDS, "angles [rad]")
            try:
                lower, upper = (require_finite(field, bound) for bound in bounds)
            except ParameterError:
                raise ParameterError(field, bounds, "bounds must be finite [rad]") from None
            if not lower < upper:
                raise ParameterError(field, bounds, "lower bound must be < upper bound [rad]")
            if not (-math.pi <= lower and upper <= math.pi):
                raise ParameterError(field, bounds, "bounds must lie in [-π, π] [rad]")
            object.__setattr__(self, joint, (lower, upper))

    def as_dict(self) -> dict[str, Any]:
        """The limits as plain JSON-ready values [rad]."""
        bounds = {joint: list(getattr(self, joint)) for joint in JOINT_NAMES}
        return {**bounds, "coupled_knee": self.coupled_knee, "name": self.name}

    @property
    def lower(self) -> npt.NDArray[np.float64]:
        """Lower bounds (θ1, θ2, θ3) [rad]; the knee's is the loosest one if coupled."""
        return np.array([self.theta1[0], self.theta2[0], self.theta3[0]])

    @property
    def upper(self) -> npt.NDArray[np.float64]:
        """Upper bounds (θ1, θ2, θ3) [rad]."""
        return np.array([self.theta1[1], self.theta2[1], self.theta3[1]])

    def knee_lower(self, theta2: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Knee lower bound at hip angle(s) ``theta2`` [rad], the coupling included."""
        theta2 = np.asarray(theta2, dtype=float)
        if self.coupled_knee:
            return np.maximum(self.theta3[0], -theta2 - math.pi / 2)
        return np.full_like(theta2, self.theta3[0])

    def contains(self, theta: npt.ArrayLike, tol: float = 0.0) -> npt.NDArray[np.bool_]:
        """Whether joint angles ``theta`` (..., 3) [rad] lie within the limits (± tol)."""
        theta = np.asarray(theta, dtype=float)
        inside = np.all((theta >= self.lower - tol) & (theta <= self.upper + tol), axis=-1)
        if self.coupled_knee:
            inside &= theta[..., 2] >= self.knee_lower(theta[..., 1]) - tol
        return inside

    def envelope(self, other: JointLimits) -> JointLimits:
        """Smallest rectangular limit set containing both ``self`` and ``other``."""
        lower = np.minimum(self.lower, other.lower)
        upper = np.maximum(self.upper, other.upper)
        t1, t2, t3 = ((float(lo), float(hi)) for lo, hi in zip(lower, upper, strict=True))
        return JointLimits(t1, t2, t3, name=f"{self.name}+{other.name}")


WORKSPACE_LIMITS = JointLimits(
    theta1=(-math.pi / 4, math.pi / 4),
    theta2=(-math.pi / 3, math.pi / 3),
    theta3=(-3 * math.pi / 4, 0.0),
    name="workspace_limits",
)
"""Table 2 (and Table 3 for θ2, θ3): the leg's working range."""

IMPROVED_LIMITS = JointLimits(
    theta1=(-math.pi / 4, math.pi / 4),
    theta2=(-math.pi / 3, math.pi / 3),
    theta3=(-math.pi / 3 - math.pi / 2, 0.0),
    coupled_knee=True,
    name="improved_limits",
)
"""Table 4: θ2 ∈ [−π/3, π/3], θ3 ∈ [−θ2 − π/2, 0] (coupled knee bound)."""

MANIPULABILITY_LIMITS = JointLimits(
    theta1=(-math.pi / 4, math.pi / 4),
    theta2=(-math.pi / 3, math.pi / 3),
    theta3=(-3 * math.pi / 4, -math.pi / 12),
    name="manipulability_limits",
)
"""Eq 26: θ2 ∈ [−60°, 60°], θ3 ∈ [−135°, −15°] (θ1 does not affect w)."""

STANCE_LIMITS = JointLimits(
    theta1=(-math.pi / 4, math.pi / 4),
    theta2=(-math.pi / 6, math.pi / 6),
    theta3=(-3 * math.pi / 4, -math.pi / 12),
    name="stance_limits",
)
"""The paper's ADAMS study (§6): limits that stop the body's motion in stance."""
