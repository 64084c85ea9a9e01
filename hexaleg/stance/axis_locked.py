"""Axis-locked body flexibility: the paper's ADAMS study (§6) on the closed-form stance.

The body moves along one of x, y, z, roll, pitch, yaw from the nominal stance, the
other five held, until the first constraint breaks: a foot out of reach, a joint
past its stance limit, or the body touching the ground. All twelve directions are
searched at once by :func:`~hexaleg.numerics.bracketing.first_crossings` on the
exact margins of the compiled kernel (:mod:`hexaleg.stance.margin_kernel`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from hexaleg._typing import ArrayF, StanceSet
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.numerics.bracketing import IndexArray, StartBroken, first_crossings
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.collisions import SelfCollision, collision_limited
from hexaleg.stance.constraints import (
    AXES,
    DIRECTIONS,
    TRANSLATIONS,
    Cause,
    broken_at_nominal,
    constraint_labels,
)
from hexaleg.stance.extremes import Extreme, FlexibilityResult, pose_extremes
from hexaleg.stance.geometry import StanceGeometry, needed_model
from hexaleg.stance.margin_kernel import kernel_geometry, margins_of


def search_ranges(geometry: StanceGeometry) -> ArrayF:
    """How far each direction is searched: 2L for translations, π for rotations."""
    leg_length = sum(geometry.lengths)
    return np.array([2 * leg_length if a in TRANSLATIONS else math.pi for a, _ in DIRECTIONS])


def axis_locked_extremes(geometry: StanceGeometry) -> tuple[Extreme, ...]:
    """The twelve axis-locked extremes of a stance geometry, with their causes."""
    return axis_locked_extremes_many([geometry])[0]


def axis_locked_extremes_many(
    geometries: Sequence[StanceGeometry],
) -> list[tuple[Extreme, ...]]:
    """The twelve axis-locked extremes of each of many stances in one vectorized search.

    The stances must share their body, mounts, stance legs and limits (as the designs of
    a sweep do: :meth:`StanceGeometry.with_design` of one template) and may differ in
    segment lengths, footholds and height: those become per-direction arrays, so the
    numerical work grows with the number of designs and the call overhead does not.
    One geometry alone is :func:`axis_locked_extremes`.
    """
    count = len(DIRECTIONS)
    kernel = kernel_geometry(geometries, smooth=False)
    design_of = np.repeat(np.arange(len(geometries)), count)
    axis_of = np.tile([AXES.index(a) for a, _ in DIRECTIONS], len(geometries))
    sign_of = np.tile([float(s) for _, s in DIRECTIONS], len(geometries))

    def margins(direction: IndexArray, t: ArrayF) -> ArrayF:
        displacements = np.zeros((len(direction), len(AXES)))
        displacements[np.arange(len(direction)), axis_of[direction]] = sign_of[direction] * t
        return margins_of(kernel, displacements, design_of[direction])

    t_max = np.concatenate([search_ranges(g) for g in geometries])
    labels = constraint_labels(geometries[0].legs)
    try:
        crossings = first_crossings(margins, t_max)
    except StartBroken as err:  # say what, where, and by how much
        which = broken_at_nominal(
            geometries[err.direction // count], labels[err.column], err.margin
        )
        raise HexalegError(f"the nominal stance breaks a stance constraint: {which}") from None
    results = []
    for i, geometry in enumerate(geometries):
        mine = range(i * count, (i + 1) * count)
        displacements = np.zeros((count, len(AXES)))
        displacements[np.arange(count), axis_of[mine]] = sign_of[mine] * crossings.t[mine]
        directions = [
            (axis, sign, [labels[c] for c in crossings.binding[d]] or [Cause("range")])
            for d, (axis, sign) in zip(mine, DIRECTIONS, strict=True)
        ]
        results.append(pose_extremes(geometry, directions, displacements))
    return results


def axis_locked_flexibility(
    design: HexapodDesign,
    stance: StanceSet | Sequence[str] = "all",
    model: HexapodModel | None = None,
    *,
    geometry: StanceGeometry | None = None,
    collisions: bool = False,
) -> FlexibilityResult:
    """Axis-locked flexibility of ``design`` (the ADAMS semantics).

    Args:
        design: The design.
        stance: ``"all"``, ``"tripod"`` or a list of stance legs.
        model: Its Pinocchio model, if already built (else built once, if needed).
        geometry: A template geometry of the same body and mounts (fast path for
            sweeps: the design's legs replace the template's by :meth:`StanceGeometry.with_design`).
        collisions: Also stop where two of the robot's own parts touch (coal).

    """
    model = needed_model(design, model, geometry, collisions)
    geometry = StanceGeometry.of_design(design, stance, model, geometry)
    extremes = axis_locked_extremes(geometry)
    return _result(design, geometry, extremes, model if collisions else None)


def axis_locked_flexibility_many(
    designs: Sequence[HexapodDesign],
    template: StanceGeometry,
    models: Sequence[HexapodModel],
    collisions: bool = False,
) -> list[FlexibilityResult]:
    """:func:`axis_locked_flexibility` of many designs of one body, searched together.

    Args:
        designs: Designs differing from ``template``'s only in their legs and posture.
        template: The stance geometry of their body, mounts and stance legs.
        models: Each design's Pinocchio model (used for collisions).
        collisions: Also stop where two of the robot's own parts touch (coal).

    """
    geometries = [template.with_design(design) for design in designs]
    return [
        _result(design, geometry, extremes, model if collisions else None)
        for design, geometry, extremes, model in zip(
            designs, geometries, axis_locked_extremes_many(geometries), models, strict=True
        )
    ]


def _result(
    design: HexapodDesign,
    geometry: StanceGeometry,
    extremes: tuple[Extreme, ...],
    collision_model: HexapodModel | None,
) -> FlexibilityResult:
    """The result of a design's axis-locked extremes, cut short by collisions on a given model."""
    collisions = collision_model is not None
    if collision_model is not None:
        collision = SelfCollision(collision_model, geometry)
        extremes = collision_limited(geometry, collision, extremes)
    return FlexibilityResult(design, geometry.legs, "axis", extremes, collisions=collisions)
