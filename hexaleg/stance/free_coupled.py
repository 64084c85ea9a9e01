"""Free-coupled body flexibility: each coordinate pushed as far as the mechanism allows.

The other five body coordinates are free to help. The body pose is the variable,
d = (x, y, z, roll, pitch, yaw) displaced from the nominal stance (world frame,
Pinocchio's roll-pitch-yaw); every stance leg follows by the closed-form knee-down
IK (eq 8–9). Each direction is a small nonlinear program, max ±d_k with every margin of
:func:`~hexaleg.stance.constraints.stance_margins` (smooth) ≥ 0 (:class:`.FreeProblem`),
whose feasible set is thin and has many local optima. The search for direction k:

1. **Climbs** (:mod:`.climb`, compiled): a local search from each of :data:`CLIMBS`
   scrambled-Sobol starts spread over a box around the nominal stance, from the
   axis-locked extreme, and then from the best point every other direction reached
   (the far tips of the feasible set, where the optima of neighbouring directions
   often lie) and from the direction's own best point made mirror-symmetric. Where
   each ends is a local optimum; equal values form a basin.
2. **Polish**: SLSQP from the best basin's point gives the optimum to full precision and
   the constraints that bind there; the next basins are polished in turn while they
   could still beat it.
3. **Reachability** (:mod:`.paths`): the answer must be joined to the nominal stance by
   a feasible path; an answer that cannot be is set aside for the next basin's.

The best reachable answer wins; it is never short of the axis-locked extreme, which is
reachable along its axis. Each extreme carries its :class:`~.extremes.SearchEvidence`
(climbs, basins, climbs agreeing, reachability), and only that evidence makes it
"converged". With self-collision the climbs see the stance margins only; the polish,
with the clearance as one more margin, runs from the best basins, the axis-locked
extreme and clear draws over the search box pushed along the direction
(:mod:`.collision_starts`); an answer SLSQP did not converge on is polished once more
from where it stopped. A robot that is its own mirror image solves one of each mirrored pair of
directions and takes the other from the mirror (:mod:`.symmetry`), re-checked.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np

from hexaleg._typing import ArrayF, StanceSet
from hexaleg.design import HexapodDesign
from hexaleg.numerics.multistart import (
    AGREEMENT,
    CoordinateProblem,
    MultiStartResult,
    Start,
    box_starts,
    maximize_coordinate,
)
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.axis_locked import axis_locked_extremes
from hexaleg.stance.basins import BASIN_TOLERANCE, Basin, grouped
from hexaleg.stance.climb import climb_all
from hexaleg.stance.collision_starts import spread_starts
from hexaleg.stance.collisions import SelfCollision, collision_limited
from hexaleg.stance.constraints import AXES
from hexaleg.stance.extremes import (
    Extreme,
    FlexibilityResult,
    FlexibilityWarning,
    SearchEvidence,
    pose_extreme,
)
from hexaleg.stance.free_problem import LOWER, UPPER, FreeProblem
from hexaleg.stance.geometry import StanceGeometry, needed_model
from hexaleg.stance.symmetry import keeping, mirror_sources

CLIMBS = 48
"""Climbs per direction from the search box (besides the one from the axis-locked extreme)."""
BOX_SCALE = 1.5
"""The search box reaches this multiple of each coordinate's larger axis-locked extreme:
the climbs' unit lengths."""
SPREAD = 2.0
"""The climbs' starts fill the search box scaled by this: starts far from the nominal
stance, infeasible at first, end in more different basins."""
CLIMB_TOLERANCE = 1e-6
"""A climb that ends with an exact margin below −this [m or rad] found no optimum."""
COLLISION_BASINS = 8
"""With self-collision, the best basins polished with the clearance."""


