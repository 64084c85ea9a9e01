"""A small dense linear program, compiled: the step of a sequential-linear-programming search.

Pure numerics, independent of the robot. :func:`elastic_lp` solves

    maximize    c·x − penalty·Σ t_i
    subject to  g_i + a_i·x + t_i ≥ 0,  t_i ≥ 0   (i = 1 … m)
                lower ≤ x ≤ upper,  lower ≤ 0 ≤ upper

for a handful of variables x: the linearized constraints of a trust-region step, where
t relaxes the ones no step in the box can satisfy (an "elastic" program: it always
has a solution, and with a penalty above the constraints' multipliers it is the
ordinary one whenever that exists). With t eliminated it is the concave
piecewise-linear program max f(x) = c·x − penalty·Σ max(0, −g_i − a_i·x) over the box,
solved by a primal simplex method on the n variables themselves (the active-set form):

- a vertex is named by n active hyperplanes (a row's g_i + a_i·x = 0, a bound of x, or,
  at the start x = 0, x_j = 0 itself), whose normals form an n × n matrix N;
- the gradient h of f in the current cell, written in those normals (Nᵀy = h), tells
  which hyperplane to leave: one whose multiplier y_w shows that moving off it along
  the edge d (N d = ±e_w) raises f;
- the ratio test walks along d past the rows' kinks (where a row turns violated or
  satisfied, f's slope drops by penalty·|a_i·d|) up to the one where the slope stops
  being positive, or a bound of x, which enters in w's place.

Each pivot costs O(m·n), not the O(m²) of a tableau over the 2m columns of t and the
surpluses: the programs here have n = 6 and up to some 60 rows. The offsets are
lowered by distinct amounts of about :data:`PERTURBATION` so that no two hyperplanes meet
a vertex together (mirror-image legs give equal rows), which keeps the method from
cycling; the answer's relaxations are those of the unperturbed offsets.
"""

from __future__ import annotations

import numpy as np

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF

PIVOT_TOLERANCE = 1e-12
"""Slopes, multipliers and rates of change smaller than this count as zero."""
PERTURBATION = 1e-13
"""Each row's offset is lowered by a distinct amount between this and twice this: no
vertex where more than n planes meet, and an answer that satisfies a row does so strictly."""
GOLDEN = 0.6180339887498949
"""The fractional parts of i·this spread the rows' perturbations evenly."""
FREE, LOWER, UPPER, ROW = 0, 1, 2, 3
"""What an active hyperplane is: x_j = 0 at the start, a bound of x_j, or a row."""


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
    residual = offsets - PERTURBATION * (1.0 + (GOLDEN * np.arange(m)) % 1.0)  # at x = 0
    x, gradient, direction = np.zeros(n), np.empty(n), np.empty(n)
    rates, kinks, kinked = np.empty(m), np.empty(m), np.empty(m, np.int64)
    kind, which = np.full(n, FREE, np.int64), np.arange(n)
    active = np.zeros(m, np.bool_)  # rows among the active hyperplanes
    edges = np.eye(n)  # row w: column w of N⁻¹, the edge off hyperplane w along its normal
    for _ in range(50 * (m + n) + 50):
        _cell_gradient(objective, rows, residual, active, penalty, gradient)
        leaving, sense = _leaving(gradient, kind, which, edges, lower, upper, penalty)
        if leaving < 0:
            break
        for j in range(n):
            direction[j] = sense * edges[leaving, j]
        for i in range(m):
            rates[i] = _dot(rows[i], direction)
        slope = _dot(gradient, direction) - (penalty if kind[leaving] == ROW and sense < 0 else 0)
        step, entering_kind, entering = _ratio_test(
            residual, rates, active, x, direction, slope, lower, upper, penalty, kinks, kinked
        )
        if entering_kind < 0:
            break
        x += step * direction
        residual += step * rates
        if kind[leaving] == ROW:
            active[which[leaving]] = False
        if entering_kind == ROW:
            active[entering] = True
        kind[leaving], which[leaving] = entering_kind, entering
        pivot = sense * (rates[entering] if entering_kind == ROW else direction[entering])
        _replace_row(
            edges, leaving, rows[entering] if entering_kind == ROW else None, entering, pivot
        )
    x = np.minimum(np.maximum(x, lower), upper)
    relaxation = np.empty(m)
    for i in range(m):
        relaxation[i] = max(0.0, -(offsets[i] + _dot(rows[i], x)))
    return x, relaxation


