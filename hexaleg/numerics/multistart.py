"""A multi-start driver for "push one coordinate as far as the constraints allow".

Pure numerics, independent of the robot: :func:`maximize_coordinate` runs SLSQP on
max ±x_k subject to g(x) ≥ 0 from every start, keeps the answers a caller's exact
check accepts, and says whether the best was reached by more than one start. Each
start may run in scaled coordinates u = x / scale: SLSQP's quasi-Newton Hessian begins
as the identity, so the scale shapes its first steps, and the same start scaled
differently can end in another local optimum.
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
"""SLSQP's stopping tolerance on the objective [m or rad]; 1e-12 took 7–14 % more
iterations and moved no extreme by more than 1e-6."""
AGREEMENT = 1e-6
"""Starts whose optima differ by less than this (relative, at least 1 unit) agree."""


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


def maximize_coordinate(
    k: int,
    sign: int,
    constraints: Callable[[ArrayF], ArrayF],
    jacobian: Callable[[ArrayF], ArrayF],
    starts: Sequence[ArrayF],
    accept: Callable[[ArrayF], bool],
    bounds: Sequence[tuple[float | None, float | None]] | None = None,
    max_iterations: int = 60,
    enough: tuple[int, int] | None = None,
    guided: int = 0,
    scales: Sequence[ArrayF | None] | None = None,
) -> MultiStartResult | None:
    """Maximize sign·x_k subject to constraints(x) ≥ 0 from the starts, in order.

    Args:
        k: The coordinate to push.
        sign: +1 to maximize it, −1 to minimize it.
        constraints: g(x), every component to be ≥ 0.
        jacobian: dg/dx.
        starts: Where SLSQP starts (feasible or not).
        accept: The exact check an answer must pass to count.
        bounds: Bounds on x, if any.
        max_iterations: SLSQP iterations per start.
        enough: (runs, agreeing): stop once at least ``runs`` starts have run and
            ``agreeing`` of them reached the best value; every start runs if None.
        guided: The first this many starts were chosen for promise (an extreme, a
            scan's best): they may win, but only the others' agreement stops the search,
            since guided starts tend to share one optimum.
        scales: Per start, the positive scale of the coordinates it runs in
            (u = x / scale), or None to run it in x; every start runs in x if omitted.

    Returns:
        The best accepted answer, or None if no start gave one.

    """
    gradient = np.zeros(len(starts[0]))
    gradient[k] = -sign
    # accepted answers: value, x, success, and the first run from the same start point
    accepted: list[tuple[float, ArrayF, bool, int]] = []
    independent: list[float] = []  # values of accepted starts that are not guided
    iterations = 0
    if scales is not None and len(scales) != len(starts):
        raise ValueError(f"{len(scales)} scales for {len(starts)} starts")
    first_run_from: dict[bytes, int] = {}  # start point → the first run from it
    for run, start in enumerate(starts, start=1):
        origin = first_run_from.setdefault(np.asarray(start, dtype=float).tobytes(), run)
        scale = None if scales is None else scales[run - 1]
        x, nit, success = _run_slsqp(
            gradient,
            constraints,
            jacobian,
            np.asarray(start, dtype=float),
            bounds,
            scale,
            max_iterations,
        )
        iterations += nit
        if accept(x):
            accepted.append((float(sign * x[k]), x, success, origin))
            if run > guided:
                independent.append(accepted[-1][0])
        if (
            enough is not None
            and run >= enough[0]
            and accepted
            and _agreeing(independent, max(item[0] for item in accepted)) >= enough[1]
        ):
            break
    if not accepted:
        return None
    best = max(item[0] for item in accepted)
    tolerance = AGREEMENT * max(1.0, abs(best))
    # Among answers that agree with the best, the earliest start's wins (which of several
    # equal optima that is can follow round-off: callers with symmetries pick one).
    value, x, success, _ = next(item for item in accepted if item[0] >= best - tolerance)
    values = tuple(sorted((item[0] for item in accepted), reverse=True))
    # A start point run twice (scaled and not) agrees with itself: count points, not runs.
    agreed = len({item[3] for item in accepted if item[0] >= best - tolerance}) >= 2
    return MultiStartResult(x, value, success, agreed, values, iterations)


def _run_slsqp(
    gradient: ArrayF,
    constraints: Callable[[ArrayF], ArrayF],
    jacobian: Callable[[ArrayF], ArrayF],
    start: ArrayF,
    bounds: Sequence[tuple[float | None, float | None]] | None,
    scale: ArrayF | None,
    max_iterations: int,
) -> tuple[ArrayF, int, bool]:
    """One SLSQP run of min gradient·u from ``start``, in u = x / scale if scaled.

    The objective is ∓u_k, the pushed coordinate in its own scaled unit: a positive
    multiple of ∓x_k, so the same optimum. Returns the answer in x, the iterations
    and SLSQP's success flag.
    """
    s = np.ones_like(start) if scale is None else np.asarray(scale, dtype=float)
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
                "fun": lambda u: constraints(u * s),
                "jac": lambda u: jacobian(u * s) * s,
            },
            options={"maxiter": max_iterations, "ftol": FTOL},
        )
    return result.x * s, int(result.nit), bool(result.success)


def _agreeing(values: Sequence[float], best: float) -> int:
    """How many of ``values`` reach ``best`` (within :data:`AGREEMENT`)."""
    tolerance = AGREEMENT * max(1.0, abs(best))
    return sum(value >= best - tolerance for value in values)


def box_starts(half_widths: ArrayF, count: int, seed: int = 0) -> list[ArrayF]:
    """``count`` deterministic starts spread over the box ±half_widths (scrambled Sobol)."""
    half_widths = np.asarray(half_widths, dtype=float)
    points = qmc.Sobol(len(half_widths), scramble=True, seed=seed).random(count) * 2 - 1
    return list(points * half_widths)
