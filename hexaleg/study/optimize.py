"""The search: the best design of a space that meets a goal, by differential evolution (pymoo).

The optimizer is pymoo's differential evolution (``DE/best/1/bin``, CR 0.9, F 0.5: on
the tests' problems it reaches optima where three constraints meet to 10⁻⁶, where
``DE/rand/1/bin`` stops 1 % short), chosen over Optuna for four reasons:

- constraints are first-class: every requirement is an inequality g ≤ 0 and the
  survival is feasibility-first (a feasible design beats any infeasible one; among
  infeasible ones the smaller violation wins), so the search also returns the least
  infeasible design, which the conflict analysis starts from; in Optuna constraints are
  an add-on of some samplers, being reworked in 5.0 (``constraints_func`` deprecated for
  ``Trial.set_constraint``);
- the problem is a few continuous variables with a cheap, deterministic, piecewise-smooth
  objective, where a population method converges to the optimum's neighbourhood (the
  tests hold it within 0.5 % of a dense grid); Optuna's TPE models noisy, expensive
  trials and does not converge tightly, its GP sampler needs PyTorch, its CMA-ES has no
  constraints;
- a generation is a batch of designs evaluated together, so it maps onto any
  ``concurrent.futures.Executor`` (the local process pool or a Dask cluster, as
  :mod:`hexaleg.study.sweep` does) while staying reproducible: the algorithm draws from its
  own seeded generator and sees the results in the order it asked for them, whatever
  order the workers finish in;
- pymoo 0.6.2 is maintained, and keeps its random state in the algorithm, not NumPy's globals.

pymoo offers no storage to resume from; the search keeps its own journal instead: every
evaluated design is appended (JSON lines, on disk before the next generation), and a
resumed search replays the same seeded algorithm, reading the designs it has already
evaluated from the journal. The replay asks for exactly the same points, so a resumed
search ends exactly where an uninterrupted one would.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from concurrent.futures import Executor
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
import numpy.typing as npt
import pymoo
from pymoo.algorithms.soo.nonconvex.de import DE
from pymoo.core.problem import Problem
from scipy.stats import qmc

from hexaleg._checks import require_int
from hexaleg._typing import ArrayF
from hexaleg.evaluation.evaluate import Evaluation
from hexaleg.evaluation.goal import Goal
from hexaleg.evaluation.requirement_specs import ROUNDOFF
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.robot.robot import Robot
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.study.progress import Progress
from hexaleg.study.search_journal import Journal
from hexaleg.study.search_space import SearchSpace

GENERATIONS = 60
"""Generations of a search with the default budget."""

POPULATION_PER_VARIABLE = 10
"""Designs per generation for each free variable (at least :data:`MIN_POPULATION`)."""

MIN_POPULATION = 24
"""Fewest designs per generation."""

MAX_EVALUATIONS = 100_000
"""Most designs one search evaluates: about an hour on 2 cores when only the segments and
the posture are free, far longer when a body field is (each design renders its URDF)."""

VARIANT = "DE/best/1/bin"
"""Mutation from the best design of the generation, one difference, binomial crossover."""

CROSSOVER = 0.9
"""DE crossover rate CR [-]: high, as the lengths interact through the leg-length sum."""

DIFFERENTIAL_WEIGHT = 0.5
"""DE differential weight F [-]."""

CHUNK = 8
"""Designs per executor task: their flexibility is searched together."""

INVALID = 1e6
"""Constraint violation and cost of a design that cannot exist or stand."""


@dataclass(frozen=True)
class SearchSettings:
    """How hard and how a search looks.

    Attributes:
        seed: Seed of the initial designs and the algorithm's generator.
        evaluations: Designs each search evaluates: whole generations of the population
            (:meth:`population`), at least two, at most :data:`MAX_EVALUATIONS`; by default
            :data:`GENERATIONS` generations.

    """

    seed: int = 0
    evaluations: int | None = None

    def __post_init__(self) -> None:
        require_int("seed", self.seed, 0, 2**32 - 1)
        if self.evaluations is not None:
            require_int("evaluations", self.evaluations, 2 * MIN_POPULATION, MAX_EVALUATIONS)

    def population(self, variables: int) -> int:
        """Designs per generation."""
        return max(MIN_POPULATION, POPULATION_PER_VARIABLE * variables)

    def generations(self, variables: int) -> int:
        """Generations, the first being the initial population: exactly :attr:`evaluations`.

        Raises:
            ParameterError: ``evaluations`` is no multiple of the population, at least two
                generations and at most :data:`MAX_EVALUATIONS`.

        """
        if self.evaluations is None:
            return GENERATIONS
        population = self.population(variables)
        generations, rest = divmod(self.evaluations, population)
        if rest or not 2 <= generations or self.evaluations > MAX_EVALUATIONS:
            below = max(2, generations) * population
            offer = sorted({n for n in (below, below + population) if n <= MAX_EVALUATIONS})
            raise ParameterError(
                "evaluations",
                self.evaluations,
                f"whole generations of {population} designs ({POPULATION_PER_VARIABLE} a free "
                f"variable, at least {MIN_POPULATION}) for {variables} free variables, at least "
                f"two, at most {MAX_EVALUATIONS}: e.g. " + " or ".join(map(str, offer)),
            )
        return generations


@dataclass(frozen=True)
class SearchOutcome:
    """What a search found.

    Attributes:
        x: The best point (the feasible one with the best objective, else the least
            infeasible).
        evaluation: Its metrics, as the search measured them.
        feasible: Whether it meets every constraint of the goal.
        evaluations: Designs evaluated (journal replays included).
        method: The algorithm and its settings, in words.

    """

    x: ArrayF
    evaluation: Evaluation
    feasible: bool
    evaluations: int
    method: str


# -- evaluating designs in workers --------------------------------------------------------


@dataclass(frozen=True)
class _Task:
    space: SearchSpace
    goal: Goal
    points: tuple[tuple[float, ...], ...]


@lru_cache(maxsize=4)
def _template(robot: Robot) -> StanceGeometry | None:
    """The stance geometry the space's designs of the robot's body derive from (or None)."""
    return StanceGeometry.template_of(robot.model)


def evaluate_points(task: _Task) -> list[Evaluation]:
    """The evaluation of each point of a task (runs in a worker): the space's robot at it."""
    space, goal = task.space, task.goal
    robots: dict[int, Robot] = {}
    out: dict[int, Evaluation] = {}
    for k, x in enumerate(task.points):
        try:
            robots[k] = space.robot_at(x)
        except HexalegError as err:
            out[k] = Evaluation(error=str(err))
    template = _template(space.robot) if space.same_body else None
    designs = [robot.design for robot in robots.values()]
    found = goal.evaluate_many(designs, [robot.model for robot in robots.values()], template)
    out |= dict(zip(robots, found, strict=True))
    return [out[k] for k in range(len(task.points))]


