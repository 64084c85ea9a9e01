"""Climbs, compiled: one body coordinate pushed as far as the stance margins allow.

A climb is sequential linear programming with a trust region: at the current
displacement it linearizes the smooth stance margins (:mod:`.margin_jacobian`, closed
form), solves the elastic linear program "push d_k, keep every linearized margin
≥ 0, move at most Δ" (:func:`~hexaleg.numerics.lp.elastic_lp`), and accepts the step if
the merit ±d_k − penalty·(violation) improves as the model predicted, growing or
shrinking Δ. A step that the margins' curvature spoils is corrected back onto the
constraints it made tight (a second-order correction). From an infeasible start the
relaxations first restore feasibility. Each iteration costs one pass for the margins
and their Jacobian, the trial's margins and a small linear program, so a search can
afford dozens of climbs per direction: :func:`climb_all` runs them and returns where each ended.

Climbs work in coordinates scaled to the search box (u = d / scale), where the trust
region is a cube.
"""

from __future__ import annotations

import math

import numpy as np

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF
from hexaleg.numerics.lp import elastic_lp
from hexaleg.stance.margin_jacobian import pose_margins_and_jacobian
from hexaleg.stance.margin_kernel import KernelGeometry, column_count, pose_margins

PENALTY = 100.0
"""Price of a unit of constraint violation (normalized margins, scaled units) in the merit."""
FIRST_RADIUS = 0.2
"""Initial trust region, as a fraction of the search box."""
SMALLEST_RADIUS = 1e-6
"""A climb stops when its trust region shrinks below this (scaled units)."""
LEAST_GAIN = 1e-6
"""... or when the linear program promises less than this gain (scaled units): near an
optimum where fewer constraints bind than there are coordinates, steps only creep
along the curved boundary, and the final polish (SLSQP) does better there."""
MAX_ITERATIONS = 150
"""Linear programs per climb at most."""
REACHABLE_ROWS = 3.0
"""Only margins within this many trust radii of zero enter the linear program."""
ACCEPT, EXPAND = 0.1, 0.5
"""A step is taken when its merit gain is at least ACCEPT of the predicted one; the
trust region doubles after a full step that gained at least EXPAND of it."""


@compiled
def climb_all(
    geometry: KernelGeometry,
    starts: ArrayF,
    scale: ArrayF,
    k: int,
    sign: float,
    lower: ArrayF,
    upper: ArrayF,
) -> tuple[ArrayF, np.ndarray]:  # pragma: no cover - compiled
    """Where each climb from ``starts`` (S, 6) ends (S, 6) [m, rad], and its iterations.

    Args:
        geometry: One design's smooth-margin kernel geometry.
        starts: Start displacements [m, rad].
        scale: The search box's half widths (6,) [m, rad]: the climbs' unit lengths.
        k: The coordinate pushed.
        sign: +1 to push it up, −1 down.
        lower: Lower bounds of the displacement (6,) (−inf where none).
        upper: Upper bounds (6,).

    """
    ends = np.empty_like(starts)
    iterations = np.zeros(starts.shape[0], np.int64)
    for s in range(starts.shape[0]):
        ends[s], iterations[s] = climb(geometry, starts[s], scale, k, sign, lower, upper)
    return ends, iterations


@compiled
def climb(
    geometry: KernelGeometry,
    start: ArrayF,
    scale: ArrayF,
    k: int,
    sign: float,
    lower: ArrayF,
    upper: ArrayF,
) -> tuple[ArrayF, int]:  # pragma: no cover - compiled
    """One climb (see :func:`climb_all`): its end [m, rad] and iterations."""
    u, radius = start / scale, FIRST_RADIUS
    low, high = lower / scale, upper / scale
    values, jacobian = linearize(geometry, u, scale)
    iteration = 0
    while iteration < MAX_ITERATIONS:
        iteration += 1
        norms = row_norms(jacobian)
        step, relaxed, tight = linear_step(values, jacobian, norms, u, radius, k, sign, low, high)
        before, violation = merit(values, norms, sign * u[k])
        predicted = sign * step[k] - PENALTY * relaxed + PENALTY * violation
        if predicted <= LEAST_GAIN:
            break
        trial = u + step
        at_trial = trial_margins(geometry, trial, scale)
        gain = merit(at_trial, norms, sign * trial[k])[0] - before
        if gain < 0.75 * predicted and tight.shape[0] > 0:
            corrected = correction(trial, at_trial, tight, jacobian, norms, low, high)
            if corrected.shape[0] == 6:
                after = merit(trial_margins(geometry, corrected, scale), norms, sign * corrected[k])
                if after[0] - before > gain:
                    trial, gain = corrected, after[0] - before
        longest = np.abs(step).max()
        if gain >= ACCEPT * predicted:
            u = trial
            values, jacobian = linearize(geometry, u, scale)
            if gain >= EXPAND * predicted and longest > 0.9 * radius:
                radius = min(2 * radius, 1.0)
        else:
            radius = 0.3 * longest
            if radius < SMALLEST_RADIUS:
                break
    return u * scale, iteration