@compiled
def _replace_row(edges: ArrayF, leaving: int, normal: ArrayF | None, j: int, pivot: float) -> None:
    """N⁻¹ (its columns as the rows of ``edges``) after N's row ``leaving`` becomes ``normal``.

    ``normal`` is row j of the program, or the unit vector e_j if None; ``pivot`` is
    normal·(column ``leaving`` of N⁻¹), not zero. A rank-one update (product form).
    """
    n = edges.shape[0]
    for k in range(n):
        edges[leaving, k] /= pivot
    for w in range(n):
        if w != leaving:
            along = edges[w, j] if normal is None else _dot(normal, edges[w])
            for k in range(n):
                edges[w, k] -= along * edges[leaving, k]


@compiled
def _dot(a: ArrayF, b: ArrayF) -> float:  # pragma: no cover - compiled
    """a·b of two short vectors (a loop: BLAS's call costs more at this size)."""
    total = 0.0
    for j in range(a.shape[0]):
        total += a[j] * b[j]
    return total


@compiled
def _cell_gradient(
    objective: ArrayF,
    rows: ArrayF,
    residual: ArrayF,
    active: np.ndarray,
    penalty: float,
    gradient: ArrayF,
) -> None:  # pragma: no cover - compiled
    """Write the cell's gradient h of f: c plus penalty·a_i of each inactive violated row."""
    gradient[:] = objective
    for i in range(rows.shape[0]):
        if residual[i] < 0.0 and not active[i]:
            for j in range(gradient.shape[0]):
                gradient[j] += penalty * rows[i, j]


@compiled
def _leaving(
    gradient: ArrayF,
    kind: np.ndarray,
    which: np.ndarray,
    edges: ArrayF,
    lower: ArrayF,
    upper: ArrayF,
    penalty: float,
) -> tuple[int, float]:  # pragma: no cover - compiled
    """The active hyperplane to leave and the side (+1: along its normal), or (−1, 0).

    The one whose edge raises f most per unit length: y = N⁻ᵀh are the multipliers of
    the cell's gradient h, column w of N⁻¹ (row w of ``edges``) the edge that moves off
    hyperplane w along its normal.
    """
    leaving, sense, best = -1, 0.0, PIVOT_TOLERANCE
    for w in range(kind.shape[0]):
        y = _dot(edges[w], gradient)
        gain, side = 0.0, 0.0
        if kind[w] == ROW:
            gain, side = (y, 1.0) if y > 0 else (-y - penalty, -1.0)
        elif kind[w] == LOWER:
            gain, side = y, 1.0
        elif kind[w] == UPPER:
            gain, side = -y, -1.0
        elif lower[which[w]] < upper[which[w]]:  # FREE, and not fixed at 0 by its bounds
            gain, side = abs(y), 1.0 if y > 0 else -1.0
        gain /= np.sqrt(_dot(edges[w], edges[w]))
        if gain > best:
            leaving, sense, best = w, side, gain
    return leaving, sense


@compiled
def _ratio_test(
    residual: ArrayF,
    rates: ArrayF,
    active: np.ndarray,
    x: ArrayF,
    direction: ArrayF,
    slope: float,
    lower: ArrayF,
    upper: ArrayF,
    penalty: float,
    kinks: ArrayF,
    kinked: np.ndarray,
) -> tuple[float, int, int]:  # pragma: no cover - compiled
    """How far to go along ``direction``, and the hyperplane that enters there.

    The first kink (row i's residual changing at ``rates[i]``) where the slope stops
    being positive, or the first bound of x (kind −1 if neither: an unbounded edge).
    ``kinks`` and ``kinked`` are work space (m,).
    """
    step, entering_kind, entering = np.inf, -1, -1
    for j in range(x.shape[0]):
        if direction[j] > PIVOT_TOLERANCE and (upper[j] - x[j]) / direction[j] < step:
            step, entering_kind, entering = max((upper[j] - x[j]) / direction[j], 0.0), UPPER, j
        elif direction[j] < -PIVOT_TOLERANCE and (lower[j] - x[j]) / direction[j] < step:
            step, entering_kind, entering = max((lower[j] - x[j]) / direction[j], 0.0), LOWER, j
    count = 0
    for i in range(residual.shape[0]):
        rate = rates[i]
        if active[i] or abs(rate) <= PIVOT_TOLERANCE:
            continue
        if (residual[i] < 0.0) == (rate > 0.0):  # turns satisfied, or turns violated
            at = max(-residual[i] / rate, 0.0)
            if at < step:
                kinks[count], kinked[count] = at, i
                count += 1
    for passed in range(count):  # the kinks in order (selection: few are passed)
        c = passed + np.argmin(kinks[passed:count])
        kinks[passed], kinks[c] = kinks[c], kinks[passed]
        kinked[passed], kinked[c] = kinked[c], kinked[passed]
        slope -= penalty * abs(rates[kinked[passed]])
        if slope <= PIVOT_TOLERANCE:
            return kinks[passed], ROW, kinked[passed]
    return step, entering_kind, entering