def free_flexibility(
    design: HexapodDesign,
    stance: StanceSet | Sequence[str] = "all",
    model: HexapodModel | None = None,
    *,
    geometry: StanceGeometry | None = None,
    collisions: bool = False,
    progress: Callable[[int, int], None] | None = None,
) -> FlexibilityResult:
    """Free-coupled flexibility: each coordinate's extreme with the other five free.

    Args:
        design: The design.
        stance: ``"all"``, ``"tripod"`` or a list of stance legs.
        model: Its Pinocchio model, if already built (else built once, if needed).
        geometry: A template geometry of the same body and mounts (fast path for
            sweeps: the design's legs replace the template's by :meth:`StanceGeometry.with_design`).
        collisions: Also stop where two of the robot's own parts touch (coal).
        progress: Called ``(done, total)`` after each step of the search (a direction's
            basins found, its extreme solved or mirrored).

    """
    model = needed_model(design, model, geometry, collisions)
    geometry = StanceGeometry.of_design(design, stance, model, geometry)
    collision = SelfCollision(model, geometry) if collisions and model is not None else None
    locked = axis_locked_extremes(geometry)
    if collision is not None:
        locked = collision_limited(geometry, collision, locked)
    search = _Search(FreeProblem(geometry, collision), locked, progress)
    result = FlexibilityResult(
        design,
        geometry.legs,
        "free",
        search.extremes(),
        iterations=search.iterations,
        collisions=collisions,
    )
    result = replace(result, converged=not result.doubts)
    if result.doubts:
        warnings.warn(
            "free-coupled flexibility: the evidence falls short of a maximum for "
            f"{'; '.join(result.doubts)}; the best values found are kept",
            FlexibilityWarning,
            stacklevel=2,
        )
    return result


def search_box(locked: Sequence[Extreme]) -> ArrayF:
    """Half widths (6,) of the box the climbs start in [m, rad]: their unit lengths too.

    :data:`BOX_SCALE` times each coordinate's larger axis-locked extreme.
    """
    value = {(e.axis, e.sign): e.value for e in locked}
    half = np.array([BOX_SCALE * max(abs(value[(a, 1)]), abs(value[(a, -1)])) for a in AXES])
    box: ArrayF = np.maximum(half, 1e-3)
    return box


def axis_locked_start(extreme: Extreme) -> ArrayF:
    """The axis-locked extreme pulled back by a hair: a feasible start on the axis."""
    start = np.zeros(len(AXES))
    start[AXES.index(extreme.axis)] = extreme.value - extreme.sign * 1e-9
    return start


def _seed(k: int, sign: int) -> int:
    return 2 * k + (sign > 0)


