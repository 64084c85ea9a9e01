"""Stability along a gait period: the zero-moment point inside the standing feet's polygon.

The ground's total push on the robot is the rate of its centroidal momentum less its
weight, ḣ − M·g: the free-flyer rows of the RNEA, RNEA[0:6] = (F, n), force F and moment
n about the body's origin (body frame, level). The zero-moment point (ZMP) is where the
ground's moment has no horizontal part: with the body's origin at height h above the
ground, relative to the origin's footprint,

    x = −(n_y + h·F_x) / F_z,    y = (n_x − h·F_y) / F_z;

standing still it is the centre of mass's footprint. (Pinocchio's
``computeCentroidalMomentumTimeVariation`` gives the same rate; the tests hold them equal.)
The margin is its signed distance to the support polygon of the standing feet (positive
inside, :class:`~hexaleg.statics.support.SupportPolygon`) [m]. A gait whose ZMP leaves the
polygon tips over: it is not feasible, and ``"zmp"`` is what binds
(:attr:`~hexaleg.gait.analysis.GaitAnalysis.feasible`).

Multiplied by F_z > 0, the ZMP's side of each polygon edge, F_z·cross(edge, ZMP − vertex),
is linear in the wrench (:func:`zmp_sides`): with the wrench static + w·inertial
(w = 1/T²) each side is affine in w, which bounds the max speed in closed form
(:mod:`hexaleg.gait.limits`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.gait.pattern import GaitPhases
from hexaleg.statics.support import SupportPolygon


def zero_moment_points(wrench: ArrayF, height: float) -> ArrayF:
    """The ZMP (N, 2) relative to the body origin's footprint [m], from the base rows (N, 6)."""
    force, moment = wrench[:, :3], wrench[:, 3:]
    x = -(moment[:, 1] + height * force[:, 0]) / force[:, 2]
    y = (moment[:, 0] - height * force[:, 1]) / force[:, 2]
    return np.stack((x, y), axis=-1)


def feet_on_ground(feet: ArrayF, configurations: ArrayF, height: float) -> ArrayF:
    """The feet (N, 6, 3) in the ground frame [m], from the body frame's and the body's poses.

    Args:
        feet: Foot positions (N, 6, 3), body frame (level, never rotated) [m].
        configurations: Pinocchio's q (N, nq): the body origin's position first [m].
        height: The body origin's nominal height above the ground [m].

    """
    body = configurations[:, None, :3] - np.array([0.0, 0.0, height])
    on_ground: ArrayF = feet + body
    return on_ground


@dataclass(frozen=True)
class Supports:
    """The standing feet's support polygons along a walk, ground frame.

    Standing feet do not move, so one polygon serves each run of samples with the same
    standing legs; every ZMP check of a walk (:func:`zmp_margins`, :func:`zmp_sides`)
    shares them.

    Attributes:
        runs: The samples of each run (consecutive; together every sample once).
        polygons: Each run's polygon.

    """

    runs: tuple[slice, ...]
    polygons: tuple[SupportPolygon, ...]

    @classmethod
    def of_feet(cls, feet: ArrayF, phases: GaitPhases) -> Supports:
        """The polygons of feet (N, 6, ≥2), ground frame [m], standing as ``phases`` say."""
        stance = phases.stance
        polygons = (SupportPolygon.of_feet(feet[r.start, stance[r.start], :2]) for r in phases.runs)
        return cls(phases.runs, tuple(polygons))


def zmp_margins(zmp: ArrayF, supports: Supports) -> ArrayF:
    """Signed distance (N,) of each ZMP to its standing feet's support polygon [m].

    Args:
        zmp: Zero-moment points (N, 2), ground frame [m].
        supports: The standing feet's polygons at those samples.

    """
    margins = np.empty(len(zmp))
    for run, polygon in zip(supports.runs, supports.polygons, strict=True):
        margins[run] = polygon.signed_distances(zmp[run])
    return margins


def zmp_sides(wrench: ArrayF, height: float, travel: ArrayF, supports: Supports) -> ArrayF:
    """F_z·cross(edge, ZMP − vertex) for every edge of every sample's polygon [N·m²].

    All ≥ 0 (with F_z > 0): the ZMP is inside every sample's polygon. Linear in ``wrench``.

    Args:
        wrench: The base rows of the RNEA (..., N, 6), as in :func:`zero_moment_points`:
            several wrenches of one motion (leading axes) share its polygons.
        height: The body origin's height above the ground [m].
        travel: The body origin's footprint (N, 2), ground frame [m].
        supports: The standing feet's polygons at the N samples.

    Returns:
        The sides (..., E), every edge of every sample, flat (one order for every wrench).

    """
    force, moment = wrench[..., :3], wrench[..., 3:]
    numerator = np.stack(  # F_z·ZMP, relative to the body origin's footprint
        (-(moment[..., 1] + height * force[..., 0]), moment[..., 0] - height * force[..., 1]),
        axis=-1,
    )
    sides = []
    for run, polygon in zip(supports.runs, supports.polygons, strict=True):
        corners = polygon.vertices - travel[run, None]  # from the body origin's footprint
        relative = numerator[..., run, None, :] - corners * force[..., run, 2, None, None]
        edges = polygon.edges
        side = edges[:, 0] * relative[..., 1] - edges[:, 1] * relative[..., 0]
        sides.append(side.reshape(*side.shape[:-2], -1))
    return np.concatenate(sides, axis=-1)
