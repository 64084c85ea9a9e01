"""Requirements in, design out: the best design that meets them, and yours checked beside it.

:func:`decide` searches the free variables (:mod:`hexaleg.study.search_space`) for the
design with the best objective among those meeting every requirement
(:mod:`hexaleg.study.optimize`), then measures the winner again with the exact
single-design analyses (its own URDF and Pinocchio model, nothing derived) before
reporting it: every requirement's value, margin, whether it binds and what limits it,
and every joint over its rating — standing with the payload at the nominal stance and the
twelve axis-locked extremes (:attr:`~hexaleg.statics.loads.LoadsAnalysis.over_rating`),
and walking the requirements' gait when one is walked
(:attr:`~hexaleg.gait.analysis.GaitAnalysis.over_rating`). The user's design is measured
the same way and checked against each requirement. When no design within the bounds
meets them all, :mod:`hexaleg.study.conflict` names the requirements that conflict and
the nearest relaxation of each.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator, Sequence
from concurrent.futures import Executor
from contextlib import contextmanager
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg._version import __version__
from hexaleg.actuators import Actuator
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.evaluate import Evaluation
from hexaleg.evaluation.goal import Goal, Objective
from hexaleg.evaluation.requirement_specs import LEG_LENGTH, MIN_COXA, RANGE_KM
from hexaleg.evaluation.requirements import RequirementCheck, Requirements
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.gait.analysis import analyze_gait
from hexaleg.gait.spec import Gait
from hexaleg.kinematics import foot_position
from hexaleg.ratings import require_ratings
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.robot import Robot, as_robot
from hexaleg.stance.flexibility import flexibility
from hexaleg.statics.forces import Payload
from hexaleg.statics.ground import Ground
from hexaleg.statics.loads import loads_at_extremes
from hexaleg.statics.ratings import OverRating, furthest_first
from hexaleg.study.conflict import Conflict, find_conflict
from hexaleg.study.decide_grid import Rounded, Rounding, Score, grid_search
from hexaleg.study.executors import local_pool
from hexaleg.study.optimize import (
    SearchOutcome,
    SearchSettings,
    evaluate_batch,
    objective_and_constraints,
    run_search,
)
from hexaleg.study.search_journal import Journal
from hexaleg.study.search_space import (
    AtBound,
    FreeVariable,
    SearchSpace,
    bounds_reached,
    search_space,
)

POSTURE_FIELD = "nominal_angles"
"""The design field a posture search frees."""

REMEASURED = 4
"""Grid points around the search's best, the best first, measured again from their URDF
before the nearest (breaking a requirement) is answered instead."""


@dataclass(frozen=True)
class WalkCheck:
    """The requirements' gait walked on one ground by one design, its joints flagged.

    Attributes:
        ground: The ground walked (level, or the walking slope up, down or across).
        over_rating: Each joint over its rated torque or speed walking it (none when it
            cannot be walked at all).
        violation: The gait's first broken constraint when it cannot be walked at all (a
            foothold out of reach: speeds without bound); empty otherwise.

    """

    ground: Ground
    over_rating: tuple[OverRating, ...] = ()
    violation: str = ""

    def where(self, gait: Gait) -> str:
        """``walking at 0.3 m/s`` on level ground, ``walking at 0.3 m/s uphill on 10°`` else."""
        ground, text = self.ground, f"walking at {gait.speed:.4g} m/s"
        if ground.level:
            return text
        return text + f" {ground.way(gait.heading)} on {math.degrees(abs(ground.slope)):.3g}°"


@dataclass(frozen=True)
class CheckedDesign:
    """One design measured with the exact single-design analyses and checked.

    Attributes:
        design: The design (its tubes sized, where its ``[structure]`` asks).
        evaluation: Its metrics (what the requirements and the objective need).
        checks: Each requirement checked on it.
        standing_over_rating: Each joint over its rated torque / F carrying the required
            payload, at the nominal stance or an axis-locked extreme.
        walks: The requirements' gait walked on each ground, its joints over their
            ratings / F flagged (none when no gait is walked).

    """

    design: HexapodDesign
    evaluation: Evaluation
    checks: tuple[RequirementCheck, ...]
    standing_over_rating: tuple[OverRating, ...] = ()
    walks: tuple[WalkCheck, ...] = ()

    @classmethod
    def of(cls, robot: Robot, goal: Goal) -> CheckedDesign:
        """Measure ``robot`` from its own URDF and model, check it, flag joints over ratings.

        Where its ``[structure]`` sizes the tubes, the design checked is the sized one.
        """
        conditions = goal.conditions
        payload, factor = conditions.payload, conditions.safety_factor
        design = robot.design
        try:
            model = robot.rebuilt().model
            locked = flexibility(design, "axis", model=model)
        except HexalegError as err:
            return cls(design, Evaluation(error=str(err)), ())
        evaluation = goal.evaluate(design, model, flexibility=locked)
        if evaluation.sized is not None:  # the tubes' masses: every flag is the sized design's
            design = evaluation.sized.design
            model = model.with_design(design)
        try:
            standing = loads_at_extremes(model, locked, payload, safety_factor=factor).over_rating
        except HexalegError as err:
            return cls(design, Evaluation(error=str(err)), ())
        if evaluation.error:
            return cls(design, evaluation, (), standing)
        if not goal.walks:
            return cls(design, evaluation, goal.checks(evaluation), standing)
        walks = tuple(
            _walked(design, model, conditions.gait, payload, ground, factor)
            for ground in conditions.grounds
        )
        return cls(design, evaluation, goal.checks(evaluation), standing, walks)

    @property
    def walking_over_rating(self) -> tuple[OverRating, ...]:
        """Each joint over its rating walking, on every ground walked."""
        return tuple(flag for walk in self.walks for flag in walk.over_rating)

    @property
    def walking_violation(self) -> str:
        """The first broken constraint of a walk that cannot be walked at all (or empty)."""
        return next((walk.violation for walk in self.walks if walk.violation), "")

    def over_rating_groups(self, result: DecideResult) -> list[tuple[str, list[OverRating]]]:
        """(where, flags furthest over first) standing with the payload, and each walk."""
        payload = result.requirements.payload_mass
        standing = f"standing with {payload:g} kg" if payload else "standing without payload"
        groups = [(standing, furthest_first(self.standing_over_rating))]
        if result.walks:
            gait = result.requirements.gait
            groups += [(walk.where(gait), furthest_first(walk.over_rating)) for walk in self.walks]
        return groups

    def over_rating(self, gait: Gait | None = None) -> list[dict[str, Any]]:
        """Every joint over its rating, JSON-ready, each saying ``while`` standing or walking.

        A walking flag also names its ``ground`` (walking ``gait``'s heading).
        """
        heading = 0.0 if gait is None else gait.heading
        return [o.to_dict() | {"while": "standing"} for o in self.standing_over_rating] + [
            o.to_dict() | {"while": "walking", "ground": walk.ground.to_dict(heading)}
            for walk in self.walks
            for o in walk.over_rating
        ]

    @property
    def meets_all(self) -> bool:
        """Whether it was measured and meets every requirement."""
        return not self.evaluation.error and all(c.met for c in self.checks)

    def objective(self, objective: Objective) -> dict[str, Any]:
        """The objective's name, sense, value, unit and what limits it, JSON-ready."""
        cause = self.evaluation.causes[objective.spec]
        return {
            "name": objective.name,
            "sense": objective.sense,
            "value": self.evaluation.metrics[objective.spec],
            "unit": objective.spec.unit,
            "limited_by": None if cause is None else cause.to_dict(),
        }


@dataclass(frozen=True)
class DecideResult:
    """The decision: the best design, yours, and what conflicts if nothing is feasible.

    Attributes:
        requirements: The requirements, resolved (the leg length set).
        objective: What was made best.
        variables: The free variables and their bounds.
        best: The best design found (the least infeasible if none is feasible), re-measured.
        yours: The user's design, measured and checked.
        feasible: Whether the best design meets every requirement.
        conflict: The conflicting requirements and their relaxations (when infeasible).
        method: The search algorithm and its settings.
        evaluations: Designs evaluated by the search (and the conflict's searches).
        seed: The search's seed.
        robot: The robot file whose segments were searched (``None``: hexaleg's template's
            designs).
        rounded: How the best design was put on a workshop's grid (``None``: as found).

    """

    requirements: Requirements
    objective: Objective
    variables: tuple[FreeVariable, ...]
    best: CheckedDesign
    yours: CheckedDesign
    feasible: bool
    conflict: Conflict | None
    method: str
    evaluations: int
    seed: int
    robot: str | None = None
    rounded: Rounded | None = None

    @property
    def bounds_binding(self) -> tuple[AtBound, ...]:
        """Each free variable the best design holds at a search bound: that bound binds.

        l1 at a ``min_coxa`` bound is left out: that requirement's check says it binds.
        """
        coxa = self.requirements.required(MIN_COXA)
        rounding = None if self.rounded is None else self.rounded.rounding
        steps = {v.name: None if rounding is None else rounding.step(v) for v in self.variables}
        return tuple(
            at
            for at in bounds_reached(self.variables, self.best.design, steps)
            if not (at.variable.name == "l1" and at.bound == "lower" and at.value == coxa)
        )

    def postures(self) -> tuple[dict[str, Any], dict[str, Any]] | None:
        """The best design's and yours' :func:`posture_figures`, or ``None``.

        Eq 7 holds for hexaleg's legs only: a robot file's posture is the file's.
        """
        if self.robot is not None:
            return None
        return posture_figures(self.best.design), posture_figures(self.yours.design)

    @property
    def walks(self) -> bool:
        """Whether the designs walk a gait (a walking requirement or objective)."""
        return Goal(self.requirements, self.objective).walks

    def walking_text(self) -> str:
        """The gait the designs walk and what is measured on it, in words."""
        speed = self.requirements.gait.speed
        worst = "; each the worst of the three walks" if self.requirements.walking_slope else ""
        return (
            f"{self.requirements.walking_conditions()}; speed: the fastest within the "
            f"ratings at that stride; peak torque and cost of transport at {speed:.4g} m/s" + worst
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI units, radians)."""
        best_posture, your_posture = self.postures() or ({}, {})
        out: dict[str, Any] = {
            "requirements": {c.name: c.to_dict(binding=True) for c in self.best.checks},
            "best": {
                **best_posture,
                "design": self.best.design.as_dict(),
                "objective": self.best.objective(self.objective),
                "over_rating": self.best.over_rating(self.requirements.gait),
                "walking_violation": self.best.walking_violation or None,
                "bounds_binding": [at.to_dict() for at in self.bounds_binding],
            },
            "yours": {
                **your_posture,
                "design": self.yours.design.as_dict(),
                "objective": self.yours.objective(self.objective),
                "requirements": {c.name: c.to_dict(binding=False) for c in self.yours.checks},
                "over_rating": self.yours.over_rating(self.requirements.gait),
                "walking_violation": self.yours.walking_violation or None,
            },
            "feasible": self.feasible,
        }
        if self.robot is not None:
            out["robot"] = self.robot
        if self.walks:
            out["gait"] = self.requirements.gait.to_dict() | {
                "payload": self.requirements.payload_mass
            }
        if self.conflict is not None:
            out["conflict"] = self.conflict.to_dict()
        if self.rounded is not None:
            out["rounded"] = self.rounded.to_dict()
        out["search"] = {
            "method": self.method,
            "evaluations": self.evaluations,
            "seed": self.seed,
            "free": {v.name: [v.lower, v.upper] for v in self.variables},
        }
        return out


def _walked(
    design: HexapodDesign,
    model: HexapodModel,
    gait: Gait,
    payload: Payload,
    ground: Ground,
    factor: float,
) -> WalkCheck:
    """The gait walked on ``ground`` with the payload, its joints over rating / F flagged."""
    walked = analyze_gait(
        design, gait, payload, ground=ground, model=model, limits=False, safety_factor=factor
    )
    if walked.violations:
        return WalkCheck(ground, (), str(walked.violations[0]))
    return WalkCheck(ground, walked.over_rating)


def posture_figures(design: HexapodDesign) -> dict[str, Any]:
    """What a posture means for the robot: its body height and its legs' reach [m, rad].

    ``nominal_angles`` (θ1, θ2, θ3) [rad]; ``nominal_height``, the body frame above the
    ground; ``foothold_radius``, each nominal foothold's horizontal distance from its leg's
    root (eq 7: l1 + l2·cos θ2 + l3·cos(θ2 + θ3) at θ1 = 0) [m].
    """
    x, y, _ = foot_position(design.lengths, design.nominal_angles)
    return {
        "nominal_angles": list(design.nominal_angles),
        "nominal_height": design.nominal_height,
        "foothold_radius": float(math.hypot(x, y)),
    }


def decide(
    robot: Robot | HexapodDesign,
    requirements: Requirements | None = None,
    objective: Objective | None = None,
    *,
    free_posture: bool = True,
    free: Sequence[FreeVariable] = (),
    actuators: Sequence[Actuator] = (),
    ratio_ranges: Sequence[tuple[float, float] | None] | None = None,
    settings: SearchSettings | None = None,
    executor: Executor | None = None,
    workers: int | None = None,
    journal: str | os.PathLike[str] | None = None,
    resume: bool = False,
    progress: bool | None = None,
    rounding: Rounding | None = None,
) -> DecideResult:
    """The best design of ``robot`` meeting ``requirements``, by ``objective``, and it checked.

    Args:
        robot: The user's robot (a design: hexaleg's template at it): its fields not freed,
            the start, and the design checked beside the best.
        requirements: What the robot must do (none by default; leg length: the robot's).
        objective: What to make best (default: maximize FB).
        free_posture: Also free the nominal hip and knee angles within the stance limits,
            where the robot lets a search (a robot file's posture is its file's).
        free: More free variables (body fields), or other bounds for l1, l2, l3.
        actuators: A catalog's actuators to choose each joint type's from (none: its own).
        ratio_ranges: One per actuator, its lowest and highest gear ratio [-] (None: its
            own only): also free each joint type's within its entry's.
        settings: Seed and budget of the search.
        executor: Where designs are evaluated; a local pool of ``workers`` if omitted.
        workers: Size of that pool (default: the number of CPUs).
        journal: A file keeping every evaluated design (JSON lines), to resume from.
        resume: Continue ``journal`` instead of refusing to overwrite it.
        progress: ``False`` shows nothing; else a bar on a terminal, a line every few seconds.
        rounding: The grids the best design is put on and measured at (:func:`workshop_answer`).

    Raises:
        ParameterError: No design, ``resume`` without ``journal``, a bound out of range, a
            rating not given; a robot file without masses (``RobotImportError``).

    """
    robot, settings = _robot(robot), settings or SearchSettings()
    _check_arguments(journal, resume)
    goal = _goal(design := robot.design, requirements, objective, bool(actuators))
    space = _space(robot, goal.requirements, free_posture, free, actuators, ratio_ranges, settings)
    kept = Journal(journal, _fingerprint(design, goal, space, settings), resume)
    with kept, _executor(executor, workers) as pool:
        search = _Searches(design, settings, pool, kept, progress)
        outcome, conflict = _search_or_conflict(space, goal, search)
        grid = rounding or Rounding()
        best, rounded = workshop_answer(space, goal, outcome.x, outcome.feasible, grid, pool)
    return DecideResult(
        requirements=goal.requirements, objective=goal.objective, variables=space.variables,
        best=best, yours=CheckedDesign.of(robot, goal), feasible=best.meets_all,
        conflict=conflict, method=outcome.method, seed=settings.seed,
        evaluations=sum(found.evaluations for found in search.done),
        robot=robot.source.path, rounded=rounded,
    )  # fmt: skip


def workshop_answer(
    space: SearchSpace,
    goal: Goal,
    x: npt.ArrayLike,
    feasible: bool,
    rounding: Rounding,
    executor: Executor | None,
) -> tuple[CheckedDesign, Rounded]:
    """The search's best ``x`` on the workshop's grid, measured again from its own URDF.

    When ``x`` meets every requirement (``feasible``), the grid points around it are
    measured as the search measures (on ``executor``; :func:`~.decide_grid.grid_search`)
    and the best of those meeting every requirement, measured again, is the answer (up to
    :data:`REMEASURED` tried, best first). Otherwise, or if none does, the grid point
    nearest ``x``.
    """
    searched = tuple(float(v) for v in np.asarray(x, dtype=float))
    nearest = rounding.rounded(space, x)
    units = tuple(v.unit for v in space.variables)
    answer = Rounded(rounding, space.names, searched, tuple(float(v) for v in nearest), 0, units)
    if not feasible:
        return _checked_at(space, nearest, goal), answer

    def scores(points: list[ArrayF]) -> list[Score]:
        measured = evaluate_batch(space, goal, points, executor)
        found = [objective_and_constraints(goal, evaluation) for evaluation in measured]
        return [(float(np.maximum(g, 0.0).sum()), cost) for cost, g in found]

    ranked = grid_search(rounding, space, x, scores)
    answer = replace(answer, measured=len(ranked))
    for (violation, _), point in ranked[:REMEASURED]:
        if violation > 0:
            break
        checked = _checked_at(space, point, goal)
        if checked.meets_all:
            return checked, replace(answer, answer=tuple(float(v) for v in point))
    return _checked_at(space, nearest, goal), answer


def _checked_at(space: SearchSpace, point: npt.ArrayLike, goal: Goal) -> CheckedDesign:
    """The space's robot at ``point`` measured from its own URDF (an error if it cannot be)."""
    try:
        robot = space.robot_at(point)
    except HexalegError as err:
        return CheckedDesign(space.base, Evaluation(error=str(err)), ())
    return CheckedDesign.of(robot, goal)


def _goal(
    design: HexapodDesign,
    requirements: Requirements | None,
    objective: Objective | None,
    actuators: bool,
) -> Goal:
    """The decision's goal: the requirements resolved (the leg length set), the objective."""
    resolved = (requirements or Requirements()).resolved(design)
    return Goal(resolved, objective or Objective()).measurable(design, actuators)


def _space(
    robot: Robot,
    requirements: Requirements,
    free_posture: bool,
    free: Sequence[FreeVariable],
    actuators: Sequence[Actuator],
    ratio_ranges: Sequence[tuple[float, float] | None] | None,
    settings: SearchSettings,
) -> SearchSpace:
    """What the search varies; a budget of partial generations is refused before any work.

    Only the fields the robot lets a search free (:meth:`~hexaleg.robot.robot.Robot.searches`:
    a robot file's segments; its posture, motors and body are its file's).
    """
    refused = [v for v in free if not robot.searches(v.name)]
    if refused:
        typed = f"{refused[0].name}={refused[0].typed}"
        raise ParameterError("--free", typed, "with --urdf, one of l1, l2, l3 (the segments)")
    space = search_space(
        robot.design,
        requirements.required(LEG_LENGTH) or 0.0,
        requirements.required(MIN_COXA),
        free_posture and robot.searches(POSTURE_FIELD),
        free,
        actuators,
        requirements.required(RANGE_KM) is not None,
        ratio_ranges,
        robot,
    )
    settings.generations(len(space.variables))
    return space


def _robot(given: Robot | HexapodDesign) -> Robot:
    """The robot decided on (a design: hexaleg's template at it), weighed and rated.

    Raises:
        RobotImportError: A robot file without masses (the payloads and torques need them).
        ParameterError: A rating the robot does not give.

    """
    given = as_robot(given)
    given.require_masses()
    require_ratings(given.design.rated_torques, given.design.rated_speeds, "decide")
    return given


def _check_arguments(journal: str | os.PathLike[str] | None, resume: bool) -> None:
    if resume and journal is None:
        raise ParameterError("resume", resume, "continues a journal: give journal=FILE")


class _Searches:
    """Runs the searches of one decision, all from the user's design among other starts."""

    def __init__(
        self,
        design: HexapodDesign,
        settings: SearchSettings,
        executor: Executor,
        journal: Journal,
        progress: bool | None,
    ) -> None:
        self.design, self.settings, self.executor = design, settings, executor
        self.journal, self.progress = journal, progress
        self.done: list[SearchOutcome] = []

    def __call__(self, space: SearchSpace, goal: Goal, *starts: npt.ArrayLike) -> SearchOutcome:
        """The outcome of one search of ``space`` for ``goal``."""
        starts = (*starts, space.point(self.design))
        found = run_search(
            space, goal, self.settings, self.executor, self.journal, self.progress, starts
        )
        self.done.append(found)
        return found


def _search_or_conflict(
    space: SearchSpace, goal: Goal, search: _Searches
) -> tuple[SearchOutcome, Conflict | None]:
    """The best design; if none meets every requirement, also what conflicts."""
    outcome = search(space, goal)
    if outcome.feasible:
        return outcome, None
    if outcome.evaluation.error:  # the least infeasible design cannot even be measured
        bounds = ", ".join(f"{v.name} {v.typed}" for v in space.variables)
        raise HexalegError(
            f"no design within the search bounds ({bounds}) can be measured: "
            f"{outcome.evaluation.error}"
        )
    least = outcome
    conflict = find_conflict(space, goal, least.evaluation, lambda s, g: search(s, g, least.x))
    missed = [r.point for r in conflict.relaxations if r.meets_original]
    if missed:  # a relaxed search met everything after all: search again from there
        outcome = search(space, goal, *missed)
        if outcome.feasible:
            return outcome, None
    return outcome, conflict


@contextmanager
def _executor(executor: Executor | None, workers: int | None) -> Iterator[Executor]:
    if executor is not None:
        yield executor
        return
    with local_pool(workers) as pool:
        yield pool


def _fingerprint(
    design: HexapodDesign, goal: Goal, space: SearchSpace, settings: SearchSettings
) -> dict[str, Any]:
    """Everything that determines a decision's searches (a resumed journal must match)."""
    return {
        "hexaleg": __version__,
        "design": design.as_dict(),
        "requirements": goal.requirements.to_dict(),
        "objective": str(goal.objective),
        "free": [[v.name, v.lower, v.upper] for v in space.variables],
        "actuators": [a.to_table() for a in space.entries],
        "ratio_ranges": [None if r is None else [*r] for r in space.ratio_ranges],
        "seed": settings.seed,
        "evaluations": settings.evaluations,
        **space.robot.fingerprint(),
    }
