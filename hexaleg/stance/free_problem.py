"""The free-coupled program of one stance: max ±d_k over body displacements d, every margin ≥ 0.

:class:`FreeProblem` gives what the free-coupled search (:mod:`.free_coupled`) asks of a
pose: the smooth margins and their Jacobian for SLSQP, the exact check every answer
passes, the constraints that bind, whether a path joins the pose to the nominal stance,
and, for a robot that is its own mirror image, one pose out of a set of mirror images.
With self-collision, the clearance between the robot's own parts (coal) is one more
margin everywhere.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.cause import Cause
from hexaleg.numerics.multistart import CoordinateProblem
from hexaleg.stance.collisions import SelfCollision
from hexaleg.stance.constraints import constraint_labels, displacement_poses
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.stance.margin_kernel import KernelGeometry, kernel_geometry, margins_of
from hexaleg.stance.paths import RESOLUTION, retreat
from hexaleg.stance.symmetry import keeping, search_flips

FEASIBILITY_TOLERANCE = 1e-9
"""Largest constraint violation [m or rad] an answer may have (exact margins)."""
MARGIN_FLOOR = 1e-11
"""SLSQP asks every smooth margin to exceed this, so answers land inside the boundary."""
STEP = 1e-7
"""Finite-difference step of the margins' Jacobian [m or rad]."""
COLLISION_STEP = 1e-5
"""... and of the distances between parts [m or rad]: coal resolves them near contact
only to a few 1e-7 m, so a step of 1e-7 would differentiate its noise."""
ACTIVE_TOLERANCE = 1e-8
"""Margins this close to the smallest [m or rad] bind together at a free extreme."""
MAX_ITERATIONS = 60
"""SLSQP iterations per local solve."""
ROTATION_BOUNDS = ((-math.pi, math.pi), (-math.pi / 2, math.pi / 2), (-math.pi, math.pi))
"""Roll, pitch, yaw stay in Pinocchio's rpy ranges, so each pose has one name [rad]."""
LOWER = np.array([-np.inf] * 3 + [lo for lo, _ in ROTATION_BOUNDS])
UPPER = np.array([np.inf] * 3 + [hi for _, hi in ROTATION_BOUNDS])
"""The same bounds as arrays (6,) [m, rad]."""


