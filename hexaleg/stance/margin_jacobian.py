"""The smooth stance margins' Jacobian in closed form, compiled: what the local searches follow.

:func:`pose_margins_and_jacobian` gives the smooth margins of one displacement
d = (x, y, z [m], roll, pitch, yaw [rad]) (as :func:`~.margin_kernel.pose_margins`) and
their derivatives with respect to d (C, 6), by the chain rule through the foothold in
each leg's root frame, the knee-down IK (eq 8–9) and the body's lowest points: about
two margin evaluations' work, where forward differences take seven. Where the IK is
clipped (a foothold out of reach) the angles' derivatives are those of the clipped
forms, zero, as a difference quotient would see them.
"""

from __future__ import annotations

import math

import numpy as np

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF
from hexaleg.stance.leg_kernel import LegSolution, leg_derivatives, leg_solution
from hexaleg.stance.margin_kernel import (
    COSINE_FORM,
    COUPLED_FORM,
    KernelGeometry,
    foot_in_root,
    ground_margins,
    leg_margins,
    rpy_matrix,
)


@compiled
def pose_margins_and_jacobian(
    geometry: KernelGeometry, design: int, d: ArrayF, values: ArrayF, jacobian: ArrayF
) -> None:  # pragma: no cover - compiled; tested against finite differences
    """Write the smooth margins (C,) of displacement d (6,) and their Jacobian (C, 6).

    ``geometry`` must hold smooth margins (``kernel_geometry(..., smooth=True)``).
    """
    rotation, turned = np.empty((3, 3)), np.empty((3, 3, 3))
    rpy_matrix(d[3], d[4], d[5], rotation)
    rotation_derivatives(d[3], d[4], d[5], rotation, turned)
    tx, ty, tz = d[0], d[1], d[2] + geometry.heights[design]
    foot = np.empty((3, 6))
    for index in range(geometry.root_positions.shape[0]):
        px, py, pz = foot_in_root(geometry, design, index, rotation, tx, ty, tz)
        leg = leg_solution(geometry.legs[design, index], px, py, pz)
        leg_margins(geometry, design, index, leg, values)
        foot_jacobian(geometry, design, index, rotation, turned, tx, ty, tz, foot)
        leg_jacobian(geometry, design, index, leg, (px, py, pz), foot, jacobian)
    ground_margins(geometry, tz, rotation, values)
    ground_jacobian(geometry, tz, rotation, turned, jacobian)


@compiled
def rotation_derivatives(
    roll: float, pitch: float, yaw: float, rotation: ArrayF, out: ArrayF
) -> None:  # pragma: no cover - compiled
    """∂R/∂roll, ∂R/∂pitch, ∂R/∂yaw (3, 3, 3) of R = Rz(yaw)·Ry(pitch)·Rx(roll) (``rotation``)."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    for r in range(3):  # roll: R·[e_x]×, columns (0, R_2, −R_1)
        out[0, r, 0], out[0, r, 1], out[0, r, 2] = 0.0, rotation[r, 2], -rotation[r, 1]
    out[1, 0, 0], out[1, 0, 1], out[1, 0, 2] = -cy * sp, cy * cp * sr, cy * cp * cr
    out[1, 1, 0], out[1, 1, 1], out[1, 1, 2] = -sy * sp, sy * cp * sr, sy * cp * cr
    out[1, 2, 0], out[1, 2, 1], out[1, 2, 2] = -cp, -sp * sr, -sp * cr
    for c in range(3):  # yaw: [e_z]×·R, rows (−R_1, R_0, 0)
        out[2, 0, c], out[2, 1, c], out[2, 2, c] = -rotation[1, c], rotation[0, c], 0.0


@compiled
def foot_jacobian(
    geometry: KernelGeometry,
    design: int,
    leg: int,
    rotation: ArrayF,
    turned: ArrayF,
    tx: float,
    ty: float,
    tz: float,
    out: ArrayF,
) -> None:  # pragma: no cover - compiled
    """∂p/∂d (3, 6) of the foothold p = R_rᵀ(Rᵀ(f − t) − p_r) in the leg's root frame."""
    foothold, frame = geometry.footholds[design, leg], geometry.root_rotations[leg]
    offset = (foothold[0] - tx, foothold[1] - ty, foothold[2] - tz)
    body = np.empty(3)  # ∂(Rᵀ(f − t))/∂d_k, then turned into the root frame
    for k in range(6):
        for c in range(3):
            if k < 3:
                body[c] = -rotation[k, c]
            else:
                body[c] = (
                    turned[k - 3, 0, c] * offset[0]
                    + turned[k - 3, 1, c] * offset[1]
                    + turned[k - 3, 2, c] * offset[2]
                )
        for c in range(3):
            out[c, k] = body[0] * frame[0, c] + body[1] * frame[1, c] + body[2] * frame[2, c]