class _Search:
    """The twelve free extremes of one stance (see the module's description)."""

    def __init__(
        self,
        problem: FreeProblem,
        locked: Sequence[Extreme],
        progress: Callable[[int, int], None] | None = None,
    ) -> None:
        self.problem = problem
        self.locked = tuple(locked)
        self.box = search_box(locked)
        self.iterations = 0
        self.progress = progress

    def extremes(self) -> tuple[Extreme, ...]:
        """Every direction: solved, or taken from its mirror image where that holds."""
        directions = [(e.axis, e.sign) for e in self.locked]
        sources = mirror_sources(directions, self.problem.flips)
        own = len(self.locked) - len(sources)  # directions solved, not mirrored
        total = 2 * own + len(sources)  # each own one's basins and solve, each mirror
        done = iter(range(1, total + 1))

        def step() -> None:
            if self.progress is not None:
                self.progress(next(done), total)

        basins = {}
        for i, e in enumerate(self.locked):
            if i not in sources:
                basins[i] = self.basins(e)
                step()
        tips = {i: found[0].points[0] for i, (found, _) in basins.items() if found}
        solved = {}
        for i, found in basins.items():
            starts = [tip for j, tip in tips.items() if j != i] + self.symmetric(i, tips)
            solved[i] = self.solve(
                self.locked[i], *self.with_climbs_from(self.locked[i], starts, *found)
            )
            step()
        for i, (source, flip) in sources.items():
            mirrored = self.mirrored(self.locked[i], solved[source], flip)
            if mirrored is None:
                mirrored = self.solve(self.locked[i], *self.basins(self.locked[i]))
            solved[i] = mirrored
            step()
        return tuple(solved[i] for i in range(len(self.locked)))

    def symmetric(self, i: int, tips: dict[int, ArrayF]) -> list[ArrayF]:
        """Direction i's best point made symmetric under each mirror that keeps its coordinate.

        The mean of the point and its image: optima on a plane of symmetry draw few
        climbs from starts off it.
        """
        if i not in tips:
            return []
        k = AXES.index(self.locked[i].axis)
        return [(tips[i] + flip * tips[i]) / 2 for flip in keeping(k, self.problem.flips)]

    def mirrored(self, locked: Extreme, source: Extreme, flip: ArrayF) -> Extreme | None:
        """``locked``'s direction as the mirror image of ``source``, if that holds.

        The mirrored pose must pass the exact check and reach the axis-locked extreme;
        its binding constraints are found there.
        """
        image = flip * np.asarray(source.pose)
        d: ArrayF | None = image
        k = AXES.index(locked.axis)
        if self.problem.collision is not None:  # coal tells mirror images apart by 1e-7 m
            d = self.problem.feasible_nearby(image)
        if d is None or not self.problem.feasible(d):
            return None
        if locked.sign * d[k] < locked.sign * locked.value:
            return None
        extreme = pose_extreme(
            self.problem.geometry, locked.axis, locked.sign, d, self.problem.binding(d)
        )
        return replace(extreme, evidence=source.evidence)

    def solve(self, locked: Extreme, basins: list[Basin], climbs: int) -> Extreme:
        """The free extreme of ``locked``'s direction from its climbs' basins.

        Never short of ``locked`` itself.
        """
        k, sign = AXES.index(locked.axis), locked.sign
        if self.problem.collision is None:
            starts = [basin.tries() for basin in basins]
        else:
            starts = self.collision_starts(locked, basins)
        answer, evidence = self.best_reachable(k, sign, locked, starts, basins, climbs)
        if answer is None:
            return replace(locked, evidence=evidence)
        pose = self.problem.canonical(answer, k)
        extreme = pose_extreme(
            self.problem.geometry, locked.axis, sign, pose, self.problem.binding(pose)
        )
        return replace(extreme, evidence=evidence)

    def collision_starts(self, locked: Extreme, basins: list[Basin]) -> list[tuple[ArrayF, ...]]:
        """With self-collision, the polish's starts: each entry's points are tried in turn.

        The axis-locked extreme; the best basins, each from its first pose clear of
        collision on the way back; and, where the best basin's parts touch (else it
        bounds the answer), clear draws pushed along the direction (:mod:`.collision_starts`).
        """
        k, sign = AXES.index(locked.axis), locked.sign
        starts: list[tuple[ArrayF, ...]] = [(axis_locked_start(locked),)]
        for basin in basins[:COLLISION_BASINS]:
            clear = self.problem.clear_on_the_way_back(basin.points[0], self.box)
            starts.append(basin.tries() if clear is None else (clear, *basin.tries()))
        if not basins or self.problem.touching(basins[0].points[0]):
            spread = spread_starts(self.problem, k, sign, self.box, _seed(k, sign))
            starts += [(start,) for start in spread]
        return starts

    def basins(self, locked: Extreme) -> tuple[list[Basin], int]:
        """Basins of the first climbs, best first, and how many climbs ran.

        From the axis-locked extreme and from :data:`CLIMBS` spread starts.
        """
        k, sign = AXES.index(locked.axis), locked.sign
        spread = box_starts(SPREAD * self.box, CLIMBS, seed=_seed(k, sign))
        return self.with_climbs_from(locked, [axis_locked_start(locked), *spread], [], 0)

    def with_climbs_from(
        self, locked: Extreme, starts: Sequence[ArrayF], basins: list[Basin], climbs: int
    ) -> tuple[list[Basin], int]:
        """``basins`` and ``climbs`` with those of climbs from ``starts`` added."""
        k, sign = AXES.index(locked.axis), locked.sign
        if not starts:
            return basins, climbs
        ends, iterations = climb_all(
            self.problem.smooth_kernel, np.array(starts), self.box, k, float(sign), LOWER, UPPER
        )
        self.iterations += int(iterations.sum())
        margins = self.problem.exact_margins(ends).min(axis=-1)
        members = [
            (float(sign * end[k]), end, float(margin))
            for end, margin in zip(ends, margins, strict=True)
            if margin >= -CLIMB_TOLERANCE
        ]
        for basin in basins:
            members += [
                (v, p, m) for v, p, m in zip(basin.values, basin.points, basin.margins, strict=True)
            ]
        return grouped(members), climbs + len(starts)

    def best_reachable(
        self,
        k: int,
        sign: int,
        locked: Extreme,
        starts: Sequence[Sequence[ArrayF]],
        basins: Sequence[Basin],
        climbs: int,
    ) -> tuple[ArrayF | None, SearchEvidence]:
        """The best polished answer from ``starts`` that is reachable (None: keep ``locked``).

        Each entry of ``starts`` is polished (its points in turn until one gives an
        answer) while it could still beat the best reachable answer so far: a climb's
        value is a lower bound on its polished one.
        """
        floor, problem = sign * locked.value, self.problem.coordinate_problem(k, sign)
        best: MultiStartResult | None = None
        unreachable: float | None = None
        answers: list[float] = []
        for i, start in enumerate(starts):
            bound = basins[i].value if self.problem.collision is None else np.inf
            if best is not None and bound <= best.value + BASIN_TOLERANCE:
                break
            result = self.polished(problem, start, bound)
            if result is None:
                continue
            answers.append(result.value)
            if result.value <= floor or (best is not None and result.value <= best.value):
                continue
            if self.problem.reachable(result.x, self.box):
                best = result
            elif unreachable is None or result.value > unreachable:
                unreachable = result.value
        if best is not None and not best.success and self.problem.collision is not None:
            again = self.polished(problem, [best.x], np.inf)  # a fresh quasi-Newton model
            if again is not None and again.value > best.value:
                answers.append(again.value)
                best = again if self.problem.reachable(again.x, self.box) else best
        evidence = self.evidence(best, floor, unreachable, basins, climbs, answers)
        return (None if best is None else best.x), evidence

    def polished(
        self, problem: CoordinateProblem, points: Sequence[ArrayF], value: float
    ) -> MultiStartResult | None:
        """The best SLSQP answer from ``points`` in turn, stopping at one that reaches ``value``.

        A basin's climbs reached ``value``: a polish that ends lower went astray, and
        one where SLSQP does not report convergence is tried again from the next point.
        With self-collision (``value`` inf) every point is: coal's distances jolt SLSQP.
        """
        best: MultiStartResult | None = None
        for point in points:
            result = maximize_coordinate(problem, [Start(point, self.box)])
            if result is None:
                result = self.unpolished(problem, point)
            if result is None:
                continue
            self.iterations += result.iterations
            tolerance = AGREEMENT * max(1.0, abs(result.value))
            if best is None or result.value > best.value + tolerance:
                best = result
            elif result.value >= best.value - tolerance and result.success and not best.success:
                best = result  # the same optimum, where SLSQP also says it converged
            if best.success and best.value >= value - AGREEMENT * max(1.0, abs(value)):
                break
        return best

    def unpolished(self, problem: CoordinateProblem, point: ArrayF) -> MultiStartResult | None:
        """A climb's end as the answer where SLSQP gave none (flagged: not polished)."""
        x = self.problem.feasible_nearby(point)
        if x is None:
            return None
        value = float(problem.sign * x[problem.k])
        return MultiStartResult(x, value, False, False, (value,), 0)

    def evidence(
        self,
        best: MultiStartResult | None,
        floor: float,
        unreachable: float | None,
        basins: Sequence[Basin],
        climbs: int,
        answers: Sequence[float],
    ) -> SearchEvidence:
        """What supports the direction's answer (``best``, or the axis-locked ``floor``)."""
        value = floor if best is None else best.value
        if unreachable is not None and unreachable <= value:
            unreachable = None
        tolerance = BASIN_TOLERANCE * max(1.0, abs(value))
        if self.problem.collision is None:
            agreeing = sum(b.climbs for b in basins if abs(b.value - value) <= tolerance)
            return SearchEvidence(
                climbs, len(basins), agreeing, True, best is None or best.success, unreachable
            )
        distinct = len({round(a / tolerance) for a in answers})
        agreeing = sum(abs(a - value) <= tolerance for a in answers)
        return SearchEvidence(
            len(answers), distinct, agreeing, True, best is None or best.success, unreachable
        )