class FreeProblem:
    """max ±d_k over body displacements d (6,) with every stance margin ≥ 0."""

    def __init__(self, geometry: StanceGeometry, collision: SelfCollision | None) -> None:
        self.geometry = geometry
        self.collision = collision
        self.labels = constraint_labels(geometry.legs)
        self.smooth_kernel = kernel_geometry([geometry], smooth=True)
        self.exact_kernel = kernel_geometry([geometry], smooth=False)
        every_leg_stands = collision is None or (
            len(geometry.legs) == len(collision.model.leg_names) and collision.mirrored
        )
        self.flips = search_flips(geometry, every_leg_stands)
        self.basis = np.vstack([np.zeros(6), STEP * np.eye(6)])
        self._at: ArrayF | None = None  # the last d evaluated, and its seven poses' margins
        self._values = np.zeros(0)
        self._steps = np.zeros(0)  # each margin's finite-difference step

    def coordinate_problem(self, k: int, sign: int) -> CoordinateProblem:
        """The program of direction (k, sign), for SLSQP (:mod:`~hexaleg.numerics.multistart`).

        With self-collision an answer a hair inside two parts (coal's distances jolt
        SLSQP, which can stall there) is pulled back until clear (:meth:`feasible_nearby`).
        """
        bounds = [(None, None)] * 3 + list(ROTATION_BOUNDS)
        repair = None if self.collision is None else self.feasible_nearby
        return CoordinateProblem(
            k, sign, self.margins, self.jacobian, self.feasible, bounds, MAX_ITERATIONS, repair
        )

    def margins(self, d: ArrayF) -> ArrayF:
        """Smooth margins at d (6,), less the floor: the NLP's inequality constraints."""
        values: ArrayF = self._around(d)[0] - MARGIN_FLOOR
        return values

    def jacobian(self, d: ArrayF) -> ArrayF:
        """Forward differences of :meth:`margins`, all seven poses in one call."""
        values = self._around(d)
        jacobian: ArrayF = (values[1:] - values[0]).T / self._steps[:, None]
        return jacobian

    def _around(self, d: ArrayF) -> ArrayF:
        """Smooth margins at d and its six forward steps (7, C), kept for the next call.

        SLSQP asks for the Jacobian where it last asked for the margins; one evaluation
        serves both. With self-collision, every pair's distance (less the contact
        distance) is a margin of its own, each smooth where the minimum is not.
        """
        if self._at is None or not (self._at == d).all():
            margins = self._kernel(self.smooth_kernel, d + self.basis)
            self._steps = np.full(margins.shape[-1], STEP)
            if self.collision is not None:
                poses = displacement_poses(self.geometry, d + self.basis * COLLISION_STEP / STEP)
                pairs = self.collision.pair_clearances(*poses)
                margins = np.concatenate([margins, pairs], axis=-1)
                self._steps = np.append(self._steps, np.full(pairs.shape[-1], COLLISION_STEP))
            self._values, self._at = margins, np.array(d, dtype=float)
        return self._values

    @staticmethod
    def _kernel(kernel: KernelGeometry, displacements: ArrayF) -> ArrayF:
        flat = np.ascontiguousarray(np.reshape(displacements, (-1, 6)), dtype=float)
        return margins_of(kernel, flat, np.zeros(len(flat), dtype=np.int64))

    def exact_margins(self, displacements: ArrayF) -> ArrayF:
        """Exact stance margins (P, 8N + 1) of displacements (P, 6) [m or rad]."""
        return self._kernel(self.exact_kernel, displacements)

    def exact(self, d: ArrayF) -> ArrayF:
        """Exact margins at d (6,) [m or rad], the collision clearance last if checked."""
        margins: ArrayF = self._kernel(self.exact_kernel, d)[0]
        if self.collision is None:
            return margins
        clearance = self.collision.clearances(*displacement_poses(self.geometry, d))[0]
        return np.append(margins, clearance)

    def feasible(self, d: ArrayF) -> bool:
        """The exact check every answer must pass."""
        return bool(self.exact(d).min() >= -FEASIBILITY_TOLERANCE)

    def clear(self, displacements: ArrayF) -> ArrayF:
        """Whether each of displacements (P, 6) meets every exact margin (P,) [bool].

        Self-collision by coal's yes/no check, asked only where the stance margins hold.
        """
        ok: ArrayF = self.exact_margins(displacements).min(axis=-1) >= 0
        if self.collision is not None and ok.any():
            ok[ok] = self._apart(displacements[ok])
        return ok

    def touching(self, d: ArrayF) -> bool:
        """Whether two of the robot's own parts touch at d (6,) (False without self-collision)."""
        if self.collision is None:
            return False
        return not bool(self._apart(np.asarray(d, dtype=float)[None])[0])

    def _apart(self, displacements: ArrayF) -> npt.NDArray[np.bool_]:
        """Whether no two parts touch at each of displacements (P, 6) (P,) [bool]: coal's yes/no."""
        assert self.collision is not None
        poses = displacement_poses(self.geometry, displacements)
        return np.asarray(self.collision.scan_clearances(*poses) >= 0, dtype=bool)

    def feasible_nearby(self, d: ArrayF) -> ArrayF | None:
        """d, or d pulled toward nominal by a hair (at most 0.1 %), if that passes the check.

        A climb's end violates its margins by 1e-6 at most.
        """
        for pull in (0.0, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3):
            pulled = np.asarray(d, dtype=float) * (1.0 - pull)
            if self.feasible(pulled):
                return pulled
        return None

    def binding(self, d: ArrayF) -> list[Cause]:
        """The constraints that bind at d, in constraint order; touching pairs last."""
        margins = self.exact(d)
        active = np.flatnonzero(margins <= margins.min() + ACTIVE_TOLERANCE)
        causes = [self.labels[i] for i in active if i < len(self.labels)]
        if self.collision is not None and len(self.labels) in active:
            causes += self.collision.closest_pairs(*displacement_poses(self.geometry, d))
        return causes

    def reachable(self, d: ArrayF, scale: ArrayF) -> bool:
        """Whether a feasible path joins d to the nominal stance (:mod:`.paths`).

        With self-collision the path found on the stance margins must also be clear
        of collisions at every step.
        """
        reached, path = retreat(self.smooth_kernel, self.exact_kernel, np.asarray(d, float), scale)
        if not reached or self.collision is None:
            return bool(reached)
        for start, end in itertools.pairwise(path):
            steps = max(1, math.ceil(np.abs(end - start).max() / RESOLUTION))
            points = start + (end - start) * (np.arange(1, steps + 1) / steps)[:, None]
            if self.collision.scan_clearances(*displacement_poses(self.geometry, points)).min() < 0:
                return False
        return True

    def clear_on_the_way_back(self, d: ArrayF, scale: ArrayF) -> ArrayF | None:
        """The first pose free of self-collision on a feasible path from d toward nominal.

        A start for the search with collisions: a stance optimum where parts touch,
        moved back along its path (:func:`~.paths.retreat`, checked every 1 cm) until
        they do not. None if no such pose is found.
        """
        if self.collision is None:
            return np.asarray(d, dtype=float)
        _, path = retreat(self.smooth_kernel, self.exact_kernel, np.asarray(d, float), scale)
        for start, end in itertools.pairwise(path):
            steps = max(1, math.ceil(np.abs(end - start).max() / (10 * RESOLUTION)))
            points = start + (end - start) * (np.arange(steps + 1) / steps)[:, None]
            clear = self.collision.scan_clearances(*displacement_poses(self.geometry, points))
            if (clear >= 0).any():
                return np.asarray(points[np.argmax(clear >= 0)])
        return None

    def canonical(self, d: ArrayF, k: int) -> ArrayF:
        """Of d and its feasible mirror images that keep coordinate k, the largest.

        A symmetric robot's optima come in mirror-image sets of equal value, and which
        one a search reaches first can follow round-off (a BLAS thread count, say). The
        largest pose in lexicographic order, compared at 1e-6, is the same whichever it is.
        d itself has passed the exact check and is not checked again.
        """
        images = [flip * d for flip in keeping(k, self.flips)]
        return max([d, *(image for image in images if self.feasible(image))], key=_rounded)


def _rounded(pose: ArrayF) -> tuple[float, ...]:
    return tuple(float(v) for v in np.round(pose, 6))
