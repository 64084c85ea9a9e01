"""Stance margins from their definitions, in NumPy: the oracle the compiled kernel is held to.

A body pose (R, t) puts each foothold f in its leg's root frame (R_r, p_r on the body),
p = R_rᵀ(Rᵀ(f − t) − p_r) (eq 11–12); the knee-down IK of eq 8–9 (``hexaleg.kinematics``,
the closed forms' NumPy oracle) gives the joint angles θ and the hip-to-foot distance r.
The pose holds while every r lies in the annulus |l2 − l3| ≤ r ≤ l2 + l3, every θ within
the stance limits (the knee above the hip-coupled bound max(θ3_min, −θ2 − π/2) where the
limits couple it, Table 4) and the body's lowest point above the ground: the lowest of a
box's eight corners, or of a cylinder's rim. The smooth forms (for gradient searches)
square the reach, bound a fixed knee range within [−π, 0] on cos θ3 by the law of cosines,
and give the ground as each corner's height, or for a cylinder g = t_z − h·|R_zz| and
g·|g| − ρ²(R_zx² + R_zy²).

Columns: per leg the outer and inner reach, then per leg (θ1, θ2, θ3) × (lower, upper),
then the ground.
"""

from __future__ import annotations

import math

import numpy as np

from hexaleg.kinematics import leg_solution
from hexaleg.stance.constraints import displacement_poses
from hexaleg.stance.geometry import CORNER_SIGNS, StanceGeometry


def feet_in_roots(geometry: StanceGeometry, rotation, translation) -> np.ndarray:
    """Each foothold in its leg-root frame (..., N, 3) [m], eq 11–12 written out."""
    rotation, translation = np.asarray(rotation), np.asarray(translation)
    offset = geometry.footholds - translation[..., None, :]
    in_body = np.einsum("...ji,...nj->...ni", rotation, offset)
    return np.einsum("nji,...nj->...ni", geometry.root_rotations, in_body - geometry.root_positions)


def exact_margins(geometry: StanceGeometry, rotation, translation) -> np.ndarray:
    """Every constraint's margin (..., 8N + 1) [m or rad]: ≥ 0 holds."""
    return _margins(geometry, rotation, translation, smooth=False)


def smooth_margins(geometry: StanceGeometry, rotation, translation) -> np.ndarray:
    """The smooth forms (..., 8N + K) of the same constraints [m, m², rad or -]."""
    return _margins(geometry, rotation, translation, smooth=True)


def displaced(geometry: StanceGeometry, displacements, smooth: bool = False) -> np.ndarray:
    """The margins of displacements (..., 6) from the nominal stance."""
    return _margins(geometry, *displacement_poses(geometry, displacements), smooth)


def _margins(geometry, rotation, translation, smooth):
    _, l2, l3 = geometry.lengths
    theta, r = leg_solution(geometry.lengths, feet_in_roots(geometry, rotation, translation))
    if smooth:
        reach = [(l2 + l3) ** 2 - r**2, r**2 - (l2 - l3) ** 2]
    else:
        reach = [l2 + l3 - r, r - abs(l2 - l3)]
    limits = geometry.limits
    joints = np.stack([theta - limits.lower, limits.upper - theta], axis=-1)  # (..., N, 3, 2)
    lowest_knee, highest_knee = limits.theta3
    if limits.coupled_knee:
        joints[..., 2, 0] = theta[..., 2] - np.maximum(lowest_knee, -theta[..., 1] - math.pi / 2)
    elif smooth and -math.pi <= lowest_knee < highest_knee <= 0:
        cos_knee = (r**2 - l2**2 - l3**2) / (2 * l2 * l3)  # the law of cosines
        joints[..., 2, 0] = cos_knee - math.cos(lowest_knee)
        joints[..., 2, 1] = math.cos(highest_knee) - cos_knee
    shape = theta.shape[:-2]
    columns = [np.stack(reach, axis=-1).reshape(*shape, -1), joints.reshape(*shape, -1)]
    return np.concatenate([*columns, _ground(geometry, rotation, translation, smooth)], axis=-1)


def _ground(geometry, rotation, translation, smooth):
    rotation, translation = np.asarray(rotation), np.asarray(translation)
    height, tilt = translation[..., 2], rotation[..., 2, :]  # the body axes' z components
    if not geometry.body_round:
        corners = height[..., None] + tilt @ (CORNER_SIGNS * geometry.body_half_extents).T
        return corners if smooth else corners.min(axis=-1, keepdims=True)
    radius, _, half = geometry.body_half_extents
    centre = height - half * np.abs(tilt[..., 2])
    rim = radius * np.hypot(tilt[..., 0], tilt[..., 1])
    if not smooth:
        return (centre - rim)[..., None]
    return np.stack([centre, centre * np.abs(centre) - rim**2], axis=-1)
