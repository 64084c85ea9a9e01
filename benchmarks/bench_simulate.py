"""Workload on the MuJoCo walk: simulated time against wall time (real time is the yardstick).

The ratio column is simulated time over wall time: how many times faster than real time
the walk runs (target ≥ 10 on two cores). Rows: the MuJoCo run alone (stepping, the
servos' commands, recording every step) and the whole ``simulate_gait`` (planning the
period, the walk, the measures and the tripod standing check).
"""

from __future__ import annotations

from harness import Row, median_time

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.gait import Gait, analyze_gait
from hexaleg.sim import SimModel, plan_of, run_plan, simulate_gait


def bench_simulate(cycles: int, repeats: int) -> list[Row]:
    """The default robot walking ``cycles`` default tripod periods in MuJoCo."""
    design, gait = HexapodDesign(), Gait()
    model = HexapodModel(design)
    simulated = cycles * gait.period
    plan = plan_of(analyze_gait(design, gait, model=model, limits=False))
    sim = SimModel(model)
    reached: list[float] = []  # the body's x at the end of each part of the trace
    run_plan(sim, plan, simulated, record=lambda part: reached.append(part.base_position[-1, 0]))
    if reached[-1] < 0.5 * gait.speed * simulated:
        raise SystemExit("benchmark MuJoCo walk: the robot did not walk")
    t_run = median_time(
        lambda: run_plan(sim, plan, simulated, record=lambda part: None), repeats, min_time=0.0
    )
    t_all = median_time(
        lambda: simulate_gait(design, gait, cycles=cycles, model=model),
        max(1, repeats // 2),
        min_time=0.0,
    )
    workload = f"MuJoCo walk, {cycles} tripod periods ({simulated:g} s simulated)"
    note = "ratio: simulated time / wall time (× real time)"
    return [
        Row(
            workload,
            "hexaleg run_plan (steps, servo commands, record)",
            t_run,
            simulated / t_run,
            None,
            "≥ 10× real time",
            note,
        ),
        Row(
            workload,
            "hexaleg simulate_gait (plan, walk, measure, stand)",
            t_all,
            simulated / t_all,
            None,
            "",
            "the tripod standing check adds 2 s simulated, not counted",
        ),
    ]
