"""Workload on the posture search: one design's best posture, beside a brute-force grid."""

from __future__ import annotations

import time

import numpy as np
from harness import Row

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.evaluation.evaluate import evaluate
from hexaleg.evaluation.goal import Goal
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError
from hexaleg.study.posture import DEFAULT_OBJECTIVE, best_posture

GRID = 31
"""Postures per angle of the baseline: a 31 × 31 grid over the stance limits."""


def grid_posture(design: HexapodDesign) -> float:
    """The baseline: every posture of a grid over the stance limits, the best one kept."""
    model, goal = HexapodModel(design), Goal(Requirements(), DEFAULT_OBJECTIVE)
    best = -np.inf
    for theta2 in np.linspace(*design.stance_limits.theta2, GRID):
        for theta3 in np.linspace(*design.stance_limits.theta3, GRID):
            try:
                posed = design.replace(nominal_angles=(0.0, float(theta2), float(theta3)))
            except HexalegError:
                continue
            found = evaluate(posed, goal.metrics, goal.conditions, model=model.with_design(posed))
            if not found.error:
                best = max(best, found.metrics.value(DEFAULT_OBJECTIVE.spec))
    return float(best)


def bench_posture(repeats: int, grid: bool = True) -> list[Row]:
    """``hexaleg posture`` on the default design (walking payload), and a grid's best."""
    design = HexapodDesign()
    times, cpu, value = [], [], 0.0
    for _ in range(repeats):
        start, used = time.perf_counter(), time.process_time()
        result = best_posture(design)
        times.append(time.perf_counter() - start)
        cpu.append(time.process_time() - used)
        value = result.best.evaluation.metrics.value(DEFAULT_OBJECTIVE.spec)
    median = float(np.median(times))
    name = f"best posture of one design ({result.evaluations} designs)"
    angles = ", ".join(f"{a:.4f}" for a in result.best.design.nominal_angles)
    posed = result.yours.evaluation.metrics.value(DEFAULT_OBJECTIVE.spec)
    note = (
        f"walking payload {value:.3f} kg at θ = ({angles}) rad; as posed {posed:.3f} kg; "
        f"CPU time {np.median(cpu):.2f} s (a shared machine's wall time runs longer)"
    )
    rows = [Row(name, "hexaleg posture (DIRECT + Nelder–Mead)", median, None, None, "≤ 2 s", note)]
    if grid:
        start = time.perf_counter()
        oracle = grid_posture(design)
        elapsed = time.perf_counter() - start
        if oracle > value + 1e-9 * abs(oracle):
            raise SystemExit(f"benchmark posture: a grid beats the search ({oracle} > {value})")
        note = "ratio: grid time / search time; max diff: the search's lead over the grid [kg]"
        grid_row = Row(name, f"brute-force {GRID}×{GRID} grid", elapsed, elapsed / median,
                       value - oracle, note=note)  # fmt: skip
        rows.append(grid_row)
    return rows
