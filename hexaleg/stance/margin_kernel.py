"""Stance margins of body displacements, compiled: the one implementation every search uses.

A displacement d = (x, y, z [m], roll, pitch, yaw [rad]) moves the body from the nominal
stance (world frame, Pinocchio's rpy). :func:`margins_of` gives, for many displacements
at once, ``stance_margins`` (the exact check) or ``smooth_stance_margins`` (the forms a
gradient-based search needs) of :mod:`hexaleg.stance.constraints`, column for column:
the NumPy functions there are the readable reference the tests hold this kernel to
(and the rotation of a roll, pitch and yaw, :func:`rpy_matrix`, is Pinocchio's).
The axis-locked search asks for the poses of many designs of one body at once (a
:class:`KernelGeometry` holds each design's lengths, footholds and height; each pose
names its design); the free-coupled search (:mod:`.climb`) asks for one pose at a time
through :func:`pose_margins`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF
from hexaleg.limits import JointLimits
from hexaleg.stance.geometry import StanceGeometry

THETA_FORM, COUPLED_FORM, COSINE_FORM = 0, 1, 2
"""How the knee's lower and upper margins are written (see ``smooth_stance_margins``):
on θ3, θ3 above the hip-coupled bound, or on cos θ3 (smooth margins only)."""


def knee_on_cosine(limits: JointLimits) -> bool:
    """Whether the smooth margins bound the knee on cos θ3 rather than on θ3.

    So they do for fixed knee limits within [−π, 0], where cos θ3 is monotonic; a coupled
    knee bound keeps the θ3 form.
    """
    return not limits.coupled_knee and -math.pi <= limits.theta3[0] < limits.theta3[1] <= 0


class KernelGeometry(NamedTuple):
    """Stance geometries of D designs sharing a body, mounts, stance legs and limits.

    Attributes:
        heights: Nominal body heights (D,) [m].
        footholds: Footholds (D, N, 3), world frame [m].
        lengths: Segment lengths (D, 3) [m].
        root_positions: Leg-root origins (N, 3), body frame [m].
        root_rotations: Leg-root orientations (N, 3, 3), body frame.
        lower: Lower joint limits (3,) [rad].
        upper: Upper joint limits (3,) [rad].
        knee: :data:`THETA_FORM`, :data:`COUPLED_FORM` or :data:`COSINE_FORM`.
        round_body: The body is a cylinder about z (else a box).
        half_extents: The body's half sizes (3,) [m] (radius, radius, half height if round).
        smooth: Smooth margins (else exact ones).

    """

    heights: ArrayF
    footholds: ArrayF
    lengths: ArrayF
    root_positions: ArrayF
    root_rotations: ArrayF
    lower: ArrayF
    upper: ArrayF
    knee: int
    round_body: bool
    half_extents: ArrayF
    smooth: bool


def kernel_geometry(geometries: Sequence[StanceGeometry], smooth: bool) -> KernelGeometry:
    """The kernel's form of stances that differ only in their legs (a sweep's designs)."""
    template = geometries[0]
    limits = template.limits
    if limits.coupled_knee:
        knee = COUPLED_FORM
    elif smooth and knee_on_cosine(limits):
        knee = COSINE_FORM
    else:
        knee = THETA_FORM
    return KernelGeometry(
        heights=np.array([g.nominal_height for g in geometries], dtype=float),
        footholds=np.ascontiguousarray([g.footholds for g in geometries], dtype=float),
        lengths=np.array([g.lengths for g in geometries], dtype=float),
        root_positions=np.ascontiguousarray(template.root_positions, dtype=float),
        root_rotations=np.ascontiguousarray(template.root_rotations, dtype=float),
        lower=np.ascontiguousarray(limits.lower, dtype=float),
        upper=np.ascontiguousarray(limits.upper, dtype=float),
        knee=knee,
        round_body=bool(template.body_round),
        half_extents=np.ascontiguousarray(template.body_half_extents, dtype=float),
        smooth=smooth,
    )


def compiled_margins(
    geometry: StanceGeometry, smooth: bool = True
) -> Callable[[npt.ArrayLike], ArrayF]:
    """Stance margins of displacements d (..., 6) from the nominal stance of one design.

    The returned function equals ``smooth_stance_margins(geometry,
    *displacement_poses(geometry, d))`` (..., 8N + K): reach [m²], joint margins [rad]
    (the knee's on cos θ3 where that form applies [-]) and the ground [m or m²]; with
    ``smooth=False``, ``stance_margins`` (..., 8N + 1) [m or rad].
    """
    kernel = kernel_geometry([geometry], smooth)

    def margins(displacements: npt.ArrayLike) -> ArrayF:
        d = np.asarray(displacements, dtype=float)
        flat = np.ascontiguousarray(d.reshape(-1, 6))
        values: ArrayF = margins_of(kernel, flat, np.zeros(len(flat), dtype=np.int64))
        return values.reshape(*d.shape[:-1], values.shape[-1])

    return margins


@compiled
def column_count(geometry: KernelGeometry) -> int:  # pragma: no cover - compiled
    """Margins per pose: 8 per stance leg, and the ground's (1 exact, 2 or 8 smooth)."""
    if not geometry.smooth:
        ground = 1
    elif geometry.round_body:
        ground = 2
    else:
        ground = 8
    return int(8 * geometry.root_positions.shape[0] + ground)


@compiled
def margins_of(
    geometry: KernelGeometry, displacements: ArrayF, designs: npt.NDArray[np.int64]
) -> ArrayF:  # pragma: no cover - compiled; tested against the NumPy reference
    """Margins (P, C) of displacements (P, 6), pose p of design ``designs[p]``."""
    out = np.empty((displacements.shape[0], column_count(geometry)))
    rotation = np.empty((3, 3))
    for p in range(displacements.shape[0]):
        pose_margins(geometry, designs[p], displacements[p], rotation, out[p])
    return out


@compiled
def rotations_of(rpy: ArrayF) -> ArrayF:  # pragma: no cover - compiled
    """Rotations (P, 3, 3) of roll, pitch, yaw (P, 3) [rad], as Pinocchio's ``rpy``."""
    out = np.empty((rpy.shape[0], 3, 3))
    for p in range(rpy.shape[0]):
        rpy_matrix(rpy[p, 0], rpy[p, 1], rpy[p, 2], out[p])
    return out


@compiled
def pose_margins(
    geometry: KernelGeometry, design: int, d: ArrayF, rotation: ArrayF, out: ArrayF
) -> None:  # pragma: no cover - compiled
    """Write the margins of displacement d (6,) of one design into ``out`` (C,)."""
    rpy_matrix(d[3], d[4], d[5], rotation)
    tx, ty, tz = d[0], d[1], d[2] + geometry.heights[design]
    for leg in range(geometry.root_positions.shape[0]):
        px, py, pz = foot_in_root(geometry, design, leg, rotation, tx, ty, tz)
        leg_margins(geometry, design, leg, px, py, pz, out)
    ground_margins(geometry, tz, rotation, out)


@compiled
def rpy_matrix(roll: float, pitch: float, yaw: float, out: ArrayF) -> None:  # pragma: no cover
    """R = Rz(yaw)·Ry(pitch)·Rx(roll) into ``out`` (3, 3): Pinocchio's ``rpy.rpyToMatrix``."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    out[0, 0] = cy * cp
    out[0, 1] = cy * sp * sr - sy * cr
    out[0, 2] = cy * sp * cr + sy * sr
    out[1, 0] = sy * cp
    out[1, 1] = sy * sp * sr + cy * cr
    out[1, 2] = sy * sp * cr - cy * sr
    out[2, 0] = -sp
    out[2, 1] = cp * sr
    out[2, 2] = cp * cr


@compiled
def foot_in_root(
    geometry: KernelGeometry,
    design: int,
    leg: int,
    rotation: ArrayF,
    tx: float,
    ty: float,
    tz: float,
) -> tuple[float, float, float]:  # pragma: no cover - compiled
    """A leg's foothold in its root frame, R_rᵀ(Rᵀ(f − t) − p_r), for the body at (R, t) [m]."""
    foothold, root = geometry.footholds[design, leg], geometry.root_positions[leg]
    fx, fy, fz = foothold[0] - tx, foothold[1] - ty, foothold[2] - tz
    bx = fx * rotation[0, 0] + fy * rotation[1, 0] + fz * rotation[2, 0] - root[0]
    by = fx * rotation[0, 1] + fy * rotation[1, 1] + fz * rotation[2, 1] - root[1]
    bz = fx * rotation[0, 2] + fy * rotation[1, 2] + fz * rotation[2, 2] - root[2]
    frame = geometry.root_rotations[leg]
    px = bx * frame[0, 0] + by * frame[1, 0] + bz * frame[2, 0]
    py = bx * frame[0, 1] + by * frame[1, 1] + bz * frame[2, 1]
    pz = bx * frame[0, 2] + by * frame[1, 2] + bz * frame[2, 2]
    return px, py, pz


@compiled
def knee_down_angles(
    lengths: ArrayF, px: float, py: float, pz: float
) -> tuple[float, float, float, float, float]:  # pragma: no cover - compiled
    """θ1, θ2, θ3 [rad] of the knee-down IK (eq 8–9), and r², r [m², m].

    As ``kinematics.leg_plane`` and ``plane_solution``, clipped where out of reach.
    """
    l1, l2, l3 = lengths[0], lengths[1], lengths[2]
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
    return theta1, theta2, theta3, planar_x**2 + pz**2, r


@compiled
def leg_margins(
    geometry: KernelGeometry,
    design: int,
    leg: int,
    px: float,
    py: float,
    pz: float,
    out: ArrayF,
) -> None:  # pragma: no cover - compiled
    """Write one leg's reach (2) and joint (6) margins for its foothold at (px, py, pz)."""
    lengths = geometry.lengths[design]
    l2, l3 = lengths[1], lengths[2]
    theta1, theta2, theta3, r2, r = knee_down_angles(lengths, px, py, pz)
    if geometry.smooth:
        out[2 * leg] = (l2 + l3) ** 2 - r2
        out[2 * leg + 1] = r2 - (l2 - l3) ** 2
    else:
        out[2 * leg] = l2 + l3 - r
        out[2 * leg + 1] = r - abs(l2 - l3)
    lower, upper = geometry.lower, geometry.upper
    j = 2 * geometry.root_positions.shape[0] + 6 * leg
    out[j] = theta1 - lower[0]
    out[j + 1] = upper[0] - theta1
    out[j + 2] = theta2 - lower[1]
    out[j + 3] = upper[1] - theta2
    out[j + 4] = theta3 - lower[2]
    out[j + 5] = upper[2] - theta3
    if geometry.knee == COUPLED_FORM:
        out[j + 4] = theta3 - max(lower[2], -theta2 - math.pi / 2)
    elif geometry.knee == COSINE_FORM:
        cos_knee = (r2 - l2**2 - l3**2) / (2 * l2 * l3)
        out[j + 4] = cos_knee - math.cos(lower[2])
        out[j + 5] = math.cos(upper[2]) - cos_knee


@compiled
def ground_margins(
    geometry: KernelGeometry, tz: float, rotation: ArrayF, out: ArrayF
) -> None:  # pragma: no cover - compiled
    """Write the ground's margins after the legs' columns of ``out``.

    As ``StanceGeometry.lowest_body_height`` (exact) or ``smooth_ground_margins``.
    """
    g = 8 * geometry.root_positions.shape[0]
    half = geometry.half_extents
    tilt_x, tilt_y, tilt_z = rotation[2, 0], rotation[2, 1], rotation[2, 2]
    if geometry.round_body and not geometry.smooth:
        out[g] = tz - (half[0] * math.hypot(tilt_x, tilt_y) + half[2] * abs(tilt_z))
    elif not geometry.smooth:
        out[g] = tz - (abs(tilt_x) * half[0] + abs(tilt_y) * half[1] + abs(tilt_z) * half[2])
    elif geometry.round_body:
        centre = tz - half[2] * abs(tilt_z)
        out[g] = centre
        out[g + 1] = centre * abs(centre) - half[0] ** 2 * (tilt_x**2 + tilt_y**2)
    else:
        c = 0
        for sx in (-1.0, 1.0):
            for sy in (-1.0, 1.0):
                for sz in (-1.0, 1.0):
                    corner = tilt_x * sx * half[0] + tilt_y * sy * half[1]
                    out[g + c] = tz + (corner + tilt_z * sz * half[2])
                    c += 1
