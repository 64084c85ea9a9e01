"""A multi-start driver for "push one coordinate as far as the constraints allow".

Pure numerics, independent of the robot: :func:`maximize_coordinate` runs SLSQP on
max ±x_k subject to g(x) ≥ 0 (a :class:`CoordinateProblem`) from every :class:`Start`,
keeps the answers a caller's exact check accepts, and says whether the best was reached
from more than one start point.
:func:`box_starts` spreads deterministic starts (a scrambled Sobol sequence with a
fixed seed) over a box.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from scipy import optimize
from scipy.stats import qmc

from hexaleg._typing import ArrayF

FTOL = 1e-9
"""SLSQP's stopping tolerance on the objective [m or rad]."""
AGREEMENT = 1e-6
"""Starts whose optima differ by less than this (relative, at least 1 unit) agree."""


@dataclass(frozen=True)
class CoordinateProblem:
    """max sign·x_k subject to g(x) ≥ 0: what every start of a multi-start solves.

    Attributes:
        k: The coordinate to push.
        sign: +1 to maximize it, −1 to minimize it.
        constraints: g(x), every component to be ≥ 0.
        jacobian: dg/dx.
        accept: The exact check an answer must pass to count.
        bounds: Bounds on x, if any.
        max_iterations: SLSQP iterations per start.
        repair: A feasible point near an answer the exact check rejects, or None:
            the answer then counts, flagged not converged (a run that stalled a hair
            outside noisy constraints, say); without it such answers are dropped.

    """

    k: int
    sign: int
    constraints: Callable[[ArrayF], ArrayF]
    jacobian: Callable[[ArrayF], ArrayF]
    accept: Callable[[ArrayF], bool]
    bounds: Sequence[tuple[float | None, float | None]] | None = None
    max_iterations: int = 60
    repair: Callable[[ArrayF], ArrayF | None] | None = None


@dataclass(frozen=True)
class Start:
    """Where one SLSQP run begins.

    Attributes:
        point: The start x.
        scale: Positive per-coordinate units the run works in (u = x / scale), or None
            to run in x: SLSQP's quasi-Newton Hessian begins as the identity, so the
            scale shapes its first steps and can lead the same start to another optimum.
        votes: Whether reaching the best value counts toward stopping early. A start
            chosen for promise (an extreme, a scan's best) may win without voting,
            since such starts tend to share one optimum.

    """

    point: ArrayF
    scale: ArrayF | None = None
    votes: bool = True


@dataclass(frozen=True)
class MultiStartResult:
    """The best accepted answer of a multi-start run.

    Attributes:
        x: The maximizer: of the answers that agree with the best, the earliest start's.
        value: ±x_k there (the quantity maximized).
        success: SLSQP reported success from the winning start.
        agreed: Starts from at least two different points reached ``value`` (within
            :data:`AGREEMENT`).
        values: Every accepted start's value, best first.
        iterations: SLSQP iterations over every start.

    """

    x: ArrayF
    value: float
    success: bool
    agreed: bool
    values: tuple[float, ...]
    iterations: int


@dataclass(frozen=True)
class _Answer:
    value: float
    x: ArrayF
    success: bool
    origin: int  # the first run from the same start point
    votes: bool


