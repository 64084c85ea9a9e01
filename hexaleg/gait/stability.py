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
inside, :class:`~hexaleg.statics.support.SupportPolygon`) [m].
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.statics.support import SupportPolygon


def zero_moment_points(wrench: ArrayF, height: float) -> ArrayF:
    """The ZMP (N, 2) relative to the body origin's footprint [m], from the base rows (N, 6)."""
    force, moment = wrench[:, :3], wrench[:, 3:]
    x = -(moment[:, 1] + height * force[:, 0]) / force[:, 2]
    y = (moment[:, 0] - height * force[:, 1]) / force[:, 2]
    return np.stack((x, y), axis=-1)


def zmp_margins(zmp: ArrayF, feet: ArrayF, stance: npt.NDArray[np.bool_]) -> ArrayF:
    """Signed distance (N,) of each ZMP to its standing feet's support polygon [m].

    Args:
        zmp: Zero-moment points (N, 2), ground frame [m].
        feet: Foot positions (N, 6, ≥2), ground frame [m].
        stance: Which feet stand (N, 6).

    Standing feet do not move, so one polygon serves each run of samples with the same
    standing legs.

    """
    margins = np.empty(len(zmp))
    change = np.flatnonzero((stance[1:] != stance[:-1]).any(axis=1)) + 1
    for run in np.split(np.arange(len(zmp)), change):
        first = run[0]
        polygon = SupportPolygon.of_feet(feet[first, stance[first], :2])
        margins[run] = polygon.signed_distances(zmp[run])
    return margins
