"""The free-coupled search's inner loop, compiled: stance margins of body displacements.

SLSQP asks for the margins of seven poses at a time (a point and its six forward steps)
some thousand times per design. In NumPy each call is ~40 array operations on 42 leg
solutions, and their overhead, not the arithmetic, was half of the search's time.
:func:`compiled_margins` computes the same numbers in one Numba-compiled loop:
``smooth_stance_margins(geometry, *displacement_poses(geometry, d))`` column for column,
or with ``smooth=False`` those of ``stance_margins`` (the exact check every answer and
the start scan pass).
The NumPy functions stay the reference (they also serve the axis-locked search, whose
batches of thousands of poses NumPy handles well); the tests hold the kernel to them.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numba
import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.stance.constraints import knee_on_cosine
from hexaleg.stance.geometry import StanceGeometry

THETA_FORM, COUPLED_FORM, COSINE_FORM = 0, 1, 2
"""How the knee's lower and upper margins are written (see ``smooth_stance_margins``):
on θ3, θ3 above the hip-coupled bound, or on cos θ3 (smooth margins only)."""


def compiled_margins(
    geometry: StanceGeometry, smooth: bool = True
) -> Callable[[npt.ArrayLike], ArrayF]:
    """Stance margins of displacements d (..., 6) from the nominal stance.

    The returned function equals ``smooth_stance_margins(geometry,
    *displacement_poses(geometry, d))`` (..., 8N + K): reach [m²], joint margins [rad]
    (the knee's on cos θ3 where that form applies [-]) and the ground [m or m²]; with
    ``smooth=False``, ``stance_margins`` (..., 8N + 1) [m or rad].
    """
    limits = geometry.limits
    if limits.coupled_knee:
        knee = COUPLED_FORM
    elif smooth and knee_on_cosine(limits):
        knee = COSINE_FORM
    else:
        knee = THETA_FORM
    parameters = (
        float(geometry.nominal_height),
        np.ascontiguousarray(geometry.footholds, dtype=float),
        np.ascontiguousarray(geometry.root_positions, dtype=float),
        np.ascontiguousarray(geometry.root_rotations, dtype=float),
        np.array(geometry.lengths, dtype=float),
        np.ascontiguousarray(limits.lower),
        np.ascontiguousarray(limits.upper),
        knee,
        bool(geometry.body_round),
        np.ascontiguousarray(geometry.body_half_extents, dtype=float),
        smooth,
    )

    def margins(displacements: npt.ArrayLike) -> ArrayF:
        d = np.asarray(displacements, dtype=float)
        flat = np.ascontiguousarray(d.reshape(-1, 6))
        values: ArrayF = _margins(flat, *parameters)
        return values.reshape(*d.shape[:-1], values.shape[-1])

    return margins


@numba.njit(cache=True)
def _margins(
    displacements: ArrayF,
    height: float,
    footholds: ArrayF,
    root_positions: ArrayF,
    root_rotations: ArrayF,
    lengths: ArrayF,
    lower: ArrayF,
    upper: ArrayF,
    knee: int,
    round_body: bool,
    half_extents: ArrayF,
    smooth: bool,
) -> ArrayF:  # pragma: no cover - compiled; tested against the NumPy reference
    legs = footholds.shape[0]
    ground = 1 if not smooth else 2 if round_body else 8
    l1, l2, l3 = lengths[0], lengths[1], lengths[2]
    cos_low, cos_high = math.cos(lower[2]), math.cos(upper[2])
    out = np.empty((displacements.shape[0], 8 * legs + ground))
    rotation = np.empty((3, 3))
    for p in range(displacements.shape[0]):
        # the body pose: Pinocchio's rpy, R = Rz(yaw)·Ry(pitch)·Rx(roll), as rpy_rotation
        cr, sr = math.cos(displacements[p, 3]), math.sin(displacements[p, 3])
        cp, sp = math.cos(displacements[p, 4]), math.sin(displacements[p, 4])
        cy, sy = math.cos(displacements[p, 5]), math.sin(displacements[p, 5])
        rotation[0, 0] = cy * cp
        rotation[0, 1] = cy * sp * sr - sy * cr
        rotation[0, 2] = cy * sp * cr + sy * sr
        rotation[1, 0] = sy * cp
        rotation[1, 1] = sy * sp * sr + cy * cr
        rotation[1, 2] = sy * sp * cr - cy * sr
        rotation[2, 0] = -sp
        rotation[2, 1] = cp * sr
        rotation[2, 2] = cp * cr
        tx, ty, tz = displacements[p, 0], displacements[p, 1], displacements[p, 2] + height
        for n in range(legs):
            # the foothold in the leg root's frame: R_rᵀ(Rᵀ(f − t) − p_r)
            fx, fy, fz = footholds[n, 0] - tx, footholds[n, 1] - ty, footholds[n, 2] - tz
            root = root_positions[n]
            bx = fx * rotation[0, 0] + fy * rotation[1, 0] + fz * rotation[2, 0] - root[0]
            by = fx * rotation[0, 1] + fy * rotation[1, 1] + fz * rotation[2, 1] - root[1]
            bz = fx * rotation[0, 2] + fy * rotation[1, 2] + fz * rotation[2, 2] - root[2]
            frame = root_rotations[n]
            px = bx * frame[0, 0] + by * frame[1, 0] + bz * frame[2, 0]
            py = bx * frame[0, 1] + by * frame[1, 1] + bz * frame[2, 1]
            pz = bx * frame[0, 2] + by * frame[1, 2] + bz * frame[2, 2]
            # knee-down IK (eq 8–9), as kinematics.leg_plane and plane_solution
            theta1 = math.atan2(py, px)
            if theta1 > math.pi / 2:
                theta1 -= math.pi
            if theta1 <= -math.pi / 2:
                theta1 += math.pi
            planar_x = px * math.cos(theta1) + py * math.sin(theta1) - l1
            r = math.hypot(planar_x, pz)
            r_safe = r if r > 0 else 1.0
            cos_hip = min(max((r**2 + l2**2 - l3**2) / (2 * l2 * r_safe), -1.0), 1.0)
            hip = math.atan2(pz, planar_x) + math.acos(cos_hip)
            theta2 = math.pi - (math.pi - hip) % (2 * math.pi)
            theta3 = -math.acos(min(max((r**2 - l2**2 - l3**2) / (2 * l2 * l3), -1.0), 1.0))
            r2 = planar_x**2 + pz**2
            cos_knee = (r2 - l2**2 - l3**2) / (2 * l2 * l3)  # the smooth form's, on r²
            if smooth:
                out[p, 2 * n] = (l2 + l3) ** 2 - r2
                out[p, 2 * n + 1] = r2 - (l2 - l3) ** 2
            else:
                out[p, 2 * n] = l2 + l3 - r
                out[p, 2 * n + 1] = r - abs(l2 - l3)
            j = 2 * legs + 6 * n
            out[p, j] = theta1 - lower[0]
            out[p, j + 1] = upper[0] - theta1
            out[p, j + 2] = theta2 - lower[1]
            out[p, j + 3] = upper[1] - theta2
            out[p, j + 4] = theta3 - lower[2]
            out[p, j + 5] = upper[2] - theta3
            if knee == COUPLED_FORM:
                out[p, j + 4] = theta3 - max(lower[2], -theta2 - math.pi / 2)
            elif knee == COSINE_FORM:
                out[p, j + 4] = cos_knee - cos_low
                out[p, j + 5] = cos_high - cos_knee
        # the ground, as StanceGeometry.lowest_body_height and smooth_ground_margins
        g = 8 * legs
        if not smooth and round_body:
            out[p, g] = tz - (
                half_extents[0] * math.hypot(rotation[2, 0], rotation[2, 1])
                + half_extents[2] * abs(rotation[2, 2])
            )
        elif not smooth:
            out[p, g] = tz - (
                abs(rotation[2, 0]) * half_extents[0]
                + abs(rotation[2, 1]) * half_extents[1]
                + abs(rotation[2, 2]) * half_extents[2]
            )
        elif round_body:
            radius, half = half_extents[0], half_extents[2]
            centre = tz - half * abs(rotation[2, 2])
            out[p, g] = centre
            out[p, g + 1] = centre * abs(centre) - radius**2 * (
                rotation[2, 0] ** 2 + rotation[2, 1] ** 2
            )
        else:
            c = 0
            for sx in (-1.0, 1.0):
                for sy in (-1.0, 1.0):
                    for sz in (-1.0, 1.0):
                        out[p, g + c] = tz + (
                            rotation[2, 0] * sx * half_extents[0]
                            + rotation[2, 1] * sy * half_extents[1]
                            + rotation[2, 2] * sz * half_extents[2]
                        )
                        c += 1
    return out
