"""The leg's foot Jacobian (eq 22) in closed form: J⁻¹·ṗ, Jᵀ·f and J̇·θ̇ from one set of partials.

With R = l1 + l2·cos θ2 + l3·cos(θ2+θ3) the foot's reach along the coxa and
Z = h + l2·sin θ2 + l3·sin(θ2+θ3) its height (eq 7; a general leg's hip height h and
lateral offset e, :mod:`hexaleg.leg_geometry`), the foot is
p = Rz(θ1)·(R, e, Z) in the leg-root frame. In the coxa's turning axes (radial, across, up)
J = [(−e, R, 0) | (R_θ, 0, Z_θ)] for θ = θ2, θ3: across the coxa only the root moves the
foot; along it and up, hip and knee form a 2×2 system of determinant l2·l3·sin θ3 (the
root's share −e·θ̇1 moved to the right-hand side). :func:`leg_partials` evaluates the
trigonometry once for every product a gait needs, for one leg or for six different legs
side by side (:data:`~hexaleg.leg_geometry.LegRows`); the tests hold each product against
:func:`hexaleg.kinematics.foot_jacobian` and finite differences.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF, Lengths
from hexaleg.leg_geometry import Dimension, LegRows, leg_parameters


class LegPartials(NamedTuple):
    """Trigonometry and partial derivatives of eq 7 at joint angles (...,) each.

    Attributes:
        c1, s1: cos θ1, sin θ1.
        c2, s2, c23, s23: cos and sin of θ2 and of θ2 + θ3.
        reach: R [m].
        r2, r3: ∂R/∂θ2, ∂R/∂θ3 [m/rad].
        z2, z3: ∂Z/∂θ2, ∂Z/∂θ3 [m/rad].
        l2, l3: Femur and tibia lengths [m] (one per leg for legs side by side).
        lateral: The foot's lateral offset e [m] (likewise).

    """

    c1: ArrayF
    s1: ArrayF
    c2: ArrayF
    s2: ArrayF
    c23: ArrayF
    s23: ArrayF
    reach: ArrayF
    r2: ArrayF
    r3: ArrayF
    z2: ArrayF
    z3: ArrayF
    l2: Dimension
    l3: Dimension
    lateral: Dimension = 0.0


def leg_partials(leg: Lengths | LegRows, theta: npt.ArrayLike) -> LegPartials:
    """The partials of eq 7 at joint angles θ (..., 3) [rad].

    Args:
        leg: The paper's segment lengths (l1, l2, l3) [m], or legs side by side (the
            angles' leg axis the one before the last).
        theta: Joint angles (..., 3) [rad].

    """
    l1, l2, l3, _, lateral = leg_parameters(leg)
    theta = np.asarray(theta, dtype=float)
    t2, t23 = theta[..., 1], theta[..., 1] + theta[..., 2]
    c2, s2, c23, s23 = np.cos(t2), np.sin(t2), np.cos(t23), np.sin(t23)
    return LegPartials(
        c1=np.cos(theta[..., 0]),
        s1=np.sin(theta[..., 0]),
        c2=c2,
        s2=s2,
        c23=c23,
        s23=s23,
        reach=l1 + l2 * c2 + l3 * c23,
        r2=-l2 * s2 - l3 * s23,
        r3=-l3 * s23,
        z2=l2 * c2 + l3 * c23,
        z3=l3 * c23,
        l2=l2,
        l3=l3,
        lateral=lateral,
    )


def inverse_times(leg: LegPartials, rhs: npt.ArrayLike) -> ArrayF:
    """J⁻¹·ṗ (..., 3): the joint rates [rad/s] that move the foot at ṗ [m/s], leg-root frame.

    Singular where R = 0 (the foot on the root's axis) or sin θ3 = 0 (a straight knee):
    the rates there are infinite or NaN.
    """
    rhs = np.asarray(rhs, dtype=float)
    radial = leg.c1 * rhs[..., 0] + leg.s1 * rhs[..., 1]
    across = -leg.s1 * rhs[..., 0] + leg.c1 * rhs[..., 1]
    det = leg.r2 * leg.z3 - leg.r3 * leg.z2
    rates = np.empty((*np.broadcast_shapes(np.shape(leg.c1), rhs.shape[:-1]), 3))
    with np.errstate(divide="ignore", invalid="ignore"):
        rates[..., 0] = root = across / leg.reach
        radial = radial + leg.lateral * root  # what the hip and knee move along the coxa
        rates[..., 1] = (leg.z3 * radial - leg.r3 * rhs[..., 2]) / det
        rates[..., 2] = (leg.r2 * rhs[..., 2] - leg.z2 * radial) / det
    return rates


def transpose_times(leg: LegPartials, force: npt.ArrayLike) -> ArrayF:
    """Jᵀ·f (..., 3): the joint torques [N·m] a force f [N] at the foot (leg-root frame) makes."""
    force = np.asarray(force, dtype=float)
    radial = leg.c1 * force[..., 0] + leg.s1 * force[..., 1]
    across = -leg.s1 * force[..., 0] + leg.c1 * force[..., 1]
    torques = np.empty((*np.broadcast_shapes(np.shape(leg.c1), force.shape[:-1]), 3))
    torques[..., 0] = leg.reach * across - leg.lateral * radial
    torques[..., 1] = leg.r2 * radial + leg.z2 * force[..., 2]
    torques[..., 2] = leg.r3 * radial + leg.z3 * force[..., 2]
    return torques


def rate_times(leg: LegPartials, rates: npt.ArrayLike) -> ArrayF:
    """J̇·θ̇ (..., 3) in the leg-root frame: the foot's acceleration at θ̈ = 0 [m/s²].

    The leg plane's centripetal terms are R_q = −(l2 cos θ2·ω2² + l3 cos θ23·ω23²) and
    Z_q = −(l2 sin θ2·ω2² + l3 sin θ23·ω23²) (ω23 = ω2 + ω3); the root's turn adds −R·ω1²
    (centripetal) along the coxa and 2·Ṙ·ω1 (Coriolis) across it, and a lateral offset e
    its own centripetal −e·ω1² across it.
    """
    rates = np.asarray(rates, dtype=float)
    w1, w2, w23 = rates[..., 0], rates[..., 1], rates[..., 1] + rates[..., 2]
    with np.errstate(invalid="ignore"):  # infinite rates of a straight leg
        reach_rate = leg.r2 * w2 + leg.r3 * rates[..., 2]
        reach_q = -(leg.l2 * leg.c2 * w2**2 + leg.l3 * leg.c23 * w23**2)
        height_q = -(leg.l2 * leg.s2 * w2**2 + leg.l3 * leg.s23 * w23**2)
        radial = reach_q - leg.reach * w1**2
        across = 2 * reach_rate * w1 - leg.lateral * w1**2
        acceleration = np.empty((*np.broadcast_shapes(np.shape(leg.c1), rates.shape[:-1]), 3))
        acceleration[..., 0] = leg.c1 * radial - leg.s1 * across
        acceleration[..., 1] = leg.s1 * radial + leg.c1 * across
        acceleration[..., 2] = height_q
        return acceleration
