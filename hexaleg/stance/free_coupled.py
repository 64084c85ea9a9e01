"""Free-coupled body flexibility: each coordinate pushed as far as the mechanism allows.

The other five body coordinates are free to help. The body pose is the variable,
d = (x, y, z, roll, pitch, yaw) displaced from the nominal stance (world frame,
Pinocchio's roll-pitch-yaw); every stance leg follows by the closed-form knee-down
IK (eq 8–9), whose solution Pinocchio's model reproduces (tested). Each direction
is a small smooth nonlinear program, max ±d_k subject to every margin of
:func:`~hexaleg.stance.constraints.smooth_stance_margins` ≥ 0, solved by SLSQP from
several deterministic starts (:mod:`~hexaleg.numerics.multistart`): the axis-locked extreme, the
feasible pose of a vectorized scan of the coupled coordinates that reaches furthest (these
two run both in metres and radians and scaled to the search box), and low-discrepancy
points of a box around the nominal stance (scaled). The best
feasible answer wins after an exact feasibility check, so the range is never
smaller than the axis-locked one; the result is flagged converged only where the
optimizer converged and at least two starts agreed on the optimum.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from hexaleg._typing import ArrayF, StanceSet
from hexaleg.design import HexapodDesign
from hexaleg.numerics.multistart import box_starts, maximize_coordinate
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.axis_locked import axis_locked_extremes
from hexaleg.stance.collisions import SelfCollision, collision_limited
from hexaleg.stance.constraints import (
    AXES,
    Cause,
    constraint_labels,
    displacement_poses,
)
from hexaleg.stance.extremes import (
    Extreme,
    FlexibilityResult,
    FlexibilityWarning,
    pose_extreme,
)
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.stance.margin_kernel import compiled_margins
from hexaleg.stance.symmetry import keeping, mirror_flips, reversing

FEASIBILITY_TOLERANCE = 1e-9
"""Largest constraint violation [m or rad] an answer may have (exact margins)."""
MARGIN_FLOOR = 1e-11
"""The NLP asks every smooth margin to exceed this, so answers land inside the boundary."""
STEP = 1e-7
"""Finite-difference step of the margins' Jacobian [m or rad]."""
ACTIVE_TOLERANCE = 1e-8
"""Margins this close to the smallest [m or rad] bind together at a free extreme."""
BOX_STARTS = 16
"""Starts per direction spread over the search box (scrambled Sobol, seeded by direction)."""
BOX_SCALE = 1.3
"""The search box reaches this multiple of each coordinate's larger axis-locked extreme."""
ENOUGH = (5, 4)
"""Stop a direction's search once 5 starts have run and 4 box starts reached the best value.
The guided starts (axis-locked and scanned, each run unscaled and scaled) may win but do
not vote: with them voting, three starts agreed on a local optimum of z− of a
0.05/0.5/0.45 m robot (0.4 % short) and of yaw± of a 0.19/0.15/0.66 m tripod (3 % short).
Three box starts were not enough either: z− of that 0.05/0.5/0.45 m robot has five local
optima within 12 %, and three scaled box starts reached the second best (0.2844 m)
before one reached the best (0.2855 m). Four cost a fifth more iterations."""
MAX_ITERATIONS = 40
"""SLSQP iterations per start: converging starts need 5–40 (a tripod's the most)."""
ROTATION_BOUNDS = ((-math.pi, math.pi), (-math.pi / 2, math.pi / 2), (-math.pi, math.pi))
"""Roll, pitch, yaw stay in Pinocchio's rpy ranges, so each pose has one name [rad]."""


@dataclass(frozen=True)
class DirectionSolution:
    """The free-coupled answer for one direction.

    Attributes:
        extreme: The extreme, with its pose and binding constraints.
        converged: The winning start's optimizer converged and another start agreed.
        iterations: SLSQP iterations over every start.

    """

    extreme: Extreme
    converged: bool
    iterations: int


