"""Closed-form leg kinematics, vectorized: the paper's D-H table (Table 1) and the general leg.

These are the independent oracle the tests hold the Pinocchio model against,
and the fast kernels of the sweeps once a test has proven them equal to it.
Every function takes a leg — the paper's by its segment lengths ``(l1, l2, l3)`` [m], or
any yaw–pitch–pitch leg as a :class:`~hexaleg.leg_geometry.LegGeometry` (coxa a1, femur
l2, tibia l3, hip height h, lateral offset e) — and joint angles with a trailing axis
of size 3 (θ1 root, θ2 hip, θ3 knee) [rad], any leading shape; positions are expressed
in the leg-root frame (z up along the yaw axis, coxa along x at θ1 = 0). The paper's
formulas are the case h = e = 0, computed by the same lines. :func:`foot_position`,
:func:`foot_jacobian` and :func:`leg_solution` also take several different legs side by
side (:data:`~hexaleg.leg_geometry.LegRows`), their angles' leg axis the one before the last.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF, Lengths
from hexaleg.leg_geometry import Dimension, LegLike, LegRows, leg_parameters
from hexaleg.limits import JointLimits


def foot_position(leg: LegLike | LegRows, theta: npt.ArrayLike) -> ArrayF:
    """Foot position p (..., 3) in the leg-root frame [m] (eq 7; h and e added for a general leg).

    Args:
        leg: The paper's segment lengths (l1, l2, l3) [m], or a general leg.
        theta: Joint angles (..., 3) [rad].

    """
    l1, l2, l3, h, e = leg_parameters(leg)
    theta = np.asarray(theta, dtype=float)
    t1, t2, t3 = theta[..., 0], theta[..., 1], theta[..., 2]
    t23 = t2 + t3
    reach = l1 + l2 * np.cos(t2) + l3 * np.cos(t23)
    c1, s1 = np.cos(t1), np.sin(t1)
    return np.stack(
        (c1 * reach - s1 * e, s1 * reach + c1 * e, h + l2 * np.sin(t2) + l3 * np.sin(t23)),
        axis=-1,
    )


def planar_foot_position(leg: LegLike, theta2: npt.ArrayLike, theta3: npt.ArrayLike) -> ArrayF:
    """Foot position (x, z) (..., 2) in the leg plane at θ1 = 0 [m] (eq 14)."""
    l1, l2, l3, h, _ = leg_parameters(leg)
    theta2 = np.asarray(theta2, dtype=float)
    t23 = theta2 + np.asarray(theta3, dtype=float)
    return np.stack(
        (l1 + l2 * np.cos(theta2) + l3 * np.cos(t23), h + l2 * np.sin(theta2) + l3 * np.sin(t23)),
        axis=-1,
    )


def foot_jacobian(leg: LegLike | LegRows, theta: npt.ArrayLike) -> ArrayF:
    """Foot linear-velocity Jacobian dp/dθ (..., 3, 3) in the leg-root frame [m/rad] (eq 22)."""
    l1, l2, l3, _, e = leg_parameters(leg)
    theta = np.asarray(theta, dtype=float)
    t1, t2, t3 = theta[..., 0], theta[..., 1], theta[..., 2]
    c1, s1 = np.cos(t1), np.sin(t1)
    t23 = t2 + t3
    reach = l1 + l2 * np.cos(t2) + l3 * np.cos(t23)
    dz2 = l3 * np.cos(t23) + l2 * np.cos(t2)  # d p_z / d θ2
    dz3 = l3 * np.cos(t23)
    dr2 = -l3 * np.sin(t23) - l2 * np.sin(t2)  # d reach / d θ2
    dr3 = -l3 * np.sin(t23)
    jac = np.empty((*theta.shape[:-1], 3, 3))
    jac[..., 0, 0] = -s1 * reach - c1 * e
    jac[..., 0, 1] = c1 * dr2
    jac[..., 0, 2] = c1 * dr3
    jac[..., 1, 0] = c1 * reach - s1 * e
    jac[..., 1, 1] = s1 * dr2
    jac[..., 1, 2] = s1 * dr3
    jac[..., 2, 0] = 0.0
    jac[..., 2, 1] = dz2
    jac[..., 2, 2] = dz3
    return jac


def manipulability(leg: LegLike, theta2: npt.ArrayLike, theta3: npt.ArrayLike) -> ArrayF:
    """Manipulability w = |det J| [m³], factored: l2·l3·|sin θ3|·|l1 + l2 cos θ2 + l3 cos(θ2+θ3)|.

    Independent of θ1, and of a general leg's hip height h and lateral offset e (det J =
    −l2·l3·sin θ3·(a1 + l2 cos θ2 + l3 cos(θ2+θ3)) whatever they are). The factored form
    is algebraically equal to the paper's printed simplification (eq 24/25,
    :func:`manipulability_eq25`); the tests prove both equal |det J| of eq 22 and of the
    Pinocchio model.
    """
    l1, l2, l3, _, _ = leg_parameters(leg)
    theta2 = np.asarray(theta2, dtype=float)
    theta3 = np.asarray(theta3, dtype=float)
    reach = l1 + l2 * np.cos(theta2) + l3 * np.cos(theta2 + theta3)
    return l2 * l3 * np.abs(np.sin(theta3) * reach)


def manipulability_eq25(leg: LegLike, theta2: npt.ArrayLike, theta3: npt.ArrayLike) -> ArrayF:
    """The paper's printed simplified form of eq 24 (= eq 25), term by term [m³]."""
    l1, l2, l3, _, _ = leg_parameters(leg)
    t2 = np.asarray(theta2, dtype=float)
    t3 = np.asarray(theta3, dtype=float)
    s2, c2, s3, c3 = np.sin(t2), np.cos(t2), np.sin(t3), np.cos(t3)
    inner = l1 * s3 - l3 * s2 + l2 * c2 * s3 + l3 * c3**2 * s2 + l3 * c2 * c3 * s3
    return np.abs(-l2 * l3 * inner)


