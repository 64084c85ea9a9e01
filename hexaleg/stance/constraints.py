"""The constraints that hold the body in stance, and how far each one is from breaking.

With the feet pinned to their footholds, a body pose is feasible while every stance
foot is within its leg's reach, every joint within its stance limits, and the body
above the ground. :func:`stance_margins` gives each constraint's margin (≥ 0 holds)
for many poses at once, by the closed-form knee-down IK (eq 8–9); :class:`Cause`
names a constraint; :func:`direction_poses` moves the body along one coordinate.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF, CauseKind
from hexaleg.kinematics import leg_solution
from hexaleg.robot.model import LEG_JOINTS
from hexaleg.stance.geometry import StanceGeometry

AXES: tuple[str, ...] = ("x", "y", "z", "roll", "pitch", "yaw")
"""Body coordinates, translations [m] then rotations about the world axes [rad]."""
TRANSLATIONS = AXES[:3]
DIRECTIONS: tuple[tuple[str, int], ...] = tuple((a, s) for a in AXES for s in (1, -1))
"""The twelve (axis, sign) directions of the flexibility study."""


@dataclass(frozen=True)
class Cause:
    """The constraint that stops the body.

    Attributes:
        kind: ``"joint"`` (a joint limit), ``"reach"`` (foothold out of the leg's
            reach), ``"ground"`` (the body touches the ground) or ``"range"`` (nothing
            broke within the searched range).
        leg: Leg name, for joint and reach causes.
        joint: ``"root"``, ``"hip"`` or ``"knee"``, for joint causes.
        bound: ``"lower"``/``"upper"`` for joints, ``"outer"``/``"inner"`` for reach.

    """

    kind: CauseKind
    leg: str | None = None
    joint: str | None = None
    bound: str | None = None

    def __str__(self) -> str:
        if self.kind == "joint":
            return f"{self.leg} {self.joint} joint at its {self.bound} limit"
        if self.kind == "reach":
            edge = "too far" if self.bound == "outer" else "too close"
            return f"{self.leg} foothold out of reach ({edge})"
        if self.kind == "ground":
            return "body touches the ground"
        return "end of the searched range"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {"kind": self.kind, "leg": self.leg, "joint": self.joint, "bound": self.bound}


def direction_poses(
    geometry: StanceGeometry, axis_index: npt.ArrayLike, value: npt.ArrayLike
) -> tuple[ArrayF, ArrayF]:
    """Body rotations (..., 3, 3) and translations (..., 3) displaced along one coordinate.

    Args:
        geometry: Provides the nominal pose.
        axis_index: Index into :data:`AXES` per sample.
        value: Signed displacement per sample [m or rad].

    """
    axis_index = np.asarray(axis_index)
    value = np.asarray(value, dtype=float)
    axis_index, value = np.broadcast_arrays(axis_index, value)
    translation = np.zeros((*value.shape, 3))
    translation[..., 2] = geometry.nominal_height
    is_translation = axis_index < 3
    for k in range(3):
        translation[..., k] += np.where(is_translation & (axis_index == k), value, 0.0)
    rotation = np.broadcast_to(np.eye(3), (*value.shape, 3, 3)).copy()
    c, s = np.cos(value), np.sin(value)
    for k, (i, j) in enumerate(((1, 2), (2, 0), (0, 1))):  # about x, y, z
        sel = axis_index == 3 + k
        rotation[sel, i, i] = c[sel]
        rotation[sel, j, j] = c[sel]
        rotation[sel, i, j] = -s[sel]
        rotation[sel, j, i] = s[sel]
    return rotation, translation


def constraint_labels(legs: Sequence[str]) -> list[Cause]:
    """Causes in the column order of :func:`stance_margins`."""
    labels = []
    for leg in legs:
        labels += [Cause("reach", leg, bound="outer"), Cause("reach", leg, bound="inner")]
    for leg in legs:
        for joint in LEG_JOINTS:
            labels += [Cause("joint", leg, joint, "lower"), Cause("joint", leg, joint, "upper")]
    return [*labels, Cause("ground")]


def stance_margins(geometry: StanceGeometry, rotation: ArrayF, translation: ArrayF) -> ArrayF:
    """Every constraint's margin (..., 8N + 1) for body poses: ≥ 0 feasible, < 0 broken.

    Columns (see :func:`constraint_labels`): per leg the outer and inner reach [m];
    per leg and joint the lower and upper limit [rad]; last the lowest body corner's
    height above the ground [m].
    """
    _, l2, l3 = geometry.lengths
    targets = geometry.feet_in_roots(rotation, translation)  # (..., N, 3)
    theta, r = leg_solution(geometry.lengths, targets)  # knee-down IK (..., N, 3), (..., N)
    reach = np.stack([l2 + l3 - r, r - abs(l2 - l3)], axis=-1)  # (..., N, 2)
    limits = geometry.limits
    lower = np.broadcast_to(limits.lower, theta.shape).copy()
    lower[..., 2] = limits.knee_lower(theta[..., 1])
    joints = np.stack([theta - lower, limits.upper - theta], axis=-1)  # (..., N, 3, 2)
    ground = geometry.lowest_corner_height(rotation, translation)
    shape = theta.shape[:-2]
    return np.concatenate(
        [reach.reshape(*shape, -1), joints.reshape(*shape, -1), ground[..., None]], axis=-1
    )
