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
    for _ in range(3):  # warm-up: caches, allocator, CPU frequency
        fn()
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


def median_times(
    fns: list[Callable[[], object]], repeats: int, min_time: float = 0.05
) -> list[float]:
    """Median wall times of several functions measured round-robin, so drift hits all alike."""
    loops = []
    for fn in fns:
        for _ in range(3):
            fn()
        start = time.perf_counter()
        fn()
        loops.append(max(1, math.ceil(min_time / max(time.perf_counter() - start, 1e-9))))
    samples: list[list[float]] = [[] for _ in fns]
    for _ in range(repeats):
        for k, fn in enumerate(fns):
            start = time.perf_counter()
            for _ in range(loops[k]):
                fn()
            samples[k].append((time.perf_counter() - start) / loops[k])
    return [statistics.median(s) for s in samples]


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
    t_hex, t_bare = median_times([hexaleg_run, bare_numpy], repeats)
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
            note=f"FB {free.fb:.4f}, {free.iterations} SLSQP iterations, "
            f"converged {free.converged}",
        )
    )
    return rows


def _optional(module: str):
    """Import an alternative if the [bench] extra is installed, else None."""
    import importlib
    import warnings

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return importlib.import_module(module)
    except ImportError:
        return None


def _missing(workload: str, name: str) -> Row:
    return Row(workload, name, math.nan, None, None, note="not installed: pip install '.[bench]'")


def _rtb_leg(lengths):
    """The paper's D-H table (Table 1) as a robotics-toolbox DHRobot."""
    rtb = _optional("roboticstoolbox")
    if rtb is None:
        return None
    l1, l2, l3 = lengths
    return rtb.DHRobot(
        [rtb.RevoluteDH(a=l1, alpha=math.pi / 2), rtb.RevoluteDH(a=l2), rtb.RevoluteDH(a=l3)]
    )


def bench_forward_kinematics(samples: int, repeats: int) -> list[Row]:
    """FK of random leg configurations: hexaleg vs NumPy, Pinocchio loop, robotics-toolbox."""
    import pinocchio as pin

    from hexaleg import HexapodDesign, LegModel, foot_position

    design = HexapodDesign()
    theta = np.random.default_rng(1).uniform(-1.0, 1.0, size=(samples, 3))
    l1, l2, l3 = design.lengths

    def hexaleg_run():
        return foot_position(design.lengths, theta)

    def bare_numpy():
        t1, t2, t3 = theta.T
        reach = l1 + l2 * np.cos(t2) + l3 * np.cos(t2 + t3)
        return np.c_[np.cos(t1) * reach, np.sin(t1) * reach, l2 * np.sin(t2) + l3 * np.sin(t2 + t3)]

    leg = LegModel(design)
    frame = leg.model.getFrameId("leg_foot")
    loop_n = min(samples, 20_000)

    def pinocchio_loop():
        out = np.empty((loop_n, 3))
        for i, q in enumerate(theta[:loop_n]):
            pin.framesForwardKinematics(leg.model, leg.data, q)
            out[i] = leg.data.oMf[frame].translation
        return out

    name = f"forward kinematics, {samples:,} configurations"
    reference = hexaleg_run()
    d = check_agree("fk / numpy", reference, bare_numpy(), 1e-12)
    t_hex, t = median_times([hexaleg_run, bare_numpy], repeats)
    rows = [Row(name, "hexaleg foot_position", t_hex, None, None)]
    rows.append(Row(name, "bare NumPy eq 7", t, t / t_hex, d, note="timed round-robin"))
    d = check_agree("fk / pinocchio", reference[:loop_n], pinocchio_loop(), 1e-12)
    t = median_time(pinocchio_loop, 3, min_time=0.0) * samples / loop_n
    rows.append(
        Row(
            name,
            "Pinocchio in a Python loop",
            t,
            t / t_hex,
            d,
            note=f"timed on {loop_n:,}, scaled" if loop_n < samples else "",
        )
    )
    robot = _rtb_leg(design.lengths)
    if robot is None:
        rows.append(_missing(name, "robotics-toolbox ETS.fkine"))
    else:
        ets = robot.ets()

        def rtb_run():
            return np.asarray(ets.fkine(theta).t)

        d = check_agree("fk / robotics-toolbox", reference, rtb_run(), 1e-12)
        t = median_time(rtb_run, repeats)
        rows.append(Row(name, "robotics-toolbox ETS.fkine (compiled)", t, t / t_hex, d))
    return rows