def _tasks(space: SearchSpace, goal: Goal, points: Sequence[tuple[float, ...]]) -> list[_Task]:
    """The points in tasks of :data:`CHUNK` designs."""
    return [_Task(space, goal, tuple(points[i : i + CHUNK])) for i in range(0, len(points), CHUNK)]


def _run(tasks: Sequence[_Task], executor: Executor | None) -> list[list[Evaluation]]:
    """Each task's evaluations, on ``executor`` (this process if ``None``), in task order."""
    if executor is None:
        return [evaluate_points(task) for task in tasks]
    return [f.result() for f in [executor.submit(evaluate_points, t) for t in tasks]]


def evaluate_batch(
    space: SearchSpace, goal: Goal, points: Sequence[npt.ArrayLike], executor: Executor | None
) -> list[Evaluation]:
    """The evaluation of the space's robot at each point for ``goal``, on ``executor``."""
    keys = [tuple(float(v) for v in np.asarray(x, dtype=float)) for x in points]
    tasks = _tasks(space, goal, keys)
    return [found for evaluations in _run(tasks, executor) for found in evaluations]


# -- the search ---------------------------------------------------------------------------


class _Evaluator:
    """Evaluates batches of points on the executor, journalled, with a progress bar."""

    def __init__(
        self,
        space: SearchSpace,
        goal: Goal,
        executor: Executor | None,
        journal: Journal | None,
        key: str,
        bar: Progress,
    ) -> None:
        self.space, self.goal, self.executor = space, goal, executor
        self.journal, self.key, self.bar = journal, key, bar
        self.seen: dict[tuple[float, ...], Evaluation] = {}

    def __call__(self, points: ArrayF) -> list[Evaluation]:
        keys = [tuple(float(v) for v in x) for x in points]
        found: dict[tuple[float, ...], Evaluation] = {}
        for x in keys:
            known = self.seen.get(x) or (self.journal.lookup(self.key, x) if self.journal else None)
            if known is not None:
                found[x] = known
        missing = list(dict.fromkeys(x for x in keys if x not in found))
        self.bar.update(len(keys) - len(missing))
        tasks = _tasks(self.space, self.goal, missing)
        for task, evaluations in zip(tasks, _run(tasks, self.executor), strict=True):
            found.update(zip(task.points, evaluations, strict=True))
            if self.journal is not None:
                self.journal.record(self.key, task.points, evaluations)
            self.bar.update(len(task.points))
        self.seen.update(found)
        return [found[x] for x in keys]