def maximize_coordinate(
    problem: CoordinateProblem,
    starts: Sequence[Start],
    enough: tuple[int, int] | None = None,
) -> MultiStartResult | None:
    """Maximize sign·x_k subject to g(x) ≥ 0 from the starts, in order.

    Args:
        problem: The program every start solves.
        starts: Where SLSQP starts (feasible or not).
        enough: (runs, agreeing): stop once at least ``runs`` starts have run and
            ``agreeing`` voting starts reached the best value; every start runs if None.

    Returns:
        The best accepted answer, or None if no start gave one.

    """
    answers: list[_Answer] = []
    iterations = 0
    first_run_from: dict[bytes, int] = {}  # start point → the first run from it
    for run, start in enumerate(starts, start=1):
        point = np.asarray(start.point, dtype=float)
        origin = first_run_from.setdefault(point.tobytes(), run)
        x, nit, success = _repaired(problem, *_run_slsqp(problem, point, start.scale))
        iterations += nit
        if problem.accept(x):
            answers.append(
                _Answer(float(problem.sign * x[problem.k]), x, success, origin, start.votes)
            )
        if enough is not None and run >= enough[0] and _enough_agree(answers, enough[1]):
            break
    if not answers:
        return None
    best = max(a.value for a in answers)
    agreeing = [a for a in answers if a.value >= best - _tolerance(best)]
    # Among answers that agree with the best, the earliest start's wins (which of several
    # equal optima that is can follow round-off: callers with symmetries pick one).
    winner = agreeing[0]
    values = tuple(sorted((a.value for a in answers), reverse=True))
    # A start point run twice (scaled and not) agrees with itself: count points, not runs.
    agreed = len({a.origin for a in agreeing}) >= 2
    return MultiStartResult(winner.x, winner.value, winner.success, agreed, values, iterations)


def _repaired(
    problem: CoordinateProblem, x: ArrayF, nit: int, success: bool
) -> tuple[ArrayF, int, bool]:
    """A run's answer, or its repair (not converged) where the exact check rejects it."""
    if problem.repair is None or problem.accept(x):
        return x, nit, success
    repaired = problem.repair(x)
    return (x, nit, success) if repaired is None else (repaired, nit, False)


def _tolerance(best: float) -> float:
    return AGREEMENT * max(1.0, abs(best))


def _enough_agree(answers: Sequence[_Answer], agreeing: int) -> bool:
    """Whether ``agreeing`` voting answers reach the best of all answers."""
    if not answers:
        return False
    best = max(a.value for a in answers)
    return sum(a.votes and a.value >= best - _tolerance(best) for a in answers) >= agreeing


def _run_slsqp(
    problem: CoordinateProblem, start: ArrayF, scale: ArrayF | None
) -> tuple[ArrayF, int, bool]:
    """One SLSQP run of ``problem`` from ``start``, in u = x / scale if scaled.

    The objective is ∓u_k, the pushed coordinate in its own scaled unit: a positive
    multiple of ∓x_k, so the same optimum. Returns the answer in x, the iterations
    and SLSQP's success flag.
    """
    s = np.ones_like(start) if scale is None else np.asarray(scale, dtype=float)
    if np.any(s <= 0):
        raise ValueError("a start's scale must be positive")
    gradient = np.zeros(len(start))
    gradient[problem.k] = -problem.sign
    bounds = problem.bounds
    if bounds is not None:
        bounds = [
            (None if lo is None else lo / si, None if hi is None else hi / si)
            for (lo, hi), si in zip(bounds, s, strict=True)
        ]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        result = optimize.minimize(
            lambda u: float(gradient @ u),
            start / s,
            jac=lambda u: gradient,
            method="SLSQP",
            bounds=bounds,
            constraints={
                "type": "ineq",
                "fun": lambda u: problem.constraints(u * s),
                "jac": lambda u: problem.jacobian(u * s) * s,
            },
            options={"maxiter": problem.max_iterations, "ftol": FTOL},
        )
    return result.x * s, int(result.nit), bool(result.success)


def box_starts(half_widths: ArrayF, count: int, seed: int = 0) -> list[ArrayF]:
    """``count`` deterministic starts spread over the box ±half_widths (scrambled Sobol)."""
    half_widths = np.asarray(half_widths, dtype=float)
    balanced = 1 << max(0, count - 1).bit_length()  # Sobol points come in powers of 2
    sobol = qmc.Sobol(len(half_widths), scramble=True, seed=seed)
    points = sobol.random(balanced)[:count] * 2 - 1
    return list(points * half_widths)
