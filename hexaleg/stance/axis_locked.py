"""Axis-locked body flexibility: the paper's ADAMS study (§6) on the closed-form stance.

The body moves along one of x, y, z, roll, pitch, yaw from the nominal stance, the
other five held, until the first constraint breaks: a foot out of reach, a joint
past its stance limit, or the body touching the ground. All twelve directions are
searched at once by :func:`~hexaleg.stance.bracketing.first_crossings` on the
vectorized margins of :mod:`hexaleg.stance.constraints`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from hexaleg._typing import ArrayF, StanceSet
from hexaleg.design import HexapodDesign
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.bracketing import IndexArray, first_crossings
from hexaleg.stance.collisions import SelfCollision, collision_limited
from hexaleg.stance.constraints import (
    AXES,
    DIRECTIONS,
    TRANSLATIONS,
    Cause,
    constraint_labels,
    direction_poses,
    stance_margins,
)
from hexaleg.stance.extremes import Extreme, FlexibilityResult, pose_extremes
from hexaleg.stance.geometry import StanceGeometry


def search_ranges(geometry: StanceGeometry) -> ArrayF:
    """How far each direction is searched: 2L for translations, π for rotations."""
    leg_length = sum(geometry.lengths)
    return np.array([2 * leg_length if a in TRANSLATIONS else math.pi for a, _ in DIRECTIONS])


def axis_locked_extremes(geometry: StanceGeometry) -> tuple[Extreme, ...]:
    """The twelve axis-locked extremes of a stance geometry, with their causes."""
    axis_of = np.array([AXES.index(a) for a, _ in DIRECTIONS])
    sign_of = np.array([s for _, s in DIRECTIONS], dtype=float)

    def margins(direction: IndexArray, t: ArrayF) -> ArrayF:
        rotation, translation = direction_poses(
            geometry, axis_of[direction], sign_of[direction] * t
        )
        return stance_margins(geometry, rotation, translation)

    crossings = first_crossings(margins, search_ranges(geometry))
    labels = constraint_labels(geometry.legs)
    displacements = np.zeros((len(DIRECTIONS), len(AXES)))
    displacements[np.arange(len(DIRECTIONS)), axis_of] = sign_of * crossings.t
    directions = [
        (axis, sign, [labels[c] for c in crossings.binding[d]] or [Cause("range")])
        for d, (axis, sign) in enumerate(DIRECTIONS)
    ]
    return pose_extremes(geometry, directions, displacements)


def axis_locked_flexibility(
    design: HexapodDesign,
    stance: StanceSet | Sequence[str] = "all",
    model: HexapodModel | None = None,
    geometry: StanceGeometry | None = None,
    collisions: bool = False,
) -> FlexibilityResult:
    """Axis-locked flexibility of ``design`` (the ADAMS semantics).

    Args:
        design: The design.
        stance: ``"all"``, ``"tripod"`` or a list of stance legs.
        model: Its Pinocchio model, if already built.
        geometry: A template geometry of the same body and mounts (fast path for
            sweeps: the design's legs replace the template's by :meth:`StanceGeometry.with_design`).
        collisions: Also stop where two of the robot's own parts touch (coal).

    """
    if geometry is None:
        model = HexapodModel(design) if model is None else model
        geometry = StanceGeometry.from_model(model, stance)
    else:
        geometry = geometry.with_design(design)
    extremes = axis_locked_extremes(geometry)
    if collisions:
        model = HexapodModel(design) if model is None else model
        extremes = collision_limited(geometry, SelfCollision(model, geometry), extremes)
    return FlexibilityResult(design, geometry.legs, "axis", extremes, collisions=collisions)
