"""How far a standing foot deflects: Euler–Bernoulli bending of the three segments as a chain.

The model: each segment is a straight Euler–Bernoulli beam along its joint-to-joint line,
of bending stiffness E·I (its tube's); the joints are rigid (the actuators hold them) and
the body does not move; axial stretch, torsion and shear deformation are left out. The
loads are those of a standing pose: the foot's force from the ground and the foot's
weight at the foot, the actuators' weights at their joints (the hip's at the coxa's end,
the knee's at the femur's end) and each segment's own weight spread along it.

The foot's deflection follows from the unit-load method (virtual work): along direction u,

    δ·u = Σ_segments ∫₀ˡ M(s)·m_u(s) / (E·I) ds,

with M(s) the bending moment at the section s along a segment (the moment of every load
beyond it, about the section, its part across the axis) and m_u(s) = (p_foot − x(s)) × u
the moment of a unit force u at the foot. Both are polynomials in s of degree at most
two and one, so Simpson's rule on each segment is exact. The integrals are kept per
segment without E·I (:func:`deflection_integrals`), so that a tube's stiffness divides
them afterwards (:func:`foot_deflections`): a cantilever of length L loaded F at its tip
gives F·L³/(3·E·I).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.design import FOOT_MASS, HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.leg_structure import Structure, segment_masses
from hexaleg.numerics.vectors import cross
from hexaleg.structure.wrenches import LegStates

SIMPSON = np.array([1.0, 4.0, 1.0]) / 6
"""Simpson's weights at s = 0, l/2, l, times the segment's length."""
SIMPSON_POINTS = np.array([0.0, 0.5, 1.0])
"""Where Simpson's rule samples a segment, over its length."""


def deflection_integrals(
    design: HexapodDesign,
    states: LegStates,
    foot_forces: npt.ArrayLike,
    gravity: npt.ArrayLike,
) -> ArrayF:
    """∫ M × (p_foot − x) ds over each segment (K, 6, 3, 3), world frame [N·m³].

    Divided by a segment's E·I [N·m²] it is that segment's share of the foot's deflection
    vector [m] (:func:`foot_deflections`).

    Args:
        design: The design: its segments' lengths and masses, its actuators' masses.
        states: The legs in K standing poses (:func:`~.wrenches.leg_states`).
        foot_forces: Each leg's foot force from the ground (K, 6, 3), world frame [N].
        gravity: Gravitational acceleration (K, 3) or (3,), world frame [m/s²].

    """
    masses = segment_masses(design.structure, design.lengths, design.link_linear_density)
    return chain_integrals(
        design.lengths, masses, point_masses(design), states, foot_forces, gravity
    )


def point_masses(design: HexapodDesign) -> tuple[float, float, float]:
    """The masses at the hip (its actuator), the knee (its actuator) and the foot [kg]."""
    hip, knee = (0.0, 0.0) if design.actuators is None else design.actuators.masses[1:]
    return (hip, knee, FOOT_MASS)


def chain_integrals(
    lengths: tuple[float, float, float],
    masses: npt.ArrayLike,
    points: npt.ArrayLike,
    states: LegStates,
    foot_forces: npt.ArrayLike,
    gravity: npt.ArrayLike,
) -> ArrayF:
    """:func:`deflection_integrals` of given masses: linear in (masses, points, foot_forces).

    Args:
        lengths: The segments' lengths (l1, l2, l3) [m].
        masses: The segments' own masses, spread along them (..., 3) [kg]: leading axes
            (B...) give as many sets of loads at once.
        points: The point masses at the hip, the knee and the foot (..., 3) [kg], likewise.
        states: The legs in K standing poses.
        foot_forces: Each leg's foot force from the ground (B..., K, 6, 3), world frame [N].
        gravity: Gravitational acceleration (K, 3) or (3,), world frame [m/s²].

    Returns:
        The integrals (B..., K, 6, 3, 3) [N·m³].

    """
    origins, axes, feet = states.origins, states.axes, states.feet
    g = np.broadcast_to(np.asarray(gravity, dtype=float), (len(feet), 3))[:, None, :]
    length = np.array(lengths)
    mass, point_mass = np.asarray(masses, dtype=float), np.asarray(points, dtype=float)
    batch = np.broadcast_shapes(mass.shape[:-1], point_mass.shape[:-1])

    def weight(values: ArrayF, i: int) -> ArrayF:  # (B..., 1, 1, 1) times g: (B..., K, 1, 3)
        return np.broadcast_to(values[..., i], batch).reshape(*batch, 1, 1, 1) * g

    foot_force = np.asarray(foot_forces, dtype=float) + weight(point_mass, 2)
    # the loads beyond each segment's end: (position, force) of each, (K, 6, 3) both; one
    # row per segment (coxa, femur, tibia), laid out as the chain is (fmt: skip below)
    middle = origins + axes * (length / 2)[:, None]
    femur, tibia = weight(mass, 1), weight(mass, 2)
    hip, knee = weight(point_mass, 0), weight(point_mass, 1)
    beyond = [
        [(middle[:, :, 1], femur), (origins[:, :, 1], hip), (middle[:, :, 2], tibia),
         (origins[:, :, 2], knee), (feet, foot_force)],
        [(middle[:, :, 2], tibia), (origins[:, :, 2], knee), (feet, foot_force)],
        [(feet, foot_force)],
    ]  # fmt: skip
    out = np.zeros((*batch, *feet.shape[:2], 3, 3))
    for k in range(3):
        axis, own = axes[:, :, k], weight(mass, k) / length[k]
        # the moment of the loads beyond about a point x: Σ p × F − x × Σ F
        about_origin, total = np.zeros(3), np.zeros(3)
        for position, force in beyond[k]:
            about_origin, total = about_origin + cross(position, force), total + force
        # Simpson's points s = 0, l/2, l along the segment, on a leading axis
        s = (length[k] * SIMPSON_POINTS).reshape(3, *(1,) * len(batch), 1, 1, 1)
        point = origins[:, :, k] + s * axis
        rest = length[k] - s  # the segment's own weight beyond s, at its middle
        moment = cross((rest / 2) * axis, rest * own) + about_origin - cross(point, total)
        across = moment - np.sum(moment * axis, axis=-1)[..., None] * axis
        out[..., k, :] = length[k] * np.tensordot(SIMPSON, cross(across, feet - point), axes=1)
    return out


def foot_deflections(integrals: npt.ArrayLike, structure: Structure) -> ArrayF:
    """Each foot's deflection vector (..., 3) [m] from :func:`deflection_integrals` (..., 3, 3).

    Raises:
        HexalegError: A segment of ``structure`` has no tube yet (it is to be sized).

    """
    moments = [tube.second_moment for tube in structure.tubes if tube is not None]
    if len(moments) != 3:
        raise HexalegError("the structure's tubes are not chosen yet: size them first")
    stiffness = structure.material.youngs_modulus * np.array(moments)
    return np.einsum("...kc,k->...c", np.asarray(integrals, dtype=float), 1.0 / stiffness)