class InverseKinematics(NamedTuple):
    """Result of :func:`inverse_kinematics`.

    Attributes:
        theta: Joint angles (..., 3) [rad]; where ``reachable`` is false, the
            angles of the nearest configuration on the boundary of reach (finite, never NaN).
        reachable: Whether the target is reached exactly (and, if limits were
            given, within them) (...).

    """

    theta: ArrayF
    reachable: npt.NDArray[np.bool_]


def inverse_kinematics(
    leg: LegLike,
    position: npt.ArrayLike,
    limits: JointLimits | None = None,
    tol: float = 1e-12,
) -> InverseKinematics:
    """Knee-down inverse kinematics (eq 8–9), vectorized, with a reachability flag.

    θ1 = arctan(p_y / p_x) ∈ (−π/2, π/2] as in eq 8, so a foot behind the root
    axis is reached with the coxa pointing away from it; the knee bends down
    (θ3 ≤ 0). The hip elevation uses atan2 in the leg plane, which equals the
    paper's arcsin form whenever the foot is outward of the hip; θ2 is wrapped
    to (−π, π]. A general leg's lateral offset e turns θ1 by atan2(e, X), X the
    foot's distance from the yaw axis in the leg plane (:func:`leg_plane`).

    Args:
        leg: The paper's segment lengths (l1, l2, l3) [m], or a general leg.
        position: Foot targets (..., 3) in the leg-root frame [m].
        limits: If given, targets whose solution violates them are flagged unreachable.
        tol: Slack on the reach annulus |l2 − l3| ≤ r ≤ l2 + l3 and on the lateral
            offset's cylinder √(p_x² + p_y²) ≥ |e| [m].

    """
    _, l2, l3, _, e = leg_parameters(leg)
    theta, r = leg_solution(leg, position)
    reachable = (r <= l2 + l3 + tol) & (r >= abs(l2 - l3) - tol) & (r > 0)
    if e != 0.0:
        p = np.asarray(position, dtype=float)
        reachable &= np.hypot(p[..., 0], p[..., 1]) >= abs(e) - tol
    if limits is not None:
        reachable &= limits.contains(theta, tol=1e-12)
    return InverseKinematics(theta, np.asarray(reachable))


