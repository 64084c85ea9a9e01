"""The leg in the compiled stance kernels: its knee-down IK (eq 8–9), its reach, their derivatives.

Everything the stance kernels (:mod:`.margin_kernel`, :mod:`.margin_jacobian`) know of
the leg's geometry is here; they pass each leg's parameters (``KernelGeometry.legs``: a1,
l2, l3, and a general leg's hip height h and lateral offset e [m]) and its foothold
p = (px, py, pz) in the leg-root frame [m]
and read back angles, reach margins and derivatives. :func:`leg_solution` turns p toward
the root angle θ1 and into the leg plane, then solves the hip and knee by the law of
cosines; :func:`reach_margins` bounds the hip-to-foot distance r by the annulus
|l2 − l3| ≤ r ≤ l2 + l3; :func:`leg_derivatives` gives the derivatives of the angles and
of r² along a foothold velocity. The NumPy form of the same IK is
:func:`hexaleg.kinematics.leg_plane` and :func:`~hexaleg.kinematics.plane_solution`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF


class LegSolution(NamedTuple):
    """The knee-down IK of one foothold, and what the margins and their derivatives reuse.

    Attributes:
        theta1: Root angle θ1 ∈ (−π/2, π/2] [rad].
        theta2: Hip angle θ2 ∈ (−π, π] [rad], clipped where out of reach.
        theta3: Knee angle θ3 ≤ 0 [rad], clipped where out of reach.
        c1: cos θ1 [-].
        s1: sin θ1 [-].
        planar_x: Hip to foothold along the coxa [m].
        r2: Hip-to-foothold distance squared, planar_x² + pz² [m²].
        r: Hip-to-foothold distance [m].
        cos_knee: cos θ3 = (r² − l2² − l3²)/(2·l2·l3) from ``r2``, unclipped [-].

    """

    theta1: float
    theta2: float
    theta3: float
    c1: float
    s1: float
    planar_x: float
    r2: float
    r: float
    cos_knee: float


@compiled
def leg_solution(
    lengths: ArrayF, px: float, py: float, pz: float
) -> LegSolution:  # pragma: no cover - compiled; tested against hexaleg.kinematics
    """The knee-down IK (eq 8–9) of the foothold (px, py, pz) [m] in the leg-root frame.

    As ``kinematics.leg_plane`` and ``plane_solution``: the angles of the nearest
    configuration where the foothold is out of reach. ``lengths`` is (a1, l2, l3) or a
    general leg's (a1, l2, l3, h, e), whose hip axis lies h above the root.
    """
    l1, l2, l3 = lengths[0], lengths[1], lengths[2]
    h, e = (lengths[3], lengths[4]) if lengths.shape[0] > 3 else (0.0, 0.0)
    if e == 0.0:
        theta1 = math.atan2(py, px)
        if theta1 > math.pi / 2:
            theta1 -= math.pi
        if theta1 <= -math.pi / 2:
            theta1 += math.pi
    else:
        theta1 = lateral_root_angle(e, px, py)
    c1, s1 = math.cos(theta1), math.sin(theta1)
    planar_x = px * c1 + py * s1 - l1
    pz = pz - h
    r = math.hypot(planar_x, pz)
    r_safe = r if r > 0 else 1.0
    cos_hip = min(max((r**2 + l2**2 - l3**2) / (2 * l2 * r_safe), -1.0), 1.0)
    hip = math.atan2(pz, planar_x) + math.acos(cos_hip)
    theta2 = math.pi - (math.pi - hip) % (2 * math.pi)
    theta3 = -math.acos(min(max((r**2 - l2**2 - l3**2) / (2 * l2 * l3), -1.0), 1.0))
    r2 = planar_x**2 + pz**2
    cos_knee = (r2 - l2**2 - l3**2) / (2 * l2 * l3)
    return LegSolution(theta1, theta2, theta3, c1, s1, planar_x, r2, r, cos_knee)


@compiled
def lateral_root_angle(e: float, px: float, py: float) -> float:  # pragma: no cover - compiled
    """θ1 of a leg whose foot lies e [m] off its plane, as ``kinematics.leg_plane`` turns it."""
    turn = math.atan2(e, math.sqrt(max(px * px + py * py - e * e, 0.0)))
    theta1 = math.atan2(py, px) - turn
    if theta1 > math.pi:
        theta1 -= 2 * math.pi
    if theta1 <= -math.pi:
        theta1 += 2 * math.pi
    other = theta1 + 2 * turn
    other = other - math.pi if other > 0 else other + math.pi
    front = -math.pi / 2 < theta1 <= math.pi / 2
    if front or other <= -math.pi / 2 or other > math.pi / 2:
        return theta1
    return other


@compiled
def reach_margins(
    lengths: ArrayF, leg: LegSolution, smooth: bool
) -> tuple[float, float]:  # pragma: no cover - compiled
    """The outer and inner reach margins: l2 + l3 − r, r − |l2 − l3| [m].

    Smooth: (l2 + l3)² − r², r² − (l2 − l3)² [m²], the same zero sets without the
    square root's kink at r = 0.
    """
    l2, l3 = lengths[1], lengths[2]
    if smooth:
        return (l2 + l3) ** 2 - leg.r2, leg.r2 - (l2 - l3) ** 2
    return l2 + l3 - leg.r, leg.r - abs(l2 - l3)


@compiled
def leg_derivatives(
    lengths: ArrayF,
    leg: LegSolution,
    px: float,
    py: float,
    pz: float,
    dx: float,
    dy: float,
    dz: float,
) -> tuple[float, float, float, float, float]:  # pragma: no cover - compiled
    """Derivatives of θ1, θ2, θ3 [rad], r² [m²] and cos θ3 [-] along the foothold velocity dp.

    Where the IK is clipped (out of reach) the clipped angles' derivatives are zero, as a
    difference quotient sees them. The smooth reach margins change by −d(r²) and d(r²).
    A general leg's θ1 keeps the foot e off the leg plane, −px·s1 + py·c1 = e, so
    dθ1 = (c1·dy − s1·dx)/(px·c1 + py·s1); its hip lies h above the root.
    """
    l2, l3 = lengths[1], lengths[2]
    h, e = (lengths[3], lengths[4]) if lengths.shape[0] > 3 else (0.0, 0.0)
    planar_x, r2, r = leg.planar_x, leg.r2, leg.r
    pz = pz - h
    r_safe = r if r > 0 else 1.0
    hip_cos = (r2 + l2**2 - l3**2) / (2 * l2 * r_safe)
    radial = px * leg.c1 + py * leg.s1
    d_theta1 = (leg.c1 * dy - leg.s1 * dx) / radial if radial != 0 else 0.0
    d_planar = leg.c1 * dx + leg.s1 * dy + e * d_theta1
    d_r2 = 2 * (planar_x * d_planar + pz * dz)
    d_knee_cos = d_r2 / (2 * l2 * l3)
    knee_cos = leg.cos_knee
    d_theta3 = d_knee_cos / math.sqrt(1 - knee_cos**2) if abs(knee_cos) < 1 else 0.0
    d_hip_cos = d_r2 / (2 * l2 * r_safe) - hip_cos * d_r2 / (2 * r_safe**2)
    d_theta2 = (planar_x * dz - pz * d_planar) / r2 if r2 > 0 else 0.0
    if abs(hip_cos) < 1:
        d_theta2 -= d_hip_cos / math.sqrt(1 - hip_cos**2)
    return d_theta1, d_theta2, d_theta3, d_r2, d_knee_cos