@compiled
def leg_jacobian(
    geometry: KernelGeometry,
    design: int,
    index: int,
    leg: LegSolution,
    p: tuple[float, float, float],
    foot: ArrayF,
    out: ArrayF,
) -> None:  # pragma: no cover - compiled
    """Write the rows of one leg's reach (2) and joint (6) margins, given ∂p/∂d (``foot``).

    ``leg`` is the IK of the foothold ``p`` (px, py, pz) in the leg-root frame [m].
    """
    lengths = geometry.legs[design, index]
    j = 2 * geometry.root_positions.shape[0] + 6 * index
    for k in range(6):
        d_theta1, d_theta2, d_theta3, d_r2, d_knee_cos = leg_derivatives(
            lengths, leg, p[0], p[1], p[2], foot[0, k], foot[1, k], foot[2, k]
        )
        out[2 * index, k], out[2 * index + 1, k] = -d_r2, d_r2
        out[j, k], out[j + 1, k] = d_theta1, -d_theta1
        out[j + 2, k], out[j + 3, k] = d_theta2, -d_theta2
        out[j + 4, k], out[j + 5, k] = d_theta3, -d_theta3
        if geometry.knee == COUPLED_FORM and -leg.theta2 - math.pi / 2 > geometry.lower[index, 2]:
            out[j + 4, k] = d_theta3 + d_theta2
        elif geometry.knee == COSINE_FORM:
            out[j + 4, k], out[j + 5, k] = d_knee_cos, -d_knee_cos


@compiled
def ground_jacobian(
    geometry: KernelGeometry, tz: float, rotation: ArrayF, turned: ArrayF, out: ArrayF
) -> None:  # pragma: no cover - compiled
    """Write the rows of the smooth ground margins (after the legs') of ``out``."""
    g = 8 * geometry.root_positions.shape[0]
    half = geometry.half_extents
    tilt_x, tilt_y, tilt_z = rotation[2, 0], rotation[2, 1], rotation[2, 2]
    rows = 2 if geometry.round_body else 8
    out[g : g + rows, :] = 0.0
    centre = tz - half[2] * abs(tilt_z)
    for k in range(6):
        dz = 1.0 if k == 2 else 0.0
        if k < 3:
            d_tilt_x, d_tilt_y, d_tilt_z = 0.0, 0.0, 0.0
        else:
            d_tilt_x, d_tilt_y = turned[k - 3, 2, 0], turned[k - 3, 2, 1]
            d_tilt_z = turned[k - 3, 2, 2]
        if geometry.round_body:
            d_centre = dz - half[2] * math.copysign(1.0, tilt_z) * d_tilt_z
            out[g, k] = d_centre
            out[g + 1, k] = 2 * abs(centre) * d_centre - half[0] ** 2 * 2 * (
                tilt_x * d_tilt_x + tilt_y * d_tilt_y
            )
            continue
        c = 0
        for sx in (-1.0, 1.0):
            for sy in (-1.0, 1.0):
                for sz in (-1.0, 1.0):
                    corner = d_tilt_x * sx * half[0] + d_tilt_y * sy * half[1]
                    out[g + c, k] = dz + corner + d_tilt_z * sz * half[2]
                    c += 1
