"""hexaleg benchmarks: each workload timed beside its baselines in the same process.

Run ``python benchmarks/run.py`` (``--json`` for machines, ``--quick`` for tiny
sizes). Every baseline must agree numerically with hexaleg before it is timed;
the table reports medians, the ratio baseline/hexaleg (> 1: hexaleg is faster)
and the largest difference. Targets are printed beside the ratios, never asserted
in the test suite: shared machines are noisy.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np


@dataclass
class Row:
    """One line of the results table."""

    workload: str
    implementation: str
    median_s: float
    ratio: float | None  # baseline median / hexaleg median
    max_difference: float | None
    target: str = ""
    note: str = ""
    extra: dict = field(default_factory=dict)


def median_time(fn: Callable[[], object], repeats: int, min_time: float = 0.05) -> float:
    """Median wall time of ``fn`` over ``repeats`` runs (each run looped to ≥ min_time)."""
    fn()  # warm-up
    start = time.perf_counter()
    fn()
    once = time.perf_counter() - start
    loops = max(1, math.ceil(min_time / max(once, 1e-9)))
    samples = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(loops):
            fn()
        samples.append((time.perf_counter() - start) / loops)
    return statistics.median(samples)


def check_agree(name: str, reference: np.ndarray, other: np.ndarray, atol: float) -> float:
    """Largest absolute difference; raise if it exceeds ``atol``."""
    diff = float(np.max(np.abs(np.asarray(reference) - np.asarray(other))))
    if not diff <= atol:
        raise SystemExit(f"benchmark {name}: results disagree by {diff:.3g} > {atol:.3g}")
    return diff


# -- workloads ------------------------------------------------------------------------


def bench_monte_carlo(samples: int, repeats: int) -> list[Row]:
    """Monte Carlo workspace: hexaleg vs bare NumPy eq 7 vs a Pinocchio loop."""
    import pinocchio as pin

    from hexaleg import HexapodDesign, LegModel
    from hexaleg.workspace import monte_carlo_workspace

    design = HexapodDesign()
    leg = LegModel(design)
    limits = design.workspace_limits
    l1, l2, l3 = design.lengths

    def hexaleg_run():
        return monte_carlo_workspace(design, samples, seed=0).points

    def bare_numpy():
        theta = np.random.default_rng(0).uniform(limits.lower, limits.upper, size=(samples, 3))
        t1, t2, t3 = theta.T
        reach = l1 + l2 * np.cos(t2) + l3 * np.cos(t2 + t3)
        return np.c_[np.cos(t1) * reach, np.sin(t1) * reach, l2 * np.sin(t2) + l3 * np.sin(t2 + t3)]

    loop_n = min(samples, 20_000)
    frame = leg.model.getFrameId("leg_foot")

    def pinocchio_loop():
        theta = np.random.default_rng(0).uniform(limits.lower, limits.upper, size=(loop_n, 3))
        out = np.empty((loop_n, 3))
        for i, q in enumerate(theta):
            pin.framesForwardKinematics(leg.model, leg.data, q)
            out[i] = leg.data.oMf[frame].translation
        return out

    reference = hexaleg_run()
    d_bare = check_agree("monte carlo / numpy", reference, bare_numpy(), 1e-12)
    d_pin = check_agree("monte carlo / pinocchio", reference[:loop_n], pinocchio_loop(), 1e-12)
    t_hex = median_time(hexaleg_run, repeats)
    t_bare = median_time(bare_numpy, repeats)
    t_pin = median_time(pinocchio_loop, max(3, repeats // 3)) * samples / loop_n
    name = f"Monte Carlo workspace, {samples:,} samples"
    return [
        Row(name, "hexaleg monte_carlo_workspace", t_hex, None, None),
        Row(
            name,
            "bare NumPy eq 7",
            t_bare,
            t_bare / t_hex,
            d_bare,
            "hexaleg ≤ 2× bare: ratio ≥ 0.5",
        ),
        Row(
            name,
            "Pinocchio in a Python loop",
            t_pin,
            t_pin / t_hex,
            d_pin,
            "ratio ≥ 10",
            note=f"loop timed on {loop_n:,} samples, scaled" if loop_n < samples else "",
        ),
    ]


def bench_average_manipulability(l3_points: int, repeats: int) -> list[Row]:
    """w_A over the Fig 11 design grid: vectorized kernel vs a per-configuration Pinocchio loop."""
    from hexaleg import LegModel
    from hexaleg.design import HexapodDesign, l3_ratio_grid
    from hexaleg.manipulability import average_manipulability, joint_grid
    from hexaleg.paper import L1_RATIOS

    limits = HexapodDesign().manipulability_limits
    r3 = l3_ratio_grid(l3_points)
    r1 = np.array(L1_RATIOS)
    l1 = np.repeat(r1, len(r3))
    l3 = np.tile(r3, len(r1))
    lengths = np.c_[l1, 1 - l1 - l3, l3]

    def hexaleg_run():
        return average_manipulability(lengths, limits)

    hip, knee = joint_grid(limits)
    sample_designs = lengths[:: max(1, len(lengths) // 2)][:2]
    legs = [LegModel(HexapodDesign(l1=a, l2=b, l3=c)) for a, b, c in sample_designs]

    def pinocchio_loop():
        out = []
        for leg in legs:
            total = 0.0
            for t2 in hip:
                for t3 in knee:
                    total += abs(np.linalg.det(leg.foot_jacobian(np.array([0.0, t2, t3]))))
            out.append(total / (len(hip) * len(knee)))
        return np.array(out)

    reference = hexaleg_run()
    index = [int(np.flatnonzero((lengths == d).all(axis=1))[0]) for d in sample_designs]
    d_pin = check_agree("w_A / pinocchio", reference[index], pinocchio_loop(), 1e-12)
    t_hex = median_time(hexaleg_run, repeats)
    t_pin = median_time(pinocchio_loop, 1, min_time=0.0) * len(lengths) / len(legs)
    name = f"w_A, {len(r1)} × {len(r3)} designs × 121 × 121 poses"
    return [
        Row(name, "hexaleg average_manipulability", t_hex, None, None, "≤ 0.1 s"),
        Row(
            name,
            "Pinocchio loop, |det J| per pose",
            t_pin,
            t_pin / t_hex,
            d_pin,
            "ratio ≥ 150",
            note=f"loop timed on {len(legs)} designs, scaled to {len(lengths)}",
        ),
    ]


def step_and_bisect_extremes(geometry, translation_step: float = 1e-3, angle_step: float = 1e-3):
    """The straightforward way: step each direction until infeasible, then bisect 50 times."""
    from hexaleg.flexibility import AXES, DIRECTIONS, direction_poses, stance_margins

    def feasible(axis: int, value: float) -> bool:
        rotation, translation = direction_poses(geometry, axis, value)
        return bool(stance_margins(geometry, rotation, translation).min() >= 0)

    values = []
    for axis_name, sign in DIRECTIONS:
        axis = AXES.index(axis_name)
        step = translation_step if axis < 3 else angle_step
        t = 0.0
        while feasible(axis, sign * (t + step)):
            t += step
        lo, hi = t, t + step
        for _ in range(50):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if feasible(axis, sign * mid) else (lo, mid)
        values.append(sign * lo)
    return np.array(values)


def bench_flexibility(l3_points: int, repeats: int) -> list[Row]:
    """Axis-locked FB of one design, the Fig 15 sweep, and free-coupled FB."""
    import tempfile
    import warnings
    from concurrent.futures import ProcessPoolExecutor

    from hexaleg import HexapodDesign, HexapodModel
    from hexaleg.design import l3_ratio_grid
    from hexaleg.flexibility import axis_locked_extremes, free_flexibility
    from hexaleg.paper import L1_RATIOS
    from hexaleg.stance import StanceGeometry
    from hexaleg.study import StudySpec, run_study

    design = HexapodDesign()
    model = HexapodModel(design)
    geometry = StanceGeometry.from_model(model, "all")

    def hexaleg_one():
        return np.array([e.value for e in axis_locked_extremes(geometry)])

    reference = hexaleg_one()
    d_one = check_agree(
        "axis-locked / step-and-bisect", reference, step_and_bisect_extremes(geometry), 1e-9
    )
    t_one = median_time(hexaleg_one, repeats)
    t_naive_one = median_time(lambda: step_and_bisect_extremes(geometry), 3, min_time=0.0)
    rows = [
        Row(
            "axis-locked FB, one design",
            "hexaleg axis_locked_extremes",
            t_one,
            None,
            None,
            "≤ 5 ms",
        ),
        Row(
            "axis-locked FB, one design",
            "step (1 mm / 1 mrad) and bisect",
            t_naive_one,
            t_naive_one / t_one,
            d_one,
        ),
    ]

    spec = StudySpec(tuple(L1_RATIOS), tuple(l3_ratio_grid(l3_points)))
    with ProcessPoolExecutor(2) as pool:
        pool.submit(int).result()  # start the workers before timing, as a long-lived pool would be

        def sweep():
            with tempfile.TemporaryDirectory() as out:
                return run_study(spec, out, executor=pool)["fb"].to_numpy()

        fb_sweep = sweep()
        t_sweep = median_time(sweep, max(3, repeats // 2), min_time=0.0)
    subset = spec.keys()[:: max(1, len(spec.keys()) // 8)]
    template = geometry

    def naive_sweep():
        out = []
        for r1, r3 in subset:
            g = template.with_design(HexapodDesign.from_ratios(r1, r3))
            out.append(step_and_bisect_extremes(g))
        return out

    t_naive_sweep = median_time(naive_sweep, 1, min_time=0.0) * len(spec.keys()) / len(subset)
    name = f"Fig 15 sweep, {len(spec.keys())} designs"
    rows += [
        Row(
            name,
            "hexaleg run_study, 2 processes",
            t_sweep,
            None,
            None,
            "≤ 2 s",
            extra={"designs": len(fb_sweep)},
        ),
        Row(
            name,
            "step and bisect, 1 process",
            t_naive_sweep,
            t_naive_sweep / t_sweep,
            None,
            note=f"timed on {len(subset)} designs, scaled",
        ),
    ]

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        free = free_flexibility(design, "all", model)
        t_free = median_time(lambda: free_flexibility(design, "all", model), 3, min_time=0.0)
    rows.append(
        Row(
            "free-coupled FB, one design",
            "hexaleg free_flexibility (SLSQP)",
            t_free,
            None,
            None,
            "≤ 1 s",
            note=f"FB {free.fb:.4f}, converged {free.converged}",
        )
    )
    return rows


WORKLOADS = {
    "monte_carlo": lambda quick, r: bench_monte_carlo(2_000 if quick else 100_000, r),
    "average_manipulability": lambda quick, r: bench_average_manipulability(4 if quick else 80, r),
    "flexibility": lambda quick, r: bench_flexibility(4 if quick else 80, r),
}


def main(argv: list[str] | None = None) -> int:
    """Run the benchmarks and print the table (or JSON)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true", help="print JSON instead of a table")
    parser.add_argument("--quick", action="store_true", help="tiny sizes (smoke test)")
    parser.add_argument("--repeats", type=int, default=7, help="timed repeats per implementation")
    parser.add_argument("--only", nargs="*", choices=sorted(WORKLOADS), help="run these workloads")
    args = parser.parse_args(argv)
    rows: list[Row] = []
    for name in args.only or WORKLOADS:
        rows += WORKLOADS[name](args.quick, 3 if args.quick else args.repeats)
    machine = f"{platform.processor() or platform.machine()}, Python {platform.python_version()}"
    if args.json:
        print(json.dumps({"machine": machine, "rows": [vars(r) for r in rows]}, indent=2))
        return 0
    print(f"hexaleg benchmarks on {machine}")
    header = (
        f"{'workload':<44} {'implementation':<34} {'median':>10} {'ratio':>8} {'max diff':>9}"
        "  target"
    )
    print(header)
    print("-" * len(header))
    for row in rows:
        ratio = f"{row.ratio:8.1f}" if row.ratio is not None else f"{'':>8}"
        diff = f"{row.max_difference:9.1e}" if row.max_difference is not None else f"{'':>9}"
        timing = f"{_seconds(row.median_s):>10} {ratio} {diff}"
        print(f"{row.workload:<44} {row.implementation:<34} {timing}  {row.target}")
        if row.note:
            print(f"{'':<44}   ({row.note})")
    return 0


def _seconds(value: float) -> str:
    if value >= 1:
        return f"{value:.2f} s"
    if value >= 1e-3:
        return f"{value * 1e3:.1f} ms"
    return f"{value * 1e6:.0f} µs"


if __name__ == "__main__":
    sys.exit(main())
