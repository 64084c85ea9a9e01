"""Workload on decide: three-variable searches with payload and slope, and with a speed."""

from __future__ import annotations

import math
import time
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

from harness import Row, check_agree

from hexaleg import HexapodDesign
from hexaleg.evaluation.evaluate import Conditions, evaluate
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
        result = decide(design, requirements, settings=settings, executor=executor,
                        free_posture=False, progress=False)  # fmt: skip
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
                       executor=pool, free_posture=False, progress=False)  # fmt: skip
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
                       free_posture=False, progress=False, **options)  # fmt: skip
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


def _timed_pair(requirements, first, second, budget):
    """Two decisions of the same requirements in one warm pool: (seconds, result) each.

    ``first`` and ``second``: (design, decide's keyword arguments); ``budget(options)``: each
    search's designs (``None``: decide's default budget).
    """
    results = []
    for design, _ in (first, second):  # every compiled kernel on disk before timing (a
        evaluate(design, tuple(METRICS), Conditions())  # first use compiles it, once)
    with ProcessPoolExecutor(2) as pool:
        pool.submit(int).result()  # workers started before timing, as a long-lived pool is
        for design, options in (first, second):
            settings = SearchSettings(seed=0, evaluations=budget(options))
            start = time.perf_counter()
            found = decide(design, requirements, settings=settings, executor=pool,
                           progress=False, **options)  # fmt: skip
            results.append((time.perf_counter() - start, found))
    return results


def _note(result) -> str:
    best = result.best
    return (
        f"FB {best.evaluation.metrics.value(METRICS.fb):.5f} at l = "
        f"({', '.join(f'{v:g}' for v in best.design.lengths)}) m, θ = "
        f"({', '.join(f'{v:g}' for v in best.design.nominal_angles[1:])}) rad, "
        f"{result.evaluations} designs + {result.rounded.measured} grid points, "
        f"feasible {result.feasible}"
    )


def _compared(name, labels, timed, target, what) -> list[Row]:
    """The baseline's row, then the compared decision's with the ratio of their times."""
    (t_base, base), (t_other, other) = timed
    ratio = t_other / t_base
    return [
        Row(name, labels[0], t_base, None, None, note=_note(base)),
        Row(name, labels[1], t_other, ratio, None, target, note=f"ratio: {what}; {_note(other)}"),
    ]


def bench_decide_posture(generations: int | None) -> list[Row]:
    """Decide with the posture free (the default) against the same decision with it fixed.

    60 kg on 20° in every heading, FB maximized; each search its default budget (its
    generations of 10 designs a free variable: 3 variables fixed, 5 free), or ``generations``
    of them (quick). The target: free ≤ 1.5 × fixed, wall time of the whole decision.
    """
    requirements = Requirements(payload=60.0, slope=math.radians(20))
    design = HexapodDesign()

    def budget(options):
        variables = 5 if options["free_posture"] else 3
        return None if generations is None else generations * POPULATION_PER_VARIABLE * variables

    timed = _timed_pair(
        requirements, (design, {"free_posture": False}), (design, {"free_posture": True}), budget
    )
    labels = ("hexaleg decide --fixed-posture, 2 processes", "hexaleg decide (posture free)")
    name = "decide, posture free vs fixed, payload + slope"
    return _compared(name, labels, timed, "ratio ≤ 1.5", "free / fixed wall time")


def bench_decide_sizing(generations: int | None) -> list[Row]:
    """Decide sizing every candidate's tubes against the same decision without tubes.

    The template's legs of 6061-T6 tubes sized per candidate (``[structure] size = true``,
    hexaleg's tube grid) against its link_linear_density, the posture fixed; 60 kg on 20°,
    FB maximized. The target: sized ≤ 2 × unsized, wall time of the whole decision.
    """
    from hexaleg.leg_structure import Structure
    from hexaleg.materials import shipped_materials

    requirements = Requirements(payload=60.0, slope=math.radians(20))
    plain = HexapodDesign()
    tubes = Structure(shipped_materials().material("aluminium_6061_t6"), size=True)
    sized = plain.replace(structure=tubes)

    def budget(_options):
        return None if generations is None else generations * POPULATION_PER_VARIABLE * 3

    fixed = {"free_posture": False}
    timed = _timed_pair(requirements, (plain, fixed), (sized, fixed), budget)
    labels = ("hexaleg decide, link density, 2 processes", "hexaleg decide, [structure] size")
    name = "decide, tubes sized per candidate vs none"
    return _compared(name, labels, timed, "ratio ≤ 2", "sized / unsized wall time")
