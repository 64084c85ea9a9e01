"""The steepest slope the robot stands on, per uphill heading: tip-over or sliding."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.cause import Cause
from hexaleg.gravity import GRAVITY
from hexaleg.statics.support import SupportPolygon

SLOPE_HEADINGS: tuple[float, ...] = (0.0, math.pi / 2, math.pi, -math.pi / 2)
"""Uphill headings of the slope study, in the body frame [rad]: ahead, left, behind, right."""


@dataclass(frozen=True)
class SlopeLimit:
    """The steepest slope the robot stands on, uphill toward one heading.

    Attributes:
        heading: Uphill direction in the body frame [rad] (0: straight ahead).
        max_slope: The slope angle α [rad].
        limited_by: Kind ``"tip"`` (the gravity line leaves the support polygon) or
            ``"slide"`` (tan α would exceed μ). A robot whose centre of mass already lies
            outside the polygon (or on its edge) tips on level ground: ``max_slope`` 0, ``"tip"``.

    """

    heading: float
    max_slope: float
    limited_by: Cause


def slope_limits(
    feet_xy: ArrayF | SupportPolygon,
    com: ArrayF,
    friction: float,
    headings: Sequence[float] = SLOPE_HEADINGS,
) -> tuple[SlopeLimit, ...]:
    """The max slope per heading: the smaller of the tip-over angle and atan μ.

    On a slope α uphill toward ψ (body parallel to the ground), gravity in the robot's
    ground frame is g·(−sin α cos ψ, −sin α sin ψ, −cos α): the gravity line through
    c meets the ground c_z·tan α downhill of c's footprint, and the robot tips when
    that point leaves the support polygon. A centre of mass whose footprint is not
    inside the polygon tips the robot over on level ground: 0 in every heading.
    """
    polygon = feet_xy if isinstance(feet_xy, SupportPolygon) else SupportPolygon.of_feet(feet_xy)
    if polygon.signed_distance(com) <= 0:
        return tuple(SlopeLimit(heading, 0.0, Cause("tip")) for heading in headings)
    slide = math.atan(friction)
    downhill = -np.column_stack([np.cos(headings), np.sin(headings)])
    tips = np.arctan2(polygon.exit_distances(com[:2], downhill), com[2])
    return tuple(
        SlopeLimit(heading, min(float(tip), slide), Cause("tip" if tip < slide else "slide"))
        for heading, tip in zip(headings, tips, strict=True)
    )


def slope_gravity(angle: float, heading: float, gravity: float = GRAVITY) -> ArrayF:
    """Gravity [m/s²] in the ground frame of a slope α uphill toward heading ψ (g [m/s²])."""
    return gravity * np.array(
        [
            -math.sin(angle) * math.cos(heading),
            -math.sin(angle) * math.sin(heading),
            -math.cos(angle),
        ]
    )
