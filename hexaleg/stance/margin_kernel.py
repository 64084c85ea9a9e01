"""Stance margins of body poses, compiled: the one implementation of the margins.

A displacement d = (x, y, z [m], roll, pitch, yaw [rad]) moves the body from the nominal
stance (world frame, Pinocchio's rpy: :func:`rpy_matrix`). :func:`margins_of` gives, for
many displacements at once, the exact margins or the smooth ones (the forms a
gradient-based search needs), column for column as
:func:`~hexaleg.stance.constraints.stance_margins` documents them; the foothold in each
leg's root frame (:func:`foot_in_root`) goes to the leg's own kernel (:mod:`.leg_kernel`),
the body's tilt to the ground's margins (:func:`ground_margins`). The axis-locked search
asks for the poses of many designs of one body at once (a :class:`KernelGeometry` holds
each design's lengths, footholds and height; each pose names its design); the
free-coupled search (:mod:`.climb`) asks for one pose at a time through
:func:`pose_margins`. The tests hold it to margins written from their definitions.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF
from hexaleg.limits import JointLimits
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.stance.leg_kernel import LegSolution, leg_solution, reach_margins

THETA_FORM, COUPLED_FORM, COSINE_FORM = 0, 1, 2
"""How the knee's lower and upper margins are written (see ``stance_margins``): on θ3,
θ3 above the hip-coupled bound, or on cos θ3 (smooth margins only)."""


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
        legs: Each design's stance legs' parameters (D, N, 5): a1, l2, l3, h, e [m]
            (:attr:`StanceGeometry.leg_parameters`).
        root_positions: Leg-root origins (N, 3), body frame [m].
        root_rotations: Leg-root orientations (N, 3, 3), body frame.
        lower: Lower joint limits per stance leg (N, 3) [rad].
        upper: Upper joint limits per stance leg (N, 3) [rad].
        knee: :data:`THETA_FORM`, :data:`COUPLED_FORM` or :data:`COSINE_FORM`.
        round_body: The body is a cylinder about z (else a box).
        half_extents: The body's half sizes (3,) [m] (radius, radius, half height if round).
        smooth: Smooth margins (else exact ones).

    """

    heights: ArrayF
    footholds: ArrayF
    legs: ArrayF
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
    if template.leg_bounds is not None:  # a robot file's limits, one box per leg
        knee = COSINE_FORM if smooth and _cosine_knees(template) else THETA_FORM
    elif limits.coupled_knee:
        knee = COUPLED_FORM
    elif smooth and knee_on_cosine(limits):
        knee = COSINE_FORM
    else:
        knee = THETA_FORM
    return KernelGeometry(
        heights=np.array([g.nominal_height for g in geometries], dtype=float),
        footholds=np.ascontiguousarray([g.footholds for g in geometries], dtype=float),
        legs=np.ascontiguousarray([g.leg_parameters for g in geometries], dtype=float),
        root_positions=np.ascontiguousarray(template.root_positions, dtype=float),
        root_rotations=np.ascontiguousarray(template.root_rotations, dtype=float),
        lower=np.ascontiguousarray(template.joint_lower, dtype=float),
        upper=np.ascontiguousarray(template.joint_upper, dtype=float),
        knee=knee,
        round_body=bool(template.body_round),
        half_extents=np.ascontiguousarray(template.body_half_extents, dtype=float),
        smooth=smooth,
    )


def _cosine_knees(geometry: StanceGeometry) -> bool:
    """Whether every leg's knee limits lie within [−π, 0] (cos θ3 monotonic there)."""
    lower, upper = geometry.joint_lower[:, 2], geometry.joint_upper[:, 2]
    return bool(np.all((-math.pi <= lower) & (lower < upper) & (upper <= 0)))


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
    posed_margins(geometry, design, rotation, d[0], d[1], d[2] + geometry.heights[design], out)


@compiled
def posed_margins(
    geometry: KernelGeometry,
    design: int,
    rotation: ArrayF,
    tx: float,
    ty: float,
    tz: float,
    out: ArrayF,
) -> None:  # pragma: no cover - compiled
    """Write the margins of the body at rotation R (3, 3) and position t [m] into ``out``."""
    for index in range(geometry.root_positions.shape[0]):
        px, py, pz = foot_in_root(geometry, design, index, rotation, tx, ty, tz)
        leg = leg_solution(geometry.legs[design, index], px, py, pz)
        leg_margins(geometry, design, index, leg, out)
    ground_margins(geometry, tz, rotation, out)


@compiled
def margins_of_poses(
    geometry: KernelGeometry, rotations: ArrayF, translations: ArrayF
) -> ArrayF:  # pragma: no cover - compiled
    """Margins (P, C) of body poses, rotations (P, 3, 3) and positions (P, 3) [m], of design 0."""
    out = np.empty((rotations.shape[0], column_count(geometry)))
    for p in range(rotations.shape[0]):
        t = translations[p]
        posed_margins(geometry, 0, rotations[p], t[0], t[1], t[2], out[p])
    return out


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
def leg_margins(
    geometry: KernelGeometry, design: int, index: int, leg: LegSolution, out: ArrayF
) -> None:  # pragma: no cover - compiled
    """Write one leg's reach (2) and joint (6) margins, given its IK (:func:`.leg_solution`)."""
    out[2 * index], out[2 * index + 1] = reach_margins(
        geometry.legs[design, index], leg, geometry.smooth
    )
    lower, upper = geometry.lower[index], geometry.upper[index]
    j = 2 * geometry.root_positions.shape[0] + 6 * index
    out[j] = leg.theta1 - lower[0]
    out[j + 1] = upper[0] - leg.theta1
    out[j + 2] = leg.theta2 - lower[1]
    out[j + 3] = upper[1] - leg.theta2
    out[j + 4] = leg.theta3 - lower[2]
    out[j + 5] = upper[2] - leg.theta3
    if geometry.knee == COUPLED_FORM:
        out[j + 4] = leg.theta3 - max(lower[2], -leg.theta2 - math.pi / 2)
    elif geometry.knee == COSINE_FORM:
        out[j + 4] = leg.cos_knee - math.cos(lower[2])
        out[j + 5] = math.cos(upper[2]) - leg.cos_knee


@compiled
def ground_margins(
    geometry: KernelGeometry, tz: float, rotation: ArrayF, out: ArrayF
) -> None:  # pragma: no cover - compiled
    """Write the ground's margins after the legs' columns of ``out``.

    Exact: the body's lowest point's height (``StanceGeometry.lowest_body_height``) [m];
    smooth: the forms ``stance_margins`` documents.
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