def bench_manipulability_grid(l3_points: int, repeats: int) -> list[Row]:
    """W on the 121 × 121 grid of one design, and w_A of the 4 × N sweep, vs robotics-toolbox."""
    from hexaleg import HexapodDesign, manipulability
    from hexaleg.manipulability import joint_grid

    design = HexapodDesign()
    hip, knee = joint_grid(design.manipulability_limits)
    t2, t3 = np.meshgrid(hip, knee, indexing="ij")
    q = np.stack([np.zeros(t2.size), t2.ravel(), t3.ravel()], axis=1)

    def hexaleg_run():
        return manipulability(design.lengths, t2, t3).ravel()

    reference = hexaleg_run()
    t_hex = median_time(hexaleg_run, repeats)
    name = "w on the 121 × 121 grid, one design"
    rows = [Row(name, "hexaleg manipulability", t_hex, None, None)]
    robot = _rtb_leg(design.lengths)
    sweep = bench_average_manipulability(l3_points, repeats)
    if robot is None:
        return [*rows, _missing(name, "robotics-toolbox manipulability"), *sweep]
    else:
        subset = q[:: max(1, len(q) // 2000)]

        def rtb_run():
            return np.asarray(robot.manipulability(subset, axes="trans"), dtype=float)

        d = check_agree(
            "w / robotics-toolbox", reference[:: max(1, len(q) // 2000)], rtb_run(), 1e-12
        )
        t = median_time(rtb_run, 1, min_time=0.0) * len(q) / len(subset)
        rows.append(
            Row(
                name,
                "robotics-toolbox manipulability(axes='trans')",
                t,
                t / t_hex,
                d,
                note=f"timed on {len(subset):,} poses, scaled",
            )
        )
        # the Fig 11 sweep: rtb needs one robot per design and a loop over poses
        t_sweep_hex = sweep[0].median_s
        designs = 4 * l3_points  # the paper's four coxa ratios
        t_rtb_sweep = t * designs
        rows += [
            sweep[0],
            Row(
                sweep[0].workload,
                "robotics-toolbox manipulability, per design",
                t_rtb_sweep,
                t_rtb_sweep / t_sweep_hex,
                None,
                note="one design's grid timed, scaled to every design",
            ),
            *sweep[1:],
        ]
    return rows


def bench_inverse_kinematics(targets: int, repeats: int) -> list[Row]:
    """IK of reachable foot targets: hexaleg closed form vs robotics-toolbox and ikpy."""
    import tempfile
    import warnings

    from hexaleg import HexapodDesign, foot_position, inverse_kinematics, render_leg

    design = HexapodDesign()
    rng = np.random.default_rng(2)
    truth = np.c_[
        rng.uniform(-0.7, 0.7, targets),
        rng.uniform(-0.9, 0.9, targets),
        rng.uniform(-2.2, -0.3, targets),
    ]
    goal = foot_position(design.lengths, truth)

    def hexaleg_run():
        return inverse_kinematics(design.lengths, goal).theta

    solution = hexaleg_run()
    d_self = check_agree("ik / fk round trip", goal, foot_position(design.lengths, solution), 1e-12)
    t_hex = median_time(hexaleg_run, repeats)
    name = f"inverse kinematics, {targets:,} reachable targets"
    rows = [
        Row(
            name,
            "hexaleg inverse_kinematics (eq 8–9)",
            t_hex,
            None,
            d_self,
            note="max diff: position error [m]",
        )
    ]

    robot = _rtb_leg(design.lengths)
    if robot is None:
        rows.append(_missing(name, "robotics-toolbox ik_LM"))
    else:
        ets = robot.ets()
        subset = min(targets, 2000)
        poses = np.repeat(np.eye(4)[None], subset, axis=0)
        poses[:, :3, 3] = goal[:subset]
        mask = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])

        def rtb_ik(method: str, count: int) -> np.ndarray:
            out = np.empty((count, 3))
            for i in range(count):
                q0 = truth[i] + 0.1  # a nearby start, as a controller would have
                if method == "ik_LM":
                    out[i] = ets.ik_LM(
                        poses[i], q0=q0, mask=mask, tol=1e-14, ilimit=100, slimit=10
                    )[0]
                else:
                    out[i] = robot.ikine_LM(poses[i], q0=q0, mask=mask, tol=1e-14).q
            return out

        for method, label, count in (
            ("ik_LM", "robotics-toolbox ik_LM (C++)", subset),
            ("ikine_LM", "robotics-toolbox ikine_LM (Python)", min(subset, 300)),
        ):
            reached = rtb_ik(method, count)
            d = check_agree(
                f"ik / {method}", goal[:count], foot_position(design.lengths, reached), 1e-6
            )
            t = (
                median_time(lambda m=method, c=count: rtb_ik(m, c), 1, min_time=0.0)
                * targets
                / count
            )
            rows.append(
                Row(
                    name,
                    label,
                    t,
                    t / t_hex,
                    d,
                    note=f"timed on {count:,}, scaled; max diff: position [m]",
                )
            )
    ikpy_chain = _optional("ikpy.chain")
    if ikpy_chain is None:
        rows.append(_missing(name, "ikpy"))
    else:
        with tempfile.NamedTemporaryFile("w", suffix=".urdf", delete=False) as handle:
            handle.write(render_leg(design))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            chain = ikpy_chain.Chain.from_urdf_file(
                handle.name,
                base_elements=["base_link"],
                active_links_mask=[False, False, True, True, True, False],
            )
        count = min(targets, 200)

        def ikpy_run():
            out = np.empty((count, 3))
            for i in range(count):
                start = np.r_[0.0, 0.0, truth[i] + 0.1, 0.0]
                out[i] = chain.inverse_kinematics(goal[i], initial_position=start)[2:5]
            return out

        reached = ikpy_run()
        d = check_agree("ik / ikpy", goal[:count], foot_position(design.lengths, reached), 1e-6)
        t = median_time(ikpy_run, 1, min_time=0.0) * targets / count
        rows.append(
            Row(
                name,
                "ikpy inverse_kinematics (from hexaleg's URDF)",
                t,
                t / t_hex,
                d,
                note=f"timed on {count:,}, scaled; max diff: position [m]",
            )
        )
    return rows


def bench_optimum_pose(repeats: int) -> list[Row]:
    """Table 6's first row: hexaleg's optimum vs a single scipy run on the plain closed form."""
    from scipy import optimize

    from hexaleg import MANIPULABILITY_LIMITS
    from hexaleg.manipulability import optimum_pose

    lengths = (0.05, 0.475, 0.475)

    def hexaleg_run():
        pose = optimum_pose(lengths, MANIPULABILITY_LIMITS)
        return np.array([pose.theta2, pose.theta3, pose.w])

    def plain_scipy():
        # what a user porting fmincon would write: SLSQP from mid-box, numeric gradient
        def w(x):
            l1, l2, l3 = lengths
            return -abs(
                l2 * l3 * math.sin(x[1]) * (l1 + l2 * math.cos(x[0]) + l3 * math.cos(x[0] + x[1]))
            )

        res = optimize.minimize(
            w,
            x0=[0.0, -1.3],
            method="SLSQP",
            options={"ftol": 1e-15},
            bounds=[MANIPULABILITY_LIMITS.theta2, MANIPULABILITY_LIMITS.theta3],
        )
        return np.array([res.x[0], res.x[1], -res.fun])

    reference = hexaleg_run()
    d = check_agree("optimum / scipy", reference, plain_scipy(), 1e-5)
    t_hex = median_time(hexaleg_run, repeats)
    t = median_time(plain_scipy, repeats)
    name = "optimum-w pose, Table 6 row 1"
    return [
        Row(name, "hexaleg optimum_pose (grid + L-BFGS-B)", t_hex, None, None),
        Row(
            name,
            "scipy SLSQP on the closed form, one start",
            t,
            t / t_hex,
            d,
            note="faster but local: hexaleg guards against local optima",
        ),
    ]


def bench_dask(l3_points: int, repeats: int) -> list[Row]:
    """The Fig 15 sweep on a 2-worker Dask LocalCluster vs the local process pool."""
    import tempfile
    from concurrent.futures import ProcessPoolExecutor

    from hexaleg.design import l3_ratio_grid
    from hexaleg.paper import L1_RATIOS
    from hexaleg.study import StudySpec, run_study

    name = f"Fig 15 sweep, {4 * l3_points} designs, 2 workers"
    distributed = _optional("distributed")
    if distributed is None:
        return [_missing(name, "Dask LocalCluster")]
    spec = StudySpec(tuple(L1_RATIOS), tuple(l3_ratio_grid(l3_points)))

    def sweep(executor):
        with tempfile.TemporaryDirectory() as out:
            return run_study(spec, out, executor=executor, progress=False)["fb"].to_numpy()

    with ProcessPoolExecutor(2) as pool:
        pool.submit(int).result()
        reference = sweep(pool)
        t_pool = median_time(lambda: sweep(pool), max(3, repeats // 2), min_time=0.0)
    with (
        distributed.LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            host="127.0.0.1",
            dashboard_address=None,
            processes=True,
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        executor = client.get_executor()
        d = check_agree("dask / pool", reference, sweep(executor), 0.0)
        t_dask = median_time(lambda: sweep(executor), max(3, repeats // 2), min_time=0.0)
    return [
        Row(name, "local process pool", t_pool, None, None),
        Row(
            name,
            "Dask LocalCluster (127.0.0.1)",
            t_dask,
            t_dask / t_pool,
            d,
            note="ratio here: Dask time / pool time (overhead)",
        ),
    ]


WORKLOADS = {
    "forward_kinematics": lambda quick, r: bench_forward_kinematics(2_000 if quick else 100_000, r),
    "monte_carlo": lambda quick, r: bench_monte_carlo(2_000 if quick else 100_000, r),
    "manipulability": lambda quick, r: bench_manipulability_grid(4 if quick else 80, r),
    "inverse_kinematics": lambda quick, r: bench_inverse_kinematics(200 if quick else 10_000, r),
    "optimum_pose": lambda quick, r: bench_optimum_pose(r),
    "flexibility": lambda quick, r: bench_flexibility(4 if quick else 80, r),
    "dask": lambda quick, r: bench_dask(4 if quick else 80, r),
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
        timing = f"{_seconds(row.median_s):>10} {ratio} {diff}"
        print(f"{row.workload:<44} {row.implementation:<48} {timing}  {row.target}")
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
