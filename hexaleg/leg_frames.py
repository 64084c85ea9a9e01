"""Closed-form frames of a leg's links, their points' Jacobians, and gravity torques.

Each segment of a :class:`~hexaleg.leg_geometry.LegGeometry` has a segment frame K(θ)
in the leg-root frame (z up along the yaw axis):

- coxa ``K1 = Rz(θ1)``;
- femur ``K2 = K1 · T(a1, 0, h) · R₋y(θ2)``, at the hip axis, x along the femur;
- tibia ``K3 = K2 · T(l2, 0, 0) · R₋y(θ3)``, at the knee axis, x along the tibia, the
  foot at ``(l3, e, 0)`` in it;

with ``R₋y(φ)`` the turn by φ about −y (x → (cos φ, 0, sin φ)). A link's own frame is
``K · P``, P its constant :attr:`~hexaleg.leg_geometry.LegGeometry.link_placements`, so
any point fixed to a link — its centre of mass — is known in closed form, and so is its
Jacobian and the torques that hold the leg against gravity.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.gravity import GRAVITY
from hexaleg.leg_geometry import LegLike, as_leg, leg_parameters, placement_matrix

STANDARD_GRAVITY = np.array([0.0, 0.0, -GRAVITY])
"""Gravity in a level leg-root frame [m/s²] (:data:`~hexaleg.gravity.GRAVITY` along −z)."""


def segment_frames(leg: LegLike, theta: npt.ArrayLike) -> ArrayF:
    """The segment frames K1, K2, K3 (..., 3, 4, 4) in the leg-root frame at θ (..., 3) [rad]."""
    a1, l2, _, h, _ = leg_parameters(leg)
    theta = np.asarray(theta, dtype=float)
    t1, t2, t23 = theta[..., 0], theta[..., 1], theta[..., 1] + theta[..., 2]
    c1, s1 = np.cos(t1), np.sin(t1)
    frames = np.zeros((*theta.shape[:-1], 3, 4, 4))
    frames[..., 3, 3] = 1.0
    frames[..., 0, :3, :3] = _turn(c1, s1, np.ones_like(t1), np.zeros_like(t1))
    frames[..., 1, :3, :3] = _turn(c1, s1, np.cos(t2), np.sin(t2))
    frames[..., 2, :3, :3] = _turn(c1, s1, np.cos(t23), np.sin(t23))
    knee_reach = a1 + l2 * np.cos(t2)
    knee_height = h + l2 * np.sin(t2)
    frames[..., 1, :3, 3] = np.stack((c1 * a1, s1 * a1, np.full_like(t1, h)), axis=-1)
    frames[..., 2, :3, 3] = np.stack((c1 * knee_reach, s1 * knee_reach, knee_height), axis=-1)
    return frames


def link_frames(leg: LegLike, theta: npt.ArrayLike) -> ArrayF:
    """Each link's own frame (..., 3, 4, 4) in the leg-root frame: K · P (coxa, femur, tibia)."""
    geometry = as_leg(leg)
    placements = np.array([placement_matrix(p) for p in geometry.link_placements])
    return segment_frames(geometry, theta) @ placements


def link_points(leg: LegLike, theta: npt.ArrayLike, points: npt.ArrayLike) -> ArrayF:
    """Points fixed to the links (..., 3, 3) [m] in the leg-root frame.

    Args:
        leg: The leg.
        theta: Joint angles (..., 3) [rad].
        points: One point per link (3, 3), each in its own link's frame [m].

    """
    frames = link_frames(leg, theta)
    local = np.asarray(points, dtype=float)
    return np.einsum("...kij,kj->...ki", frames[..., :3, :3], local) + frames[..., :3, 3]


def link_point_jacobians(leg: LegLike, theta: npt.ArrayLike, points: npt.ArrayLike) -> ArrayF:
    """dp/dθ (..., 3, 3, 3) of each link's point [m/rad]: [link, coordinate, joint].

    Column j of link k's block is ωⱼ × (p − cⱼ) for the joints j ≤ k that move it, ωⱼ
    the axis the positive θⱼ turns about (z for the root, −y of the coxa for the hip and
    knee) and cⱼ a point on it; zero for the joints beyond the link.
    """
    theta = np.asarray(theta, dtype=float)
    positions = link_points(leg, theta, points)
    frames = segment_frames(leg, theta)
    t1 = theta[..., 0]
    pitch = np.stack((np.sin(t1), -np.cos(t1), np.zeros_like(t1)), axis=-1)  # −y of K1
    yaw = np.broadcast_to(np.array([0.0, 0.0, 1.0]), pitch.shape)
    axes = (yaw, pitch, pitch)
    jac = np.zeros((*theta.shape[:-1], 3, 3, 3))
    for joint in range(3):
        on_axis = frames[..., joint, :3, 3]
        for link in range(joint, 3):
            arm = positions[..., link, :] - on_axis
            jac[..., link, :, joint] = np.cross(axes[joint], arm)
    return jac


def gravity_torques(
    leg: LegLike,
    theta: npt.ArrayLike,
    masses: npt.ArrayLike,
    coms: npt.ArrayLike,
    gravity: npt.ArrayLike = STANDARD_GRAVITY,
) -> ArrayF:
    """Joint torques (..., 3) [N·m] on θ that hold the leg still against gravity.

    τ = −Σₖ Jₖᵀ mₖ g over the three links (Pinocchio's generalized gravity g(θ)); the
    file's joint torques are ``JointMap.torques_to_file`` of them.

    Args:
        leg: The leg.
        theta: Joint angles (..., 3) [rad].
        masses: Each link's mass (3,) [kg].
        coms: Each link's centre of mass (3, 3), in its own link's frame [m].
        gravity: Gravity's acceleration in the leg-root frame (3,) [m/s²].

    """
    jac = link_point_jacobians(leg, theta, coms)
    weights = np.asarray(masses, dtype=float)[:, None] * np.asarray(gravity, dtype=float)
    return -np.einsum("...kij,ki->...j", jac, weights)


def _turn(c1: ArrayF, s1: ArrayF, cos: ArrayF, sin: ArrayF) -> ArrayF:
    """Rz(θ1) · R₋y(φ) (..., 3, 3) from the cosines and sines of θ1 and φ."""
    zero = np.zeros_like(c1)
    return np.stack(
        (
            np.stack((c1 * cos, -s1, -c1 * sin), axis=-1),
            np.stack((s1 * cos, c1, -s1 * sin), axis=-1),
            np.stack((sin, zero, cos), axis=-1),
        ),
        axis=-2,
    )
