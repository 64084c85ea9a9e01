"""The constraints that hold the body in stance, and how far each one is from breaking.

With the feet pinned to their footholds, a body pose is feasible while every stance
foot is within its leg's reach, every joint within its stance limits, and the body
above the ground. :func:`stance_margins` gives each constraint's margin (≥ 0 holds)
for many poses at once, by the closed-form knee-down IK (eq 8–9); a :class:`~hexaleg.cause.Cause`
names a constraint; :func:`direction_poses` moves the body along one coordinate.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.cause import Cause
from hexaleg.robot.model import LEG_JOINTS
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.stance.margin_kernel import kernel_geometry, margins_of_poses, rotations_of

AXES: tuple[str, ...] = ("x", "y", "z", "roll", "pitch", "yaw")
"""Body coordinates, translations [m] then rotations about the world axes [rad]."""
TRANSLATIONS = AXES[:3]
DIRECTIONS: tuple[tuple[str, int], ...] = tuple((a, s) for a in AXES for s in (1, -1))
"""The twelve (axis, sign) directions of the flexibility study."""


def direction_label(axis: str, sign: int) -> str:
    """A direction's label: ``x+``, ``yaw-``."""
    return f"{axis}{'+' if sign > 0 else '-'}"


def rpy_rotation(rpy: npt.ArrayLike) -> ArrayF:
    """Rotations (..., 3, 3) from roll, pitch, yaw (..., 3) [rad], as Pinocchio's ``rpy``.

    R = Rz(yaw)·Ry(pitch)·Rx(roll): roll, pitch and yaw about the world x, y, z axes;
    computed by the compiled kernel's :func:`~.margin_kernel.rpy_matrix`.
    """
    rpy = np.asarray(rpy, dtype=float)
    flat = np.ascontiguousarray(rpy.reshape(-1, 3))
    return np.asarray(rotations_of(flat)).reshape(*rpy.shape[:-1], 3, 3)


def displacement_poses(
    geometry: StanceGeometry, displacement: npt.ArrayLike
) -> tuple[ArrayF, ArrayF]:
    """Body rotations (..., 3, 3) and translations (..., 3) displaced from the nominal stance.

    Args:
        geometry: Provides the nominal pose (level, at the nominal height).
        displacement: (..., 6) = x, y, z [m] added to the nominal position and roll,
            pitch, yaw [rad] (Pinocchio's ``rpy``, about the world axes), world frame.

    """
    displacement = np.asarray(displacement, dtype=float)
    translation = displacement[..., :3].copy()
    translation[..., 2] += geometry.nominal_height
    return rpy_rotation(displacement[..., 3:]), translation


def direction_poses(
    geometry: StanceGeometry, axis_index: npt.ArrayLike, value: npt.ArrayLike
) -> tuple[ArrayF, ArrayF]:
    """Body rotations (..., 3, 3) and translations (..., 3) displaced along one coordinate.

    Args:
        geometry: Provides the nominal pose.
        axis_index: Index into :data:`AXES` per sample.
        value: Signed displacement per sample [m or rad].

    """
    axis_index, value = np.broadcast_arrays(np.asarray(axis_index), np.asarray(value, dtype=float))
    displacement = np.zeros((*value.shape, len(AXES)))
    np.put_along_axis(displacement, axis_index[..., None], value[..., None], axis=-1)
    return displacement_poses(geometry, displacement)


def constraint_labels(legs: Sequence[str]) -> list[Cause]:
    """Causes in the column order of :func:`stance_margins`."""
    labels = []
    for leg in legs:
        labels += [Cause("reach", leg, bound="outer"), Cause("reach", leg, bound="inner")]
    for leg in legs:
        for joint in LEG_JOINTS:
            labels += [Cause("joint", leg, joint, "lower"), Cause("joint", leg, joint, "upper")]
    return [*labels, Cause("ground")]


def stance_margins(
    geometry: StanceGeometry, rotation: ArrayF, translation: ArrayF, smooth: bool = False
) -> ArrayF:
    """Every constraint's margin (..., C) for body poses: ≥ 0 feasible, < 0 broken.

    Computed by the compiled kernel (:mod:`.margin_kernel`). Columns (see
    :func:`constraint_labels`): per leg the outer and inner reach [m]; per leg and joint the
    lower and upper limit [rad]; last the body's lowest point's height above the ground [m]
    (C = 8N + 1).

    With ``smooth``, the forms a gradient-based search needs, smooth up to the boundary,
    with the same feasible poses: reach as squared distances, (l2 + l3)² − r² and
    r² − (l2 − l3)² [m²]; the knee's fixed limits on cos θ3 = (r² − l2² − l3²)/(2·l2·l3) [-]
    instead of θ3 through arccos, whose slope is infinite where the leg straightens (a
    coupled knee bound, or a knee that may pass 0, keeps the θ3 form); the ground as
    several smooth columns instead of the lowest point's kinked one: each corner's height
    for a box [m], and for a cylinder g = t_z − h·|R_zz| [m] and g·|g| − r²(R_zx² + R_zy²)
    [m²], whose zero sets together are the rim's lowest point touching the ground.
    """
    rotation = np.asarray(rotation, dtype=float)
    translation = np.asarray(translation, dtype=float)
    shape = np.broadcast_shapes(rotation.shape[:-2], translation.shape[:-1])
    rotations = np.ascontiguousarray(np.broadcast_to(rotation, (*shape, 3, 3)).reshape(-1, 3, 3))
    positions = np.ascontiguousarray(np.broadcast_to(translation, (*shape, 3)).reshape(-1, 3))
    values = margins_of_poses(kernel_geometry([geometry], smooth), rotations, positions)
    return values.reshape(*shape, values.shape[-1])


def broken_at_nominal(geometry: StanceGeometry, cause: Cause, margin: float) -> str:
    """What the nominal stance breaks, in words, from its ``cause`` and (negative) ``margin``.

    The constraint, the leg and the joint or body part, and the value against its limit.
    """
    if cause.kind == "joint" and cause.leg is not None and cause.joint is not None:
        leg, joint = geometry.legs.index(cause.leg), LEG_JOINTS.index(cause.joint)
        if cause.bound == "lower":
            limit = float(geometry.joint_lower[leg, joint])
            value, side = limit + margin, "below its lower limit"
        else:
            limit = float(geometry.joint_upper[leg, joint])
            value, side = limit - margin, "above its upper limit"
        return (
            f"leg {cause.leg}'s {cause.joint} joint at {value:.6g} rad, {side} {limit:.6g} rad "
            f"(θ, hexaleg's angles)"
        )
    if cause.kind == "reach":
        how = "farther than its reach" if cause.bound == "outer" else "nearer than its reach"
        return f"leg {cause.leg}'s foothold {1000 * -margin:.3g} mm {how} (the foot is not on it)"
    if cause.kind == "ground":
        return f"the body's lowest point {1000 * -margin:.3g} mm below the ground (limit: 0)"
    return f"{cause} (margin {margin:.6g})"
