"""Workload of the legs' structure: sizing one design's tubes, beside its unsized evaluation.

Sizing (≤ 50 ms a design, the target of issue #41) finds the flexibility extremes once,
then iterates the standing loads and the lightest tubes that hold them until they settle.
Beside it, the same design's evaluation without sizing (every metric a decision reads:
FB, statics, the walk) says what sizing adds to a candidate of ``decide``. Before timing,
the sized tubes are checked again from scratch (the design with them, its own model and
loads): the same ratios. On a shared machine the wall time swings with its load; the CPU
time sizing takes is noted beside it.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable

from harness import Row, check_agree, median_times

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.evaluation.evaluate import Conditions, evaluate
from hexaleg.evaluation.metrics import METRICS
from hexaleg.leg_structure import Structure
from hexaleg.materials import shipped_materials
from hexaleg.statics.forces import Payload
from hexaleg.structure.sizing import size_structure
from hexaleg.structure.standing import check_standing, standing_cases

PAYLOAD, SLOPE = Payload(20.0), math.radians(10)


def _cpu_time(fn: Callable[[], object], runs: int = 10) -> float:
    """Median CPU time of ``fn`` [s]: what it costs, whatever else shares the machine."""
    times = []
    for _ in range(runs):
        start = time.process_time()
        fn()
        times.append(time.process_time() - start)
    return statistics.median(times)


def bench_structure(repeats: int) -> list[Row]:
    """Sizing one design (aluminium, steel) against the unsized evaluation of the design."""
    rows = []
    for name in ("aluminium_6061_t6", "steel_s355"):
        design = HexapodDesign(structure=Structure(shipped_materials().material(name), size=True))
        model = HexapodModel(design)
        sized = size_structure(design, payload=PAYLOAD, slope=SLOPE, model=model)
        again = check_standing(
            model.with_design(sized.design),
            standing_cases(model, model.leg_names, [], PAYLOAD, SLOPE),
        )
        nominal = sized.check.ratios[[0, *range(13, 17)]]  # nominal and the slope's cases
        difference = check_agree(f"structure / {name}", nominal, again.ratios, 1e-12)
        unsized = design.replace(structure=None)
        conditions = Conditions(payload=PAYLOAD, slope=SLOPE)
        sizing, evaluation = median_times(
            [
                lambda d=design, m=model: size_structure(d, payload=PAYLOAD, slope=SLOPE, model=m),
                lambda d=unsized, c=conditions: evaluate(d, tuple(METRICS), c),
            ],
            repeats,
            min_time=0.0,
        )
        cpu = _cpu_time(
            lambda d=design, m=model: size_structure(d, payload=PAYLOAD, slope=SLOPE, model=m)
        )
        tubes = ", ".join(
            f"{t.outer_diameter * 1e3:.0f}×{t.wall * 1e3:.1f}" for t in sized.structure.tubes
        )
        rows.append(
            Row(
                f"sizing one design's tubes ({name})",
                "hexaleg size_structure",
                sizing,
                None,
                difference,
                "≤ 50 ms",
                f"{sized.iterations} rounds; tubes D×t [mm] {tubes}; CPU time {cpu * 1e3:.1f} ms; "
                f"sizing / unsized evaluation = {sizing / evaluation:.2f}",
            )
        )
        rows.append(
            Row(
                "  the same design's unsized evaluation",
                "hexaleg evaluate (every metric)",
                evaluation,
                None,
                None,
            )
        )
    return rows