def free_flexibility(
    design: HexapodDesign,
    stance: StanceSet | Sequence[str] = "all",
    model: HexapodModel | None = None,
    collisions: bool = False,
    geometry: StanceGeometry | None = None,
) -> FlexibilityResult:
    """Free-coupled flexibility: each coordinate's extreme with the other five free.

    Args:
        design: The design.
        stance: ``"all"``, ``"tripod"`` or a list of stance legs.
        model: Its Pinocchio model, if already built.
        collisions: Also stop where two of the robot's own parts touch (coal).
        geometry: A template geometry of the same body and mounts (fast path for
            sweeps: the design's legs replace the template's by :meth:`StanceGeometry.with_design`).

    """
    geometry = StanceGeometry.of_design(design, stance, model, geometry)
    collision = None
    if collisions:
        collision = SelfCollision(HexapodModel(design) if model is None else model, geometry)
    locked = axis_locked_extremes(geometry)
    if collision is not None:
        locked = collision_limited(geometry, collision, locked)
    problem = _FreeProblem(geometry, collision)
    solved: dict[tuple[str, int], DirectionSolution] = {}
    for extreme in locked:
        mirrored = problem.mirrored(extreme, solved)
        solved[(extreme.axis, extreme.sign)] = mirrored or problem.solve(extreme, locked)
    solutions = [solved[(e.axis, e.sign)] for e in locked]
    doubtful = [_name(s.extreme) for s in solutions if not s.converged]
    if doubtful:
        warnings.warn(
            "free-coupled flexibility: the optimizer did not converge, or its starts did "
            f"not agree, for {', '.join(doubtful)}; the best feasible values found are kept",
            FlexibilityWarning,
            stacklevel=2,
        )
    return FlexibilityResult(
        design,
        geometry.legs,
        "free",
        tuple(s.extreme for s in solutions),
        converged=not doubtful,
        iterations=sum(s.iterations for s in solutions),
        collisions=collisions,
    )


def _rounded(pose: ArrayF) -> tuple[float, ...]:
    return tuple(float(v) for v in np.round(pose, 6))


def _name(extreme: Extreme) -> str:
    return f"{extreme.axis}{'+' if extreme.sign > 0 else '-'}"


def search_box(locked: Sequence[Extreme]) -> ArrayF:
    """Half widths (6,) of the box the starts spread over [m, rad].

    :data:`BOX_SCALE` times each coordinate's larger axis-locked extreme.
    """
    value = {(e.axis, e.sign): e.value for e in locked}
    half = np.array([BOX_SCALE * max(abs(value[(a, 1)]), abs(value[(a, -1)])) for a in AXES])
    return np.maximum(half, 1e-3)


def axis_locked_start(k: int, sign: int, locked: Sequence[Extreme]) -> ArrayF:
    """The axis-locked extreme of direction (k, sign), pulled back by a hair: the first start."""
    start = np.zeros(len(AXES))
    start[k] = next(e.value for e in locked if (e.axis, e.sign) == (AXES[k], sign))
    start[k] -= sign * 1e-9
    return start


def _seed(k: int, sign: int) -> int:
    return 2 * k + (sign > 0)


SCAN_SAMPLES = 1024
"""Poses of the search box whose exact margins are checked at once, before any start:
the feasible one reaching furthest starts right after the axis-locked extreme (more
scanned starts crowd out the box starts, and agreeing starts then share one optimum)."""


