"""Feasible paths from the nominal stance, compiled: which poses the body can reach.

A pose is reachable when a path of feasible poses joins it to the nominal stance. The
path here is a polyline whose every point, at steps of at most :data:`RESOLUTION`
(1 mm, 1 mrad) in each coordinate, passes the exact stance margins
(:func:`segment_feasible`). :func:`retreat` builds one backwards: from the pose, steps
that bring the body closer to nominal while moving away from the constraints that bind
(each step a small linear program on the linearized smooth margins), until the
straight segment to nominal is itself feasible. It proves reachability when it
succeeds; when it stalls (a pocket the straight retreat cannot leave) it proves
nothing either way.
"""

from __future__ import annotations

import numpy as np

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF
from hexaleg.numerics.lp import elastic_lp
from hexaleg.stance.climb import PENALTY, linearize, row_norms
from hexaleg.stance.margin_kernel import KernelGeometry, column_count, pose_margins

RESOLUTION = 1e-3
"""Largest step between checked points of a path, per coordinate [m or rad]."""
TOLERANCE = 1e-9
"""Largest violation of an exact margin a path point may have [m or rad]."""
MAX_WAYPOINTS = 400
"""A retreat gives up after this many steps."""
FIRST_RADIUS, LARGEST_RADIUS, SMALLEST_RADIUS = 0.05, 0.2, 1e-7
"""A retreat step's trust region (scaled units): its start, cap and floor."""
CLEARANCES = (0.3, 0.1, 0.03)
"""How far (in trust radii) a retreat step tries to move the near margins from zero."""
COARSE_POINTS = 16
"""Points of a segment checked before the full check at :data:`RESOLUTION`."""


@compiled
def segment_feasible(
    geometry: KernelGeometry, start: ArrayF, end: ArrayF, points: int
) -> bool:  # pragma: no cover - compiled
    """Whether the exact margins hold at ``points`` evenly spaced points of (start, end]."""
    values = np.empty(column_count(geometry))
    rotation, d = np.empty((3, 3)), np.empty(6)
    for s in range(1, points + 1):
        d[:] = start + (end - start) * (s / points)
        pose_margins(geometry, 0, d, rotation, values)
        if values.min() < -TOLERANCE:
            return False
    return True


@compiled
def path_feasible(geometry: KernelGeometry, start: ArrayF, end: ArrayF) -> bool:  # pragma: no cover
    """Whether the segment start → end is feasible at :data:`RESOLUTION` (a coarse look first)."""
    if not segment_feasible(geometry, start, end, COARSE_POINTS):
        return False
    points = int(np.ceil(np.abs(end - start).max() / RESOLUTION))
    return segment_feasible(geometry, start, end, max(points, 1))


@compiled
def retreat(
    smooth: KernelGeometry, exact: KernelGeometry, pose: ArrayF, scale: ArrayF
) -> tuple[bool, ArrayF]:  # pragma: no cover - compiled
    """A feasible polyline from ``pose`` (6,) to nominal (W, 6), and whether it got there.

    Args:
        smooth: The design's smooth-margin kernel geometry (for the steps).
        exact: Its exact-margin kernel geometry (for the checks).
        pose: A feasible displacement [m, rad].
        scale: Unit lengths of the steps (the search box's half widths) [m, rad].

    """
    path = np.zeros((MAX_WAYPOINTS + 2, 6))
    path[0] = pose
    u, radius, count = pose / scale, FIRST_RADIUS, 1
    for _ in range(MAX_WAYPOINTS):
        if path_feasible(exact, u * scale, np.zeros(6)):
            return True, path[: count + 1]  # the last row: nominal
        values, jacobian = linearize(smooth, u, scale)
        norms = row_norms(jacobian)
        near = np.flatnonzero(values / norms <= 3 * LARGEST_RADIUS)
        offsets, gradients = values[near] / norms[near], jacobian[near] / norms[near].reshape(-1, 1)
        step = np.zeros(6)
        while radius > SMALLEST_RADIUS and not step.any():
            step = _retreat_step(exact, offsets, gradients, u, scale, radius)
            radius = min(2 * radius, LARGEST_RADIUS) if step.any() else 0.5 * radius
        if not step.any():
            break
        u = u + step
        path[count] = u * scale
        count += 1
    return False, path[:count]


@compiled
def _retreat_step(
    exact: KernelGeometry,
    offsets: ArrayF,
    gradients: ArrayF,
    u: ArrayF,
    scale: ArrayF,
    radius: float,
) -> ArrayF:  # pragma: no cover - compiled
    """A step within ``radius`` toward nominal whose segment is feasible; zeros if none.

    The linear program minimizes u·step (toward nominal) while asking every near margin
    to rise to a fraction of the radius (away from the constraints); the fractions of
    :data:`CLEARANCES` are tried in turn.
    """
    bound = np.full(6, radius)
    for clearance in CLEARANCES:
        step, _ = elastic_lp(-u, offsets - clearance * radius, gradients, -bound, bound, PENALTY)
        if u @ step < -1e-12 and path_feasible(exact, u * scale, (u + step) * scale):
            return step
    return np.zeros(6)
