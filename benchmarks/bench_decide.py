"""Workload on decide: three-variable searches with payload and slope, and with a speed."""

from __future__ import annotations

import math
import time
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

from harness import Row, check_agree

from hexaleg import HexapodDesign
from hexaleg.evaluation.goal import Objective
from hexaleg.evaluation.metrics import METRICS
from hexaleg.evaluation.requirements import Requirements
from hexaleg.study.decide import decide
from hexaleg.study.optimize import POPULATION_PER_VARIABLE, SearchSettings


def bench_decide(evaluations: int | None) -> list[Row]:
    """l1, l2, l3 free, 60 kg on 20° in every heading, FB maximized: 2 processes vs 1."""
    design = HexapodDesign()
    requirements = Requirements(payload=60.0, slope=math.radians(20))
    settings = SearchSettings(seed=0, evaluations=evaluations)

    def run(executor):
        start = time.perf_counter()
        result = decide(design, requirements, settings=settings, executor=executor, progress=False)
        return time.perf_counter() - start, result

    with ProcessPoolExecutor(2) as pool:
        pool.submit(int).result()  # workers started before timing, as a long-lived pool is
        t_pool, found = run(pool)
    with ThreadPoolExecutor(1) as here:
        t_here, alone = run(here)
    best = [found.best.evaluation.metrics.value(METRICS.fb), *found.best.design.lengths]
    difference = check_agree(
        "decide 2 processes / 1",
        best,
        [alone.best.evaluation.metrics.value(METRICS.fb), *alone.best.design.lengths],
        0.0,
    )
    name = f"decide, 3 free lengths, payload + slope, {found.evaluations} designs"
    note = (
        f"FB {found.best.evaluation.metrics.value(METRICS.fb):.5f} at l = "
        f"({', '.join(f'{v:.4f}' for v in found.best.design.lengths)}) m, feasible {found.feasible}"
    )
    return [
        Row(name, "hexaleg decide, 2 processes", t_pool, None, None, "≤ 60 s", note=note),
        Row(
            name,
            "hexaleg decide, this process",
            t_here,
            t_here / t_pool,
            difference,
            note="ratio: 1-process time / 2-process time",
        ),
    ]


def bench_decide_walking(evaluations: int | None) -> list[Row]:
    """l1, l2, l3 free, a tripod at 0.3 m/s carrying 10 kg within the ratings, area maximized."""
    design = HexapodDesign()
    requirements = Requirements(payload=10.0, speed=0.3)
    settings = SearchSettings(seed=0, evaluations=evaluations)
    with ProcessPoolExecutor(2) as pool:
        pool.submit(int).result()
        start = time.perf_counter()
        found = decide(design, requirements, Objective("improved_area"), settings=settings,
                       executor=pool, progress=False)  # fmt: skip
        elapsed = time.perf_counter() - start
    best = found.best.evaluation.metrics
    note = (
        f"area {best.improved_area:.5f} m² at l = "
        f"({', '.join(f'{v:.4f}' for v in found.best.design.lengths)}) m, max speed "
        f"{best.max_speed:.4f} m/s, feasible {found.feasible}"
    )
    name = f"decide, 3 free lengths, speed + payload, {found.evaluations} designs"
    return [Row(name, "hexaleg decide, 2 processes", elapsed, None, None, "≤ 60 s", note=note)]


def bench_decide_actuators(evaluations: int | None) -> list[Row]:
    """l1, l2, l3 free and each joint type's actuator from the catalog, lightest robot.

    Timed beside two baselines in the same pool: the lengths alone with the actuators
    fixed (the catalog entries the search picks), and with the gear ratios free too.
    Ratios are per design evaluated, since each search's budget grows with its variables.
    """
    from hexaleg.actuator_catalog import shipped_catalog
    from hexaleg.actuators import Actuators

    design = HexapodDesign()
    requirements = Requirements(continuous_margin=1.0)
    objective = Objective("robot_mass", "minimize")
    settings = SearchSettings(seed=0, evaluations=evaluations)
    catalog = list(shipped_catalog())
    entries = [entry.actuator for entry in catalog]
    ranges = [entry.gear_ratio_range for entry in catalog]

    quick_geared = SearchSettings(seed=0, evaluations=2 * 9 * POPULATION_PER_VARIABLE)
    geared_settings = settings if evaluations is None else quick_geared  # 2 generations

    def run(pool, base, settings=settings, **options):
        start = time.perf_counter()
        found = decide(base, requirements, objective, settings=settings, executor=pool,
                       progress=False, **options)  # fmt: skip
        return time.perf_counter() - start, found

    with ProcessPoolExecutor(2) as pool:
        pool.submit(int).result()
        elapsed, found = run(pool, design, actuators=entries)
        chosen_motors = found.best.design.actuators or Actuators(*entries[:3])
        t_fixed, fixed = run(pool, design.replace(actuators=chosen_motors))
        t_geared, geared = run(
            pool, design, geared_settings, actuators=entries, ratio_ranges=ranges
        )

    def note(result) -> str:
        best = result.best.design
        motors = best.actuators.joints if best.actuators else ()
        chosen = ", ".join(f"{a.catalog or 'given'} N={a.gear_ratio:.4g}" for a in motors)
        return (
            f"{result.best.evaluation.metrics.value(METRICS.robot_mass):.2f} kg at l = "
            f"({', '.join(f'{v:.4f}' for v in best.lengths)}) m with {chosen}, "
            f"feasible {result.feasible}"
        )

    name = f"decide --choose-actuators, 3 free lengths, {found.evaluations} designs"

    def compared(label: str, seconds: float, result, ratio: float, what: str) -> Row:
        return Row(name, label, seconds, ratio, None, note=f"ratio: time per design {what}; "
                   + note(result))  # fmt: skip

    def per_design(seconds: float, result) -> float:
        return seconds / result.evaluations

    return [
        Row(name, "hexaleg decide, 2 processes", elapsed, None, None, "≤ 90 s", note=note(found)),
        compared(
            f"baseline: lengths only, those actuators fixed ({fixed.evaluations} designs)",
            t_fixed,
            fixed,
            per_design(elapsed, found) / per_design(t_fixed, fixed),
            "choosing / with the actuators fixed",
        ),
        compared(
            f"--free-gear-ratio too ({geared.evaluations} designs)",
            t_geared,
            geared,
            per_design(t_geared, geared) / per_design(elapsed, found),
            "with free ratios / choosing only",
        ),
    ]
