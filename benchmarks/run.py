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
import platform
import sys

from bench_decide import (
    bench_decide,
    bench_decide_actuators,
    bench_decide_posture,
    bench_decide_sizing,
    bench_decide_walking,
)
from bench_electrical import bench_electrical
from bench_explore import bench_explore, bench_explore_robot
from bench_flexibility import bench_dask, bench_flexibility
from bench_gait import bench_gait, bench_walking_columns
from bench_import import bench_import
from bench_kinematics import bench_forward_kinematics, bench_inverse_kinematics, bench_monte_carlo
from bench_manipulability import bench_manipulability_grid, bench_optimum_pose
from bench_posture import bench_posture
from bench_simulate import bench_simulate
from bench_structure import bench_structure
from harness import Row, seconds

WORKLOADS = {
    "forward_kinematics": lambda quick, r: bench_forward_kinematics(2_000 if quick else 100_000, r),
    "monte_carlo": lambda quick, r: bench_monte_carlo(2_000 if quick else 100_000, r),
    "manipulability": lambda quick, r: bench_manipulability_grid(4 if quick else 80, r),
    "inverse_kinematics": lambda quick, r: bench_inverse_kinematics(200 if quick else 10_000, r),
    "optimum_pose": lambda quick, r: bench_optimum_pose(r),
    "flexibility": lambda quick, r: bench_flexibility(4 if quick else 80, r),
    "dask": lambda quick, r: bench_dask(4 if quick else 80, r),
    "gait": lambda quick, r: bench_gait(4 if quick else 80, r),
    "walking_columns": lambda quick, r: bench_walking_columns(4 if quick else 80, r),
    "electrical": lambda quick, r: bench_electrical(r),
    "decide": lambda quick, r: bench_decide(60 if quick else None),
    "simulate": lambda quick, r: bench_simulate(2 if quick else 4, r),
    "decide_walking": lambda quick, r: bench_decide_walking(60 if quick else None),
    "import": lambda quick, r: bench_import(r),
    "explore": lambda quick, r: bench_explore(4 if quick else 12, r),
    "explore_robot": lambda quick, r: bench_explore_robot(4 if quick else 12, r),
    "decide_actuators": lambda quick, r: bench_decide_actuators(120 if quick else None),
    "posture": lambda quick, r: bench_posture(1 if quick else r, grid=not quick),
    "structure": lambda quick, r: bench_structure(r),
    "decide_posture": lambda quick, r: bench_decide_posture(2 if quick else None),
    "decide_sizing": lambda quick, r: bench_decide_sizing(2 if quick else None),
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
        f"{'workload':<44} {'implementation':<48} {'median':>10} {'ratio':>8} {'max diff':>9}"
        "  target"
    )
    print(header)
    print("-" * len(header))
    for row in rows:
        ratio = f"{row.ratio:8.1f}" if row.ratio is not None else f"{'':>8}"
        diff = f"{row.max_difference:9.1e}" if row.max_difference is not None else f"{'':>9}"
        timing = f"{seconds(row.median_s):>10} {ratio} {diff}"
        print(f"{row.workload:<44} {row.implementation:<48} {timing}  {row.target}")
        if row.note:
            print(f"{'':<44}   ({row.note})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
