"""Whether a gait period can be walked: every constraint at every sample, and the first broken.

At each sample and for each leg:

- the foot within the leg's reach, |l2 − l3| ≤ r ≤ l2 + l3 (r hip to foot);
- every joint within the design's URDF limits (swinging legs) or within the stance limits
  of §6 (standing legs, which are tighter: the URDF's are the envelope of every limit set);
  an imported robot's legs within the file's limits, standing or swinging (as its
  flexibility holds them);
- the knee above the ground, hence the whole tibia (its other end, the foot, stands on the
  ground or swings above it: H·64·s³(1 − s)³ ≥ 0).

A constraint is broken when its margin is below −:data:`TOLERANCE`. The violations name
each broken constraint once, at the first sample it breaks, earliest first.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.cause import Cause
from hexaleg.gait.jacobian import LegPartials
from hexaleg.gait.trajectory import LegFrames, knee_heights
from hexaleg.leg_geometry import leg_parameters
from hexaleg.limits import LEG_JOINTS, JointLimits
from hexaleg.robot.model import HexapodModel

TOLERANCE = 1e-12
"""How far past a bound a margin may go before the constraint counts as broken [m or rad]."""

COLUMNS = 9
"""Margins per leg: reach outer and inner, three joints' lower and upper, the knee's height."""


def leg_causes(leg: str) -> list[Cause]:
    """The constraints of one leg, in the column order of :func:`gait_margins`."""
    causes = [Cause("reach", leg, bound="outer"), Cause("reach", leg, bound="inner")]
    causes += [Cause("joint", leg, j, bound) for j in LEG_JOINTS for bound in ("lower", "upper")]
    return [*causes, Cause("ground", leg)]


@dataclass(frozen=True)
class JointBounds:
    """The joint limits a gait is held to (6, 3) [rad], ``leg_names`` order.

    Attributes:
        urdf_lower: The URDF's lower limits, read from the model (on hexaleg's θ).
        urdf_upper: The URDF's upper limits.
        stance: The design's stance limits (§6) that hold the standing legs; ``None`` for
            an imported robot, whose standing legs keep the file's limits.

    """

    urdf_lower: ArrayF
    urdf_upper: ArrayF
    stance: JointLimits | None

    @classmethod
    def from_model(cls, model: HexapodModel) -> JointBounds:
        """The model's URDF limits and the limits that hold its standing legs (if others)."""
        limits = [model.joint_limits(leg) for leg in model.leg_names]
        return cls(
            urdf_lower=np.array([lower for lower, _ in limits]),
            urdf_upper=np.array([upper for _, upper in limits]),
            stance=model.stance_limits,
        )

    def bounds(
        self, stance: npt.NDArray[np.bool_], theta: ArrayF
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """The (lower, upper) limits (..., N, 6, 3) [rad] at angles θ (..., N, 6, 3) [rad].

        Standing legs (``stance`` (N, 6)) get the stance limits, their knee's lower bound
        coupled to the hip where those are.
        """
        if self.stance is None:
            return self.urdf_lower, self.urdf_upper
        standing = stance[..., None]
        lower = np.where(standing, self.stance.lower, self.urdf_lower)
        upper = np.where(standing, self.stance.upper, self.urdf_upper)
        if self.stance.coupled_knee:
            coupled = self.stance.knee_lower(theta[..., 1])
            lower = np.broadcast_to(lower, theta.shape).copy()
            lower[..., 2] = np.where(stance, coupled, lower[..., 2])
        return lower, upper


def gait_margins(
    frames: LegFrames,
    bounds: JointBounds,
    stance: npt.NDArray[np.bool_],
    theta: ArrayF,
    reach: ArrayF,
    partials: LegPartials | None = None,
) -> ArrayF:
    """Every constraint's margin (..., N, 6, :data:`COLUMNS`): ≥ 0 holds [m or rad].

    Args:
        frames: The legs.
        bounds: Joint limits.
        stance: Whether each leg stands at each sample (N, 6).
        theta: Joint angles (..., N, 6, 3) [rad].
        reach: Hip-to-foot distances (..., N, 6) [m].
        partials: The angles' partials (:func:`~hexaleg.gait.jacobian.leg_partials`), if
            known (their trigonometry serves the knees' heights).

    """
    _, l2, l3, _, _ = leg_parameters(frames.parameters)
    lower, upper = bounds.bounds(stance, theta)
    joints = np.stack((theta - lower, upper - theta), axis=-1).reshape(*theta.shape[:-1], 6)
    return np.concatenate(
        (
            (l2 + l3 - reach)[..., None],
            (reach - abs(l2 - l3))[..., None],
            joints,
            knee_heights(frames, theta, partials)[..., None],
        ),
        axis=-1,
    )


def feasible(margins: ArrayF) -> npt.NDArray[np.bool_]:
    """Whether every margin holds, over the last three axes (sample, leg, constraint)."""
    return np.asarray((margins >= -TOLERANCE).all(axis=(-3, -2, -1)))


@dataclass(frozen=True)
class Violation:
    """A constraint that breaks during the period.

    Attributes:
        time: When it first breaks [s], 0 ≤ t < T.
        cause: Which constraint (its leg, joint and bound).

    """

    time: float
    cause: Cause

    def __str__(self) -> str:
        return f"t = {self.time:.3f} s: {self.cause}"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: ``time`` [s] and the cause's fields."""
        return {"time": self.time, **self.cause.to_dict()}


def violations(margins: ArrayF, legs: Sequence[str], times: ArrayF) -> tuple[Violation, ...]:
    """Each broken constraint at the first sample it breaks, earliest first (then leg order).

    Args:
        margins: One period's margins (N, 6, :data:`COLUMNS`).
        legs: Leg names (6,).
        times: Sample times (N,) [s].

    """
    broken = margins < -TOLERANCE
    flat = broken.reshape(len(times), -1)
    ever = flat.any(axis=0)
    if not ever.any():
        return ()
    first = flat.argmax(axis=0)
    causes = [cause for leg in legs for cause in leg_causes(leg)]
    order = sorted(np.flatnonzero(ever), key=lambda c: (first[c], c))
    return tuple(Violation(float(times[first[c]]), causes[c]) for c in order)