class _Problem(Problem):  # type: ignore[misc,unused-ignore]  # pymoo ships no types
    """The search as pymoo sees it: each design's cost and scaled constraints, in batches."""

    def __init__(self, space: SearchSpace, goal: Goal, evaluate: _Evaluator) -> None:
        count = max(1, len(goal.constraints))
        super().__init__(
            n_var=len(space.variables), n_obj=1, n_ieq_constr=count, xl=space.lower, xu=space.upper
        )
        self.goal, self.batch = goal, evaluate

    def _evaluate(self, x: ArrayF, out: dict[str, Any], *args: Any, **kwargs: Any) -> None:
        scored = [objective_and_constraints(self.goal, e) for e in self.batch(x)]
        out["F"] = np.array([[cost] for cost, _ in scored])
        out["G"] = np.array([g for _, g in scored])


def objective_and_constraints(goal: Goal, evaluation: Evaluation) -> tuple[float, ArrayF]:
    """The cost to minimize and the scaled constraint values g (≤ 0: met) of an evaluation."""
    count = max(1, len(goal.constraints))
    if evaluation.error:
        return INVALID, np.full(count, INVALID)
    checks = {c.name: c for c in goal.checks(evaluation)}
    g = [  # met within round-off (ROUNDOFF) is met: g ≤ 0, as the checks say
        -checks[name].margin / max(abs(checks[name].required), 1e-9) - ROUNDOFF
        for name in goal.constraints
    ]
    cost = goal.objective.cost(evaluation.metrics.value(goal.objective.spec))
    return cost, np.array(g or [0.0])


def run_search(
    space: SearchSpace,
    goal: Goal,
    settings: SearchSettings,
    executor: Executor | None = None,
    journal: Journal | None = None,
    progress: bool | None = None,
    starts: Sequence[npt.ArrayLike] = (),
) -> SearchOutcome:
    """The best design of ``space`` for ``goal`` (pymoo differential evolution).

    Args:
        space: The free variables and their bounds.
        goal: The requirements to meet and the objective.
        settings: Seed and budget.
        executor: Where designs are evaluated; this process if omitted.
        journal: Where evaluated designs are kept (and read back on resume).
        progress: ``False`` shows nothing; otherwise a bar on stderr if it is a terminal,
            else a line every few seconds (:class:`~hexaleg.study.progress.Progress`).
        starts: Points put into the initial population (e.g. the user's design).

    """
    variables = len(space.variables)
    population, generations = settings.population(variables), settings.generations(variables)
    key = json.dumps({"goal": _goal_key(goal), "space": _space_key(space)}, sort_keys=True)
    with Progress(population * generations, unit="designs", show=progress) as bar:
        evaluate = _Evaluator(space, goal, executor, journal, key, bar)
        algorithm = DE(
            pop_size=population,
            sampling=initial_points(space, population, settings.seed, starts),
            variant=VARIANT,
            CR=CROSSOVER,
            F=DIFFERENTIAL_WEIGHT,
            return_least_infeasible=True,
        )
        problem = _Problem(space, goal, evaluate)
        algorithm.setup(problem, termination=("n_gen", generations), seed=settings.seed)
        while algorithm.has_next():
            algorithm.next()
    best = algorithm.result()  # the least infeasible design if none is feasible
    x = np.atleast_2d(best.X)[0]
    evaluation = evaluate.seen[tuple(float(v) for v in x)]
    return SearchOutcome(
        x=x,
        evaluation=evaluation,
        feasible=goal.meets(evaluation),
        evaluations=population * generations,
        method=method_text(population, generations),
    )


def method_text(population: int, generations: int) -> str:
    """The algorithm and its settings, in words."""
    return (
        f"pymoo {pymoo.__version__} differential evolution ({VARIANT}, CR {CROSSOVER}, "
        f"F {DIFFERENTIAL_WEIGHT}), population {population}, {generations} generations, "
        "feasibility-first constraints"
    )


def initial_points(
    space: SearchSpace, population: int, seed: int, starts: Sequence[npt.ArrayLike] = ()
) -> ArrayF:
    """A seeded Latin hypercube over the bounds, its first rows replaced by ``starts`` (clipped)."""
    sampler = qmc.LatinHypercube(d=len(space.variables), seed=np.random.default_rng(seed))
    points: ArrayF = qmc.scale(sampler.random(population), space.lower, space.upper)
    for row, start in enumerate(list(starts)[:population]):
        points[row] = np.clip(np.asarray(start, dtype=float), space.lower, space.upper)
    return points


def _goal_key(goal: Goal) -> dict[str, Any]:
    return {
        "requirements": goal.requirements.to_dict(),
        "objective": str(goal.objective),
        "relaxed": goal.relaxed,
    }


def _space_key(space: SearchSpace) -> list[list[Any]]:
    return [[v.name, v.lower, v.upper] for v in space.variables]
