"""The standing loads as affine functions of the three segments' masses.

A segment's tube is uniform and centred mid-segment whatever its diameter and wall, so its
mass m_s enters the standing cases only as a weight m_s·g at the segment's middle on every
leg. Each joint's wrench from the links beyond it (:attr:`~.wrenches.LegStates.own`) is
then affine in (m_coxa, m_femur, m_tibia); so is the robot's weight and its moment, and the
minimum-norm feet forces (:func:`~hexaleg.statics.forces.min_norm_forces`: the least Σ|f|²
balancing them, linear in the equilibrium's right-hand side, whose rows about the centre of
mass c of the masses given are those about any other point, row-combined); so are the
wrenches at the segments' joints (:func:`~.wrenches.segment_wrenches`: the own wrench less
the foot's) and the deflection integrals (:func:`~.deflection.chain_integrals`, linear in
the masses and the foot's force).

:func:`affine_terms` measures them once, at the model's own masses, with their exact
derivatives (no difference quotient): one kilogram more at each segment's middle adds −g
and its moment to the wrenches (:func:`~.wrenches.weight_wrenches`) and changes the feet's
forces by the least-norm solution of the equilibrium with the right-hand side
(−n·g, −Σ_legs (p_middle − c) × g), n the legs. :meth:`AffineTerms.at` gives the terms of
any masses without a new Pinocchio model; hexaleg's tests hold them to the full computation
(:func:`~.standing.standing_terms` of a model with those tubes) on seeded random designs.
Another distribution (min-torque: a QP with friction) is not linear: it has none.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.exceptions import ParameterError
from hexaleg.leg_structure import segment_masses
from hexaleg.robot.model import HexapodModel
from hexaleg.statics.forces import equilibrium, min_norm_forces
from hexaleg.structure.deflection import chain_integrals, point_masses
from hexaleg.structure.standing import StandingCases, standing_balance
from hexaleg.structure.wrenches import (
    LegStates,
    leg_states,
    require_template,
    segment_wrenches,
    weight_wrenches,
)

UNIT_MASSES = np.eye(3)
"""One kilogram at each segment in turn (coxa, femur, tibia) [kg]."""


@dataclass(frozen=True, eq=False)
class AffineTerms:
    """The standing cases' wrenches and deflection integrals, affine in the segments' masses.

    Attributes:
        masses: The masses (coxa, femur, tibia) they were measured at (3,) [kg].
        wrenches: The wrenches there (K, 6, 3, 6) [N, N·m] (:func:`~.standing.standing_terms`).
        integrals: The deflection integrals there (K, 6, 3, 3) [N·m³].
        wrench_slopes: Their change per kilogram of each segment (3, K, 6, 3, 6) [N/kg, m·N/kg].
        integral_slopes: Likewise (3, K, 6, 3, 3) [N·m³/kg].

    """

    masses: ArrayF
    wrenches: ArrayF
    integrals: ArrayF
    wrench_slopes: ArrayF
    integral_slopes: ArrayF

    def at(self, masses: npt.ArrayLike) -> tuple[ArrayF, ArrayF]:
        """The wrenches and deflection integrals with these segment masses (3,) [kg]."""
        extra = np.asarray(masses, dtype=float) - self.masses
        return (
            self.wrenches + np.tensordot(extra, self.wrench_slopes, axes=1),
            self.integrals + np.tensordot(extra, self.integral_slopes, axes=1),
        )


def affine_terms(model: HexapodModel, cases: StandingCases) -> AffineTerms:
    """The standing terms of ``cases`` at ``model``'s masses and their derivatives by them.

    Raises:
        ParameterError: The cases' distribution is not ``"min-norm"`` (not linear), or the
            model is not hexaleg's template.

    """
    if cases.distribution != "min-norm":
        raise ParameterError(
            "distribution", cases.distribution, "min-norm only: the others are not linear"
        )
    require_template(model)
    design = model.design
    states = leg_states(model, cases.configurations, cases.gravities)
    forces, com = standing_balance(model, cases, states.feet)
    slopes = _force_slopes(model, cases, states, com)  # (3, K, 6, 3)
    weights = weight_wrenches(states, design.lengths, cases.gravities)
    masses = segment_masses(design.structure, design.lengths, design.link_linear_density)
    integrals = chain_integrals(  # at the masses, then per kilogram of each segment
        design.lengths,
        np.vstack([masses, UNIT_MASSES]),
        np.vstack([point_masses(design), np.zeros((3, 3))]),
        states,
        np.concatenate([forces[None], slopes]),
        cases.gravities,
    )
    return AffineTerms(
        np.array(masses),
        segment_wrenches(states, forces),
        integrals[0],
        np.stack([segment_wrenches(replace(states, own=weights[s]), slopes[s]) for s in range(3)]),
        integrals[1:],
    )


def _force_slopes(
    model: HexapodModel, cases: StandingCases, states: LegStates, com: ArrayF
) -> ArrayF:
    """The feet's forces' change per kilogram of each segment (3, K, 6, 3) [N/kg].

    Every leg's segment s gains the kilogram at its middle: the weight grows by n·g and
    its moment about the centre of mass c (K, 3) by Σ_legs (p_middle − c) × g.
    """
    stance = [model.leg_names.index(leg) for leg in cases.legs]
    rows, _ = equilibrium(states.feet[:, stance], com, 1.0, cases.gravities)  # (K, 6, 3N)
    g, lengths = cases.gravities, model.design.lengths  # (K, 3), [m]
    rhs = np.empty((len(com), 6, 3))
    for s in range(3):
        middle = states.origins[:, :, s] + states.axes[:, :, s] * (lengths[s] / 2)
        arms = (middle - com[:, None, :]).sum(axis=1)  # (K, 3)
        rhs[:, :3, s] = -len(model.leg_names) * g
        rhs[:, 3:, s] = -np.cross(arms, g)
    solved = min_norm_forces(rows, rhs)  # (K, 3N, 3)
    out = np.zeros((3, len(com), len(model.leg_names), 3))
    out[:, :, stance] = solved.reshape(len(com), len(stance), 3, 3).transpose(3, 0, 1, 2)
    return out
