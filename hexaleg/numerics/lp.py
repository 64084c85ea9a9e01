"""A small dense linear program, compiled: the step of a sequential-linear-programming search.

Pure numerics, independent of the robot. :func:`elastic_lp` solves

    maximize    c·x − penalty·Σ t_i
    subject to  g_i + a_i·x + t_i ≥ 0,  t_i ≥ 0   (i = 1 … m)
                lower ≤ x ≤ upper,  lower ≤ 0 ≤ upper

for a handful of variables x: the linearized constraints of a trust-region step, where
t relaxes the ones no step in the box can satisfy (an "elastic" program: it always
has a solution, and with a penalty above the constraints' multipliers it is the
ordinary one whenever that exists). The primal simplex method with bounded variables
runs on a dense tableau from x = 0 (the current point of the search, usually close to
the answer): x = x⁺ − x⁻ with 0 ≤ x⁺ ≤ upper and 0 ≤ x⁻ ≤ −lower, and each row's
surplus s_i ≥ 0 turns it into the equation a_i·(x⁺ − x⁻) + t_i − s_i = −g_i.
"""

from __future__ import annotations

import numpy as np

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF

PIVOT_TOLERANCE = 1e-12
"""Tableau entries and reduced costs smaller than this count as zero."""


@compiled
def elastic_lp(
    objective: ArrayF,
    offsets: ArrayF,
    rows: ArrayF,
    lower: ArrayF,
    upper: ArrayF,
    penalty: float,
) -> tuple[ArrayF, ArrayF]:  # pragma: no cover - compiled; tested against SciPy's HiGHS
    """The solution x (n,) and relaxations t (m,) of the elastic program above.

    Args:
        objective: c (n,).
        offsets: g (m,).
        rows: a (m, n).
        lower: Lower bounds of x (n,), each ≤ 0.
        upper: Upper bounds of x (n,), each ≥ 0.
        penalty: The price of a unit of relaxation.

    """
    m, n = rows.shape
    tableau, cost, bound, basis = _initial_tableau(objective, offsets, rows, lower, upper, penalty)
    at_upper = np.zeros(cost.shape[0], np.bool_)
    _simplex(tableau, cost, bound, basis, at_upper)
    value = np.where(at_upper, bound, 0.0)
    for i in range(m):
        value[basis[i]] = tableau[i, -1]
    relaxation = value[2 * n : 2 * n + m].copy()
    return value[:n] - value[n : 2 * n], relaxation


@compiled
def _initial_tableau(
    objective: ArrayF,
    offsets: ArrayF,
    rows: ArrayF,
    lower: ArrayF,
    upper: ArrayF,
    penalty: float,
) -> tuple[ArrayF, ArrayF, ArrayF, np.ndarray]:  # pragma: no cover - compiled
    """The tableau at x = 0, the costs, the upper bounds of the columns, and the basis.

    Columns: x⁺ (n), x⁻ (n), t (m), s (m), then the basic variables' values. Row i is
    the row of t_i (value −g_i) where g_i < 0, else the row of s_i (value g_i), signed
    so that its basic variable has coefficient 1.
    """
    m, n = rows.shape
    width = 2 * n + 2 * m
    tableau = np.zeros((m, width + 1))
    basis = np.empty(m, np.int64)
    for i in range(m):
        side = 1.0 if offsets[i] < 0 else -1.0  # t_i basic: +1; s_i basic: the row negated
        tableau[i, :n] = side * rows[i]
        tableau[i, n : 2 * n] = -side * rows[i]
        tableau[i, 2 * n + i] = side
        tableau[i, 2 * n + m + i] = -side
        tableau[i, width] = -side * offsets[i]
        basis[i] = 2 * n + i if offsets[i] < 0 else 2 * n + m + i
    cost = np.zeros(width)
    cost[:n], cost[n : 2 * n], cost[2 * n : 2 * n + m] = objective, -objective, -penalty
    bound = np.full(width, np.inf)
    bound[:n], bound[n : 2 * n] = upper, -lower
    return tableau, cost, bound, basis


@compiled
def _simplex(
    tableau: ArrayF, cost: ArrayF, bound: ArrayF, basis: np.ndarray, at_upper: np.ndarray
) -> None:  # pragma: no cover - compiled
    """Pivot to optimality in place (maximization, variables in [0, bound]).

    A nonbasic variable sits at 0 or at its bound (``at_upper``). The most improving
    column enters (Dantzig's rule); after a run of steps that do not move (degenerate
    ones) the first improving column does (Bland's rule, which cannot cycle).
    """
    stalled = 0
    for _ in range(50 * tableau.shape[1]):
        entering, direction = _entering(tableau, cost, basis, at_upper, stalled > tableau.shape[0])
        if entering < 0:
            return
        leaving, step = _ratio_test(tableau, bound, basis, entering, direction)
        stalled = stalled + 1 if step == 0.0 else 0
        tableau[:, -1] -= direction * step * tableau[:, entering]
        if leaving < 0:  # the entering variable reaches its own bound first
            at_upper[entering] = not at_upper[entering]
            continue
        leaving_variable = basis[leaving]
        at_upper[leaving_variable] = direction * tableau[leaving, entering] < 0
        value = (bound[entering] if at_upper[entering] else 0.0) + direction * step
        at_upper[entering] = False
        tableau[leaving, :-1] /= tableau[leaving, entering]
        tableau[leaving, -1] = value
        for i in range(tableau.shape[0]):
            if i != leaving and tableau[i, entering] != 0.0:
                factor = tableau[i, entering]
                tableau[i, :-1] -= factor * tableau[leaving, :-1]
        basis[leaving] = entering


@compiled
def _entering(
    tableau: ArrayF, cost: ArrayF, basis: np.ndarray, at_upper: np.ndarray, bland: bool
) -> tuple[int, float]:  # pragma: no cover - compiled
    """The entering column and its direction (+1 up from 0, −1 down from its bound).

    Its reduced cost c_j − c_B·column_j must improve the objective in that direction;
    the first (Bland) or the most (Dantzig) improving column; −1 if none.
    """
    entering, direction, best = -1, 0.0, PIVOT_TOLERANCE
    is_basic = np.zeros(cost.shape[0], np.bool_)
    is_basic[basis] = True
    for j in range(cost.shape[0]):
        if is_basic[j]:
            continue
        gain = cost[j]
        for i in range(basis.shape[0]):
            gain -= cost[basis[i]] * tableau[i, j]
        sense = -1.0 if at_upper[j] else 1.0
        if sense * gain > best:
            entering, direction, best = j, sense, sense * gain
            if bland:
                break
    return entering, direction


@compiled
def _ratio_test(
    tableau: ArrayF, bound: ArrayF, basis: np.ndarray, entering: int, direction: float
) -> tuple[int, float]:  # pragma: no cover - compiled
    """The row whose basic variable stops the entering one first, and the step.

    −1 if the entering variable reaches its own bound first. Ties go to the smallest
    basic index.
    """
    leaving, step = -1, bound[entering]
    for i in range(tableau.shape[0]):
        rate = -direction * tableau[i, entering]  # d(basic_i) / d(step)
        if rate < -PIVOT_TOLERANCE:
            limit = tableau[i, -1] / -rate
        elif rate > PIVOT_TOLERANCE and np.isfinite(bound[basis[i]]):
            limit = (bound[basis[i]] - tableau[i, -1]) / rate
        else:
            continue
        limit = max(limit, 0.0)
        if limit < step or (limit == step and leaving >= 0 and basis[i] < basis[leaving]):
            leaving, step = i, limit
    return leaving, step