@compiled
def linearize(
    geometry: KernelGeometry, u: ArrayF, scale: ArrayF
) -> tuple[ArrayF, ArrayF]:  # pragma: no cover - compiled
    """Smooth margins at u (C,) and their Jacobian in scaled units (C, 6)."""
    columns = column_count(geometry)
    values, jacobian = np.empty(columns), np.empty((columns, 6))
    pose_margins_and_jacobian(geometry, 0, u * scale, values, jacobian)
    for j in range(6):
        jacobian[:, j] *= scale[j]
    return values, jacobian


@compiled
def trial_margins(geometry: KernelGeometry, u: ArrayF, scale: ArrayF) -> ArrayF:  # pragma: no cover
    """Smooth margins at u (C,)."""
    values = np.empty(column_count(geometry))
    pose_margins(geometry, 0, u * scale, np.empty((3, 3)), values)
    return values


@compiled
def row_norms(jacobian: ArrayF) -> ArrayF:  # pragma: no cover - compiled
    """Each margin's gradient length (1 where it is flat): margins / norms are distances."""
    norms = np.empty(jacobian.shape[0])
    for i in range(jacobian.shape[0]):
        total = 0.0
        for j in range(jacobian.shape[1]):
            total += jacobian[i, j] ** 2
        norms[i] = math.sqrt(total) if total > 0.0 else 1.0
    return norms


@compiled
def merit(values: ArrayF, norms: ArrayF, pushed: float) -> tuple[float, float]:  # pragma: no cover
    """The merit ±u_k − penalty·violation, and the violation (normalized margins)."""
    violation = 0.0
    for i in range(values.shape[0]):
        violation += max(0.0, -values[i] / norms[i])
    return pushed - PENALTY * violation, violation


@compiled
def linear_step(
    values: ArrayF,
    jacobian: ArrayF,
    norms: ArrayF,
    u: ArrayF,
    radius: float,
    k: int,
    sign: float,
    low: ArrayF,
    high: ArrayF,
) -> tuple[ArrayF, float, np.ndarray]:  # pragma: no cover - compiled
    """The linear program's step, its total relaxation, and the rows it made tight."""
    rows, offsets, gradients = near_rows(values, jacobian, norms, REACHABLE_ROWS * radius)
    lower, upper, objective = np.empty(6), np.empty(6), np.zeros(6)
    for j in range(6):
        lower[j] = max(-radius, low[j] - u[j])
        upper[j] = min(radius, high[j] - u[j])
    objective[k] = sign
    step, relaxation = elastic_lp(objective, offsets, gradients, lower, upper, PENALTY)
    tight = np.empty(rows.shape[0], np.int64)
    count = 0
    for i in range(rows.shape[0]):
        residual = offsets[i] + relaxation[i]
        for j in range(6):
            residual += gradients[i, j] * step[j]
        if abs(residual) < 1e-9 and relaxation[i] == 0.0:
            tight[count] = rows[i]
            count += 1
    return step, relaxation.sum(), tight[:count]


@compiled
def near_rows(
    values: ArrayF, jacobian: ArrayF, norms: ArrayF, reach: float
) -> tuple[np.ndarray, ArrayF, ArrayF]:  # pragma: no cover - compiled
    """The margins within ``reach`` of zero (as distances): their indices, values, gradients.

    Each normalized by its gradient's length.
    """
    count = 0
    for i in range(values.shape[0]):
        count += values[i] / norms[i] <= reach
    rows, offsets = np.empty(count, np.int64), np.empty(count)
    gradients = np.empty((count, jacobian.shape[1]))
    r = 0
    for i in range(values.shape[0]):
        if values[i] / norms[i] <= reach:
            rows[r], offsets[r] = i, values[i] / norms[i]
            for j in range(jacobian.shape[1]):
                gradients[r, j] = jacobian[i, j] / norms[i]
            r += 1
    return rows, offsets, gradients


@compiled
def correction(
    trial: ArrayF,
    values: ArrayF,
    tight: np.ndarray,
    jacobian: ArrayF,
    norms: ArrayF,
    low: ArrayF,
    high: ArrayF,
) -> ArrayF:  # pragma: no cover - compiled
    """``trial`` moved back onto the tight constraints; empty if that leaves the bounds.

    The least-norm shift that zeroes their linearized margins (``values`` at ``trial``,
    the Jacobian of the current point).
    """
    count = tight.shape[0]
    gradients = np.empty((count, 6))
    for i in range(count):
        for j in range(6):
            gradients[i, j] = jacobian[tight[i], j] / norms[tight[i]]
    gram = np.empty((count, count))  # the least-norm shift: Gᵀ(GGᵀ)⁻¹(−g)
    for a in range(count):
        for b in range(count):
            gram[a, b] = (gradients[a] * gradients[b]).sum() + (1e-12 if a == b else 0.0)
    shift = gradients.T @ np.linalg.solve(gram, -values[tight] / norms[tight])
    corrected: ArrayF = trial + shift
    if np.any(corrected < low) or np.any(corrected > high) or not math.isfinite(shift.sum()):
        return np.empty(0)
    return corrected
