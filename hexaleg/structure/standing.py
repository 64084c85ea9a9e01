"""The standing load cases of the legs' structure, and the structure checked under them.

The cases (:class:`StandingCases`): the nominal stance with the payload; each of the twelve
flexibility extremes (its pose), with the payload; and, when a slope is required, the
nominal stance on that slope uphill toward each of the statics' headings
(:data:`~hexaleg.statics.slopes.SLOPE_HEADINGS`, the body parallel to the ground), with
the payload. The feet's forces are the statics' (:class:`~hexaleg.statics.forces.Statics`,
its distribution and friction); the legs' wrenches, stresses and deflections follow
(:mod:`.wrenches`, :mod:`.deflection`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from hexaleg._typing import ArrayF, Distribution
from hexaleg.exceptions import ParameterError
from hexaleg.gravity import LEVEL_GRAVITY, slope_gravity
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.configurations import extreme_configurations
from hexaleg.stance.extremes import Extreme
from hexaleg.statics.forces import (
    DEFAULT_FRICTION,
    Payload,
    Statics,
    equilibrium,
    min_norm_forces,
)
from hexaleg.statics.slopes import SLOPE_HEADINGS
from hexaleg.structure.check import StructureCheck
from hexaleg.structure.deflection import deflection_integrals, foot_deflections
from hexaleg.structure.wrenches import LegStates, leg_states, require_template, segment_wrenches

NOMINAL = "nominal"
"""The first standing case: the nominal stance."""


@dataclass(frozen=True, eq=False)
class StandingCases:
    """The poses and gravities a standing structure is checked in.

    Attributes:
        names: Each case's name (K): ``"nominal"``, an extreme's (``"x+"``), or a slope's.
        configurations: q (K, nq).
        gravities: Gravity in the ground frame (K, 3) [m/s²].
        legs: The stance legs.
        payload: The payload on the body.
        friction: Friction coefficient μ [-].
        distribution: How the feet share the load.

    """

    names: tuple[str, ...]
    configurations: ArrayF
    gravities: ArrayF
    legs: tuple[str, ...]
    payload: Payload
    friction: float = DEFAULT_FRICTION
    distribution: Distribution = "min-norm"


def slope_name(slope: float, heading: float) -> str:
    """A slope case's name: ``"slope 15° uphill at +90°"``."""
    return f"slope {math.degrees(slope):.4g}° uphill at {math.degrees(heading):+.0f}°"


def standing_cases(
    model: HexapodModel,
    legs: Sequence[str],
    extremes: Sequence[Extreme] = (),
    payload: Payload | None = None,
    slope: float = 0.0,
    friction: float = DEFAULT_FRICTION,
    distribution: Distribution = "min-norm",
) -> StandingCases:
    """The nominal stance, the extremes and, on a ``slope`` > 0 [rad], every heading."""
    if not 0 <= slope < math.pi / 2:
        raise ParameterError("slope", slope, "must lie in [0, π/2) [rad]")
    nominal = model.nominal_configuration()
    poses = (
        [nominal[None], extreme_configurations(model, extremes)] if extremes else [nominal[None]]
    )
    headings = SLOPE_HEADINGS if slope > 0 else ()
    q = np.concatenate([*poses, np.tile(nominal, (len(headings), 1))])
    gravities = [LEVEL_GRAVITY] * (1 + len(extremes)) + [slope_gravity(slope, h) for h in headings]
    names = (NOMINAL, *(e.name for e in extremes), *(slope_name(slope, h) for h in headings))
    return StandingCases(
        names, q, np.array(gravities), tuple(legs), payload or Payload(), friction, distribution
    )


def standing_forces(
    model: HexapodModel, cases: StandingCases, states: LegStates | None = None
) -> ArrayF:
    """Every foot's force from the ground in each case (K, 6, 3), world frame [N].

    The stance feet's forces balance the robot and its payload (the statics); a foot in
    the air carries none. ``states``: the legs in the cases, if already found.
    """
    if states is None:
        states = leg_states(model, cases.configurations, cases.gravities)
    return standing_balance(model, cases, states.feet)[0]


def standing_balance(
    model: HexapodModel, cases: StandingCases, feet: ArrayF
) -> tuple[ArrayF, ArrayF]:
    """Each case's feet's forces (K, 6, 3) [N] and centre of mass (K, 3) [m], world frame.

    They are the statics' (:class:`~hexaleg.statics.forces.Statics`). With the min-norm
    distribution the forces are its least-norm balance
    (:func:`~hexaleg.statics.forces.equilibrium`,
    :func:`~hexaleg.statics.forces.min_norm_forces`) of the feet (``feet``, (K, 6, 3) [m]:
    :attr:`~.wrenches.LegStates.feet`) about each case's centre of mass under its own
    gravity, all cases at once; with another, each case's statics.
    """
    statics = Statics(model, cases.legs, cases.payload, cases.friction)
    stance = [model.leg_names.index(leg) for leg in cases.legs]
    q, gravities = cases.configurations, cases.gravities
    forces = np.zeros((len(q), len(model.leg_names), 3))
    if cases.distribution == "min-norm":
        com = statics.centres_of_mass(q)
        rows = equilibrium(feet[:, stance], com, statics.mass, gravities)
        forces[:, stance] = min_norm_forces(*rows).reshape(len(q), -1, 3)
        return forces, com
    com = np.empty((len(q), 3))
    for k in range(len(q)):
        state = statics.state(q[k], cases.distribution, gravities[k])
        forces[k, stance], com[k] = state.foot_forces, state.com
    return forces, com


def standing_terms(model: HexapodModel, cases: StandingCases) -> tuple[ArrayF, ArrayF]:
    """Wrenches (K, 6, 3, 6) and deflection integrals (K, 6, 3, 3) of each case.

    What a tube's stress and its foot's deflection follow from, with the model's masses
    (:func:`~.wrenches.segment_wrenches`, :func:`~.deflection.deflection_integrals`).
    """
    require_template(model)
    states = leg_states(model, cases.configurations, cases.gravities)
    forces = standing_forces(model, cases, states)
    integrals = deflection_integrals(model.design, states, forces, cases.gravities)
    return segment_wrenches(states, forces), integrals


def check_standing(model: HexapodModel, cases: StandingCases) -> StructureCheck:
    """The model's structure (its design's ``[structure]``, every tube given) in each case."""
    design = model.design
    if design.structure is None:
        raise ParameterError("structure", None, "the design has no [structure] to check")
    require_template(model)
    wrenches, integrals = standing_terms(model, cases)
    deflections = np.linalg.norm(foot_deflections(integrals, design.structure), axis=-1)
    return StructureCheck(
        design.structure,
        design.lengths,
        model.leg_names,
        cases.names,
        wrenches,
        deflections,
        design.structure.limit(design.leg_length),
    )