class _FreeProblem:
    """max ±d_k over body displacements d (6,) with every stance margin ≥ 0."""

    def __init__(self, geometry: StanceGeometry, collision: SelfCollision | None) -> None:
        self.geometry = geometry
        self.collision = collision
        self.labels = constraint_labels(geometry.legs)
        self._smooth_margins = compiled_margins(geometry)
        self._exact_margins = compiled_margins(geometry, smooth=False)
        self.flips = mirror_flips(geometry)
        self.basis = np.vstack([np.zeros(len(AXES)), STEP * np.eye(len(AXES))])
        self._at: ArrayF | None = None  # the last d evaluated, and its seven poses' margins
        self._values = np.zeros(0)

    def margins(self, d: ArrayF) -> ArrayF:
        """Smooth margins at d (6,), less the floor: the NLP's inequality constraints."""
        return self._around(d)[0] - MARGIN_FLOOR

    def jacobian(self, d: ArrayF) -> ArrayF:
        """Forward differences of :meth:`margins`, all seven poses in one vectorized call."""
        values = self._around(d)
        return (values[1:] - values[0]).T / STEP

    def _around(self, d: ArrayF) -> ArrayF:
        """Smooth margins at d and its six forward steps (7, C), kept for the next call.

        SLSQP asks for the Jacobian where it last asked for the margins; one vectorized
        evaluation serves both, and costs about what one pose alone does.
        """
        if self._at is None or not (self._at == d).all():
            self._values = self._smooth(d + self.basis)
            self._at = np.array(d, dtype=float)
        return self._values

    def _smooth(self, displacements: ArrayF) -> ArrayF:
        margins = self._smooth_margins(displacements)
        if self.collision is None:
            return margins
        clearance = self.collision.clearances(*displacement_poses(self.geometry, displacements))[0]
        return np.concatenate([margins, clearance[..., None]], axis=-1)

    def exact(self, d: ArrayF) -> ArrayF:
        """Exact margins at d (6,) [m or rad], the collision clearance last if checked."""
        margins = self._exact_margins(d)
        if self.collision is None:
            return margins
        clearance = self.collision.clearances(*displacement_poses(self.geometry, d))[0]
        return np.append(margins, clearance)

    def binding(self, d: ArrayF) -> list[Cause]:
        """The constraints that bind at d, in constraint order; touching pairs last."""
        margins = self.exact(d)
        active = np.flatnonzero(margins <= margins.min() + ACTIVE_TOLERANCE)
        causes = [self.labels[i] for i in active if i < len(self.labels)]
        if self.collision is not None and len(self.labels) in active:
            causes += self.collision.closest_pairs(*displacement_poses(self.geometry, d))
        return causes

    def feasible(self, d: ArrayF) -> bool:
        """The exact check every answer must pass."""
        return bool(self.exact(d).min() >= -FEASIBILITY_TOLERANCE)

    def mirrored(
        self,
        extreme: Extreme,
        solved: dict[tuple[str, int], DirectionSolution],
    ) -> DirectionSolution | None:
        """``extreme``'s direction as the mirror image of the opposite one, if solved.

        The reflected pose must pass the exact feasibility check and reach at least the
        axis-locked extreme; its binding constraints are found at the pose as for any
        answer. None when no symmetry gives it.
        """
        k = AXES.index(extreme.axis)
        opposite = solved.get((extreme.axis, -extreme.sign))
        if opposite is None:
            return None
        for flip in reversing(k, self.flips):
            d = flip * np.asarray(opposite.extreme.pose)
            if not self.feasible(d) or extreme.sign * d[k] < extreme.sign * extreme.value:
                continue
            binding = self.binding(d)
            solved_extreme = pose_extreme(self.geometry, extreme.axis, extreme.sign, d, binding)
            return DirectionSolution(solved_extreme, opposite.converged, 0)
        return None

    def scanned(self, k: int, sign: int, samples: ArrayF) -> list[ArrayF]:
        """The feasible sample reaching furthest in direction (k, sign), if any.

        A list of at most one start. The scan checks the stance margins only: checking
        collisions at every sample would cost more than the start saves.
        """
        feasible = np.flatnonzero(self._exact_margins(samples).min(-1) >= 0)
        if feasible.size == 0:
            return []
        return [samples[feasible[np.argmax(sign * samples[feasible, k])]]]

    def solve(self, extreme: Extreme, locked: Sequence[Extreme]) -> DirectionSolution:
        """The free extreme of ``extreme``'s direction, never short of ``extreme`` itself."""
        k = AXES.index(extreme.axis)
        box = search_box(locked)
        # The starts: the axis-locked extreme and the furthest feasible pose of a scan of
        # the search box (guided), then the scan's first BOX_STARTS points: the better
        # optima couple coordinates (z− with yaw and a sideways shift, say), which no start
        # on the axis finds. The scan is the box starts' own Sobol sequence, continued.
        samples = np.asarray(box_starts(box, SCAN_SAMPLES, seed=_seed(k, extreme.sign)))
        guided = [
            axis_locked_start(k, extreme.sign, locked),
            *self.scanned(k, extreme.sign, samples),
        ]
        # SLSQP runs in coordinates scaled to the search box (u = d / box), whose first
        # steps then span the box, except that the guided starts also run unscaled: on 27
        # chosen, 16 random and the 320 Fig 15 designs, the scaled runs found tripod
        # optima the unscaled ones missed by up to 0.22 rad, and the unscaled guided runs
        # z− optima of all-leg robots that every scaled run missed by up to 1 cm.
        result = maximize_coordinate(
            k,
            extreme.sign,
            self.margins,
            self.jacobian,
            [*guided, *guided, *samples[:BOX_STARTS]],
            self.feasible,
            bounds=[(None, None)] * 3 + list(ROTATION_BOUNDS),
            max_iterations=MAX_ITERATIONS,
            enough=ENOUGH,
            guided=2 * len(guided),
            scales=[None] * len(guided) + [box] * (len(guided) + BOX_STARTS),
        )
        if result is None:
            return DirectionSolution(extreme, False, 0)
        converged = result.success and result.agreed
        if result.value <= extreme.sign * extreme.value:  # axis-locked is feasible: keep it
            return DirectionSolution(extreme, converged, result.iterations)
        pose = self.canonical(result.x, k)
        binding = self.binding(pose)
        solved = pose_extreme(self.geometry, extreme.axis, extreme.sign, pose, binding)
        return DirectionSolution(solved, converged, result.iterations)

    def canonical(self, d: ArrayF, k: int) -> ArrayF:
        """Of d and its feasible mirror images that keep coordinate k, the largest.

        A symmetric robot's optima come in mirror-image sets of equal value, and which
        one a start reaches first can follow round-off (a BLAS thread count, say). The
        largest pose in lexicographic order, compared at 1e-6, is the same whichever it is.
        """
        images: list[ArrayF] = [d, *(flip * d for flip in keeping(k, self.flips))]
        feasible = [image for image in images if self.feasible(image)]
        return max(feasible, key=_rounded)
