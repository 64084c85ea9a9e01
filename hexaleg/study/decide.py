"""Requirements in, design out: the best design that meets them, and yours checked beside it.

:func:`decide` searches the free variables (:mod:`hexaleg.study.search_space`) for the
design with the best objective among those meeting every requirement
(:mod:`hexaleg.study.optimize`), then measures the winner again with the exact
single-design analyses (its own URDF and Pinocchio model, nothing derived) before
reporting it: every requirement's value, margin and whether it binds. The user's design
is measured the same way and checked against each requirement. When no design within
the bounds meets them all, :mod:`hexaleg.study.conflict` names the requirements that
conflict and the nearest relaxation of each.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Sequence
from concurrent.futures import Executor
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import numpy.typing as npt

from hexaleg._version import __version__
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.study.conflict import Conflict, find_conflict
from hexaleg.study.evaluation import (
    GAIT_METRICS,
    METRIC_UNITS,
    Evaluation,
    Goal,
    Objective,
    evaluate_design,
)
from hexaleg.study.executors import local_pool
from hexaleg.study.optimize import SearchOutcome, SearchSettings, run_search
from hexaleg.study.requirements import RequirementCheck, Requirements
from hexaleg.study.search_journal import Journal
from hexaleg.study.search_space import FreeVariable, SearchSpace, search_space


@dataclass(frozen=True)
class CheckedDesign:
    """One design measured with the exact single-design analyses and checked.

    Attributes:
        design: The design.
        evaluation: Its metrics (what the requirements and the objective need).
        checks: Each requirement checked on it.

    """

    design: HexapodDesign
    evaluation: Evaluation
    checks: tuple[RequirementCheck, ...]

    @classmethod
    def of(cls, design: HexapodDesign, goal: Goal) -> CheckedDesign:
        """Measure ``design`` from its own URDF and model, and check it."""
        evaluation = evaluate_design(design, goal)
        checks = () if evaluation.error else evaluation.checks(goal.requirements)
        return cls(design, evaluation, checks)

    @property
    def meets_all(self) -> bool:
        """Whether it was measured and meets every requirement."""
        return not self.evaluation.error and all(c.met for c in self.checks)

    def objective(self, objective: Objective) -> dict[str, Any]:
        """The objective's name, sense, value and unit, JSON-ready."""
        value = self.evaluation.values.get(objective.name)
        return {"name": objective.name, "sense": objective.sense, "value": value,
                "unit": METRIC_UNITS[objective.name]}  # fmt: skip


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

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI units, radians)."""
        out: dict[str, Any] = {
            "requirements": {c.name: c.to_dict(binding=True) for c in self.best.checks},
            "best": {
                "design": self.best.design.as_dict(),
                "objective": self.best.objective(self.objective),
            },
            "yours": {
                "design": self.yours.design.as_dict(),
                "objective": self.yours.objective(self.objective),
                "requirements": {c.name: c.to_dict(binding=False) for c in self.yours.checks},
            },
            "feasible": self.feasible,
        }
        if self.conflict is not None:
            out["conflict"] = self.conflict.to_dict()
        out["search"] = {
            "method": self.method,
            "evaluations": self.evaluations,
            "seed": self.seed,
            "free": {v.name: [v.lower, v.upper] for v in self.variables},
        }
        return out


def decide(
    design: HexapodDesign,
    requirements: Requirements | None = None,
    objective: Objective | None = None,
    *,
    free_posture: bool = False,
    free: Sequence[FreeVariable] = (),
    settings: SearchSettings | None = None,
    executor: Executor | None = None,
    workers: int | None = None,
    journal: str | os.PathLike[str] | None = None,
    resume: bool = False,
    progress: bool | None = None,
) -> DecideResult:
    """The best design meeting ``requirements``, by ``objective``, and ``design`` checked.

    Args:
        design: The user's design: every field not freed, and the design checked.
        requirements: What the robot must do (none by default; the leg length defaults
            to ``design``'s).
        objective: What to make best (default: maximize FB).
        free_posture: Also free the nominal hip and knee angles.
        free: More free variables (body fields), or other bounds for l1, l2, l3.
        settings: Seed and budget of the search.
        executor: Where designs are evaluated; a local process pool if omitted.
        workers: Size of that pool (default: the number of CPUs).
        journal: A file keeping every evaluated design (JSON lines), to resume from.
        resume: Continue ``journal`` instead of refusing to overwrite it.
        progress: Show a progress bar on stderr; by default only on a terminal.

    """
    requirements = (requirements or Requirements()).resolved(design)
    objective = objective or Objective()
    settings = settings or SearchSettings()
    goal = Goal(requirements, objective)
    _require_available(goal)
    space = search_space(
        design, float(requirements.leg_length or 0), requirements.min_coxa, free_posture, free
    )
    kept = Journal(journal, _fingerprint(design, goal, space, settings), resume)
    with _executor(executor, workers) as pool:
        search = _Searches(design, settings, pool, kept, progress)
        outcome, conflict = _search_or_conflict(space, goal, search)
    best = CheckedDesign.of(space.design(outcome.x), goal)
    return DecideResult(
        requirements=requirements,
        objective=objective,
        variables=space.variables,
        best=best,
        yours=CheckedDesign.of(design, goal),
        feasible=best.meets_all,
        conflict=conflict,
        method=outcome.method,
        evaluations=sum(found.evaluations for found in search.done),
        seed=settings.seed,
    )


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
    least = outcome
    conflict = find_conflict(space, goal, least.evaluation, lambda s, g: search(s, g, least.x))
    missed = [r.point for r in conflict.relaxations if r.meets_original]
    if missed:  # a relaxed search met everything after all: search again from there
        outcome = search(space, goal, *missed)
        if outcome.feasible:
            return outcome, None
    return outcome, conflict


def _require_available(goal: Goal) -> None:
    """Refuse, in one line, the walking metrics until the gait analysis is there."""
    unavailable = set(goal.metrics) & set(GAIT_METRICS)
    if unavailable:
        raise HexalegError(
            f"{', '.join(sorted(unavailable))}: walking requirements and objectives need "
            "hexaleg's gait analysis, not in this version"
        )


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
        "seed": settings.seed,
        "evaluations": settings.evaluations,
    }