def leg_plane(
    leg: float | LegLike | LegRows, position: npt.ArrayLike
) -> tuple[ArrayF, ArrayF, ArrayF, ArrayF]:
    """θ1 toward the target, and the target in the leg plane seen from the hip.

    θ1 = atan2(p_y, p_x) − atan2(e, X), X = √(p_x² + p_y² − e²), the foot's distance
    from the yaw axis along the coxa; where that θ1 lies outside (−π/2, π/2], the other
    branch (X < 0, the coxa pointing away from the foot) is taken if it lies inside, as
    eq 8 does for e = 0. A foot inside the cylinder |e| about the yaw axis gets X = 0.

    Args:
        leg: The coxa length l1 [m] alone (the paper's leg), the three lengths, or a
            general leg.
        position: Targets (..., 3) in the leg-root frame [m].

    Returns:
        (θ1, planar_x, z, r): planar_x along the coxa from the hip axis, z up from it,
        r the hip-to-foot distance in the leg plane [m].

    """
    a1: Dimension
    h: Dimension
    e: Dimension
    if isinstance(leg, int | float | np.floating):
        a1, h, e = float(leg), 0.0, 0.0
    else:
        a1, _, _, h, e = leg_parameters(leg)
    p = np.asarray(position, dtype=float)
    px, py, pz = p[..., 0], p[..., 1], p[..., 2]
    turn = np.arctan2(e, np.sqrt(np.maximum(px * px + py * py - e * e, 0.0)))
    theta1 = np.arctan2(py, px) - turn
    theta1 = np.where(theta1 > np.pi, theta1 - 2 * np.pi, theta1)
    theta1 = np.where(theta1 <= -np.pi, theta1 + 2 * np.pi, theta1)
    other = theta1 + 2 * turn  # the branch X < 0, less π or plus π
    other = np.where(other > 0, other - np.pi, other + np.pi)
    front = (theta1 > -np.pi / 2) & (theta1 <= np.pi / 2)
    theta1 = np.where(front | (other <= -np.pi / 2) | (other > np.pi / 2), theta1, other)
    planar_x = px * np.cos(theta1) + py * np.sin(theta1) - a1  # hip to foot, along the coxa
    z = pz - h
    return theta1, planar_x, z, np.hypot(planar_x, z)  # r² = τ + l1² of eq 9


def leg_solution(leg: LegLike | LegRows, position: npt.ArrayLike) -> tuple[ArrayF, ArrayF]:
    """Knee-down joint angles (..., 3) [rad] and hip-to-foot distance r (...) [m].

    The kernel behind :func:`inverse_kinematics` and the flexibility margins: the
    angles are those of the nearest configuration when r is out of reach.
    """
    a1, l2, l3, _, _ = leg_parameters(leg)
    theta1, planar_x, z, r = leg_plane(leg, position)
    return plane_solution((a1, l2, l3), theta1, planar_x, z, r), r


def plane_solution(
    lengths: Lengths | tuple[Dimension, Dimension, Dimension],
    theta1: ArrayF,
    planar_x: ArrayF,
    pz: ArrayF,
    r: ArrayF,
) -> ArrayF:
    """Knee-down joint angles (..., 3) [rad] from a target already in the leg plane.

    Args:
        lengths: Segment lengths (l1, l2, l3) [m], each an array of several legs' if
            the angles are theirs side by side.
        theta1: Root angle toward the target [rad] (from :func:`leg_plane`).
        planar_x: Hip-to-target distance along the coxa [m].
        pz: Target height above the hip axis [m].
        r: Hip-to-target distance [m].

    """
    _, l2, l3 = lengths
    r_safe = np.where(r > 0, r, 1.0)
    cos_knee = np.clip((r**2 - l2**2 - l3**2) / (2 * l2 * l3), -1.0, 1.0)
    cos_hip = np.clip((r**2 + l2**2 - l3**2) / (2 * l2 * r_safe), -1.0, 1.0)
    theta2 = _wrap(np.arctan2(pz, planar_x) + np.arccos(cos_hip))
    return np.stack((theta1, theta2, -np.arccos(cos_knee)), axis=-1)


def _wrap(angle: ArrayF) -> ArrayF:
    """Angles wrapped to (−π, π] [rad]."""
    return np.pi - np.mod(np.pi - angle, 2 * np.pi)
