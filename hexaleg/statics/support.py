"""The support polygon of the stance feet and the stability margin inside it."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.exceptions import HexalegError


def ground_point(com: ArrayF, gravity: ArrayF) -> ArrayF:
    """Where the gravity line through the centre of mass meets the ground z = 0 (x, y) [m]."""
    t = com[2] / -gravity[2]
    point: ArrayF = (com + t * gravity)[:2]
    return point


@dataclass(frozen=True)
class SupportPolygon:
    """The convex hull of the stance feet on the ground, with its edges precomputed.

    Attributes:
        vertices: Hull vertices, counter-clockwise (K, 2) [m].
        edges: Vector from each vertex to the next (K, 2) [m].
        lengths: Edge lengths (K,) [m].

    """

    vertices: ArrayF
    edges: ArrayF
    lengths: ArrayF

    @classmethod
    def of_feet(cls, feet_xy: npt.ArrayLike) -> SupportPolygon:
        """The support polygon of the feet (x, y) (N, 2) [m]."""
        feet_xy = np.asarray(feet_xy, dtype=float)
        indices = _hull(feet_xy)
        if len(indices) < 3:
            raise HexalegError(
                f"the stance feet span no support polygon: {len(feet_xy)} feet on one line"
            )
        vertices = feet_xy[indices]
        edges = feet_xy[indices[1:] + indices[:1]] - vertices  # each vertex to the next
        return cls(vertices, edges, np.hypot(edges[:, 0], edges[:, 1]))

    def signed_distance(self, point: npt.ArrayLike) -> float:
        """Signed distance [m] from ``point`` (x, y) to the boundary: > 0 inside."""
        return float(self.signed_distances(np.asarray(point, dtype=float)[None, :2])[0])

    def signed_distances(self, points: npt.ArrayLike) -> ArrayF:
        """:meth:`signed_distance` of each of ``points`` (P, 2) (P,) [m]."""
        relative = np.asarray(points, dtype=float)[:, None, :2] - self.vertices  # (P, K, 2)
        edges = self.edges
        inward = (edges[:, 0] * relative[..., 1] - edges[:, 1] * relative[..., 0]) / self.lengths
        along = (relative[..., 0] * edges[:, 0] + relative[..., 1] * edges[:, 1]) / self.lengths**2
        gap = relative - np.clip(along, 0.0, 1.0)[..., None] * edges
        inside = inward.min(axis=1)
        margins: ArrayF = np.where(
            inside >= 0, inside, -np.hypot(gap[..., 0], gap[..., 1]).min(axis=1)
        )
        return margins

    def exit_distance(self, point: ArrayF, direction: ArrayF) -> float:
        """How far from ``point`` (inside) along ``direction`` the boundary lies [m]."""
        return float(self.exit_distances(point, np.asarray(direction)[None])[0])

    def exit_distances(self, point: ArrayF, directions: ArrayF) -> ArrayF:
        """:meth:`exit_distance` along each of ``directions`` (H, 2) [m] (inf: none)."""

        def cross(u: ArrayF, v: ArrayF) -> ArrayF:
            return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]

        d = np.asarray(directions, dtype=float)[:, None, :]  # (H, 1, 2)
        offset = self.vertices - np.asarray(point)[:2]  # (K, 2), point to each vertex
        denominator = cross(d, self.edges)  # (H, K)
        parallel = np.abs(denominator) < 1e-15
        denominator = np.where(parallel, 1.0, denominator)
        t = cross(offset, self.edges) / denominator  # along the ray
        s = cross(offset, d) / denominator  # along the edge
        hit = ~parallel & (t >= 0) & (s >= -1e-12) & (s <= 1 + 1e-12)
        distances: ArrayF = np.where(hit, t, np.inf).min(axis=1)
        return distances


def _hull(points: ArrayF) -> list[int]:
    """Indices of the convex hull's vertices, counter-clockwise (Andrew's monotone chain).

    A handful of feet: plain Python beats qhull's setup tenfold. Collinear points on an
    edge are left out; all points on one line give fewer than three.
    """
    xy = points[:, :2].tolist()  # plain floats: a handful of points, many small products
    order = sorted(range(len(xy)), key=lambda k: (xy[k][0], xy[k][1]))

    def turn(o: int, a: int, b: int) -> float:
        (ox, oy), (ax, ay), (bx, by) = xy[o], xy[a], xy[b]
        return float((ax - ox) * (by - oy) - (ay - oy) * (bx - ox))

    def chain(indices: list[int]) -> list[int]:
        kept: list[int] = []
        for k in indices:
            while len(kept) >= 2 and turn(kept[-2], kept[-1], k) <= 0:
                kept.pop()
            kept.append(k)
        return kept

    lower, upper = chain(order), chain(order[::-1])
    return lower[:-1] + upper[:-1]


def stability_margin(feet_xy: ArrayF, point: ArrayF) -> float:
    """Signed distance [m] from ``point`` to the convex hull of the feet: > 0 inside."""
    return SupportPolygon.of_feet(feet_xy).signed_distance(point)
