"""Workloads on walking: one design's gait period, its limits, the Fig 15 sweep's gait columns."""

from __future__ import annotations

import tempfile
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pinocchio as pin
from harness import Row, check_agree, median_time, median_times

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.design import l3_ratio_grid
from hexaleg.gait import Gait, Walker, analyze_gait
from hexaleg.kinematics import inverse_kinematics
from hexaleg.paper import L1_RATIOS
from hexaleg.study import StudySpec, run_study
from hexaleg.study.rows import design_walking_row
from hexaleg.study.sweep import sweep_in_process


def per_sample_period(model: HexapodModel, gait: Gait) -> np.ndarray:
    """The straightforward way: each sample on its own, every Jacobian from Pinocchio.

    Joint rates by solving the model's foot Jacobian, accelerations with Pinocchio's
    Jacobian time variation, RNEA at the period's v and a, and the minimum-norm forces by
    least squares on the base rows. Returns the joint torques (N, 6, 3) [N·m].
    """
    walker = Walker(model, gait)
    paths = walker.stride(gait.stride).paths
    frames, period = walker.frames, gait.period
    m, d = model.model, model.data
    beta = walker.phases.duty_factor
    travel = gait.stride / beta * walker.heading
    torques = np.empty((gait.samples, 6, 3))
    for k in range(gait.samples):
        q = model.nominal_configuration()
        q[:3] += k / gait.samples * travel
        for i, leg in enumerate(model.leg_names):
            target = frames.to_roots(paths.position[k])[i]
            q[model.leg_q_indices(leg)] = inverse_kinematics(frames.lengths, target).theta
        v = np.zeros(m.nv)
        v[:3] = travel / period
        pin.computeJointJacobians(m, d, q)
        pin.updateFramePlacements(m, d)
        jac = {
            leg: pin.getFrameJacobian(m, d, model.foot_frame_id(leg), pin.LOCAL_WORLD_ALIGNED)[:3]
            for leg in model.leg_names
        }
        for i, leg in enumerate(model.leg_names):
            cols = model.leg_v_indices(leg)
            # the foot's world velocity is the body's plus J_leg·θ̇ (the body never turns)
            v[cols] = np.linalg.solve(jac[leg][:, cols], paths.velocity[k, i] / period)
        pin.computeJointJacobiansTimeVariation(m, d, q, v)
        a = np.zeros(m.nv)
        for i, leg in enumerate(model.leg_names):
            cols = model.leg_v_indices(leg)
            dj = pin.getFrameJacobianTimeVariation(
                m, d, model.foot_frame_id(leg), pin.LOCAL_WORLD_ALIGNED
            )[:3]
            rhs = paths.acceleration[k, i] / period**2 - dj @ v
            a[cols] = np.linalg.solve(jac[leg][:, cols], rhs)
        tau = pin.rnea(m, d, q, v, a)
        standing = [leg for i, leg in enumerate(model.leg_names) if walker.phases.stance[k, i]]
        stacked = np.vstack([jac[leg] for leg in standing])  # (3n, nv)
        forces = np.linalg.lstsq(stacked[:, :6].T, tau[:6], rcond=None)[0]
        tau = tau - stacked.T @ forces
        torques[k] = [tau[model.leg_v_indices(leg)] for leg in model.leg_names]
    return torques


def bench_gait(l3_points: int, repeats: int) -> list[Row]:
    """One design's period (≤ 10 ms), with its limits, and the sweep with gait columns (≤ 2×)."""
    design = HexapodDesign()
    model = HexapodModel(design)
    gait = Gait()

    def hexaleg_period():
        return analyze_gait(design, gait, model=model, limits=False).joint_torques

    d = check_agree("gait / per sample", hexaleg_period(), per_sample_period(model, gait), 1e-9)
    t_fast, t_slow = median_times(
        [hexaleg_period, lambda: per_sample_period(model, gait)], repeats, min_time=0.0
    )
    t_limits = median_time(lambda: analyze_gait(design, gait, model=model), repeats)
    t_columns = median_time(lambda: design_walking_row(design, model), repeats)
    name = f"gait period, one design ({gait.samples} samples, six legs)"
    rows = [
        Row(name, "hexaleg analyze_gait(limits=False)", t_fast, None, None, "≤ 10 ms"),
        Row(name, "per sample, Pinocchio Jacobians", t_slow, t_slow / t_fast, d),
        Row(name, "hexaleg analyze_gait (+ max stride, max speed)", t_limits, None, None),
        Row(
            name,
            "hexaleg design_walking_row (+ max speed)",
            t_columns,
            None,
            None,
            note="what a study row's walking columns cost",
        ),
    ]
    return rows + bench_walking_columns(l3_points, repeats)


def bench_walking_columns(l3_points: int, repeats: int) -> list[Row]:
    """The Fig 15 sweep with and without the walking columns (≤ 2×): its ratio in one run.

    Timed round-robin on one 2-process pool (what a user runs), and in one process (no
    pool: the ratio of the work alone, steadier on a shared machine).
    """
    keys = (tuple(L1_RATIOS), tuple(l3_ratio_grid(l3_points)))
    with_gait, without = StudySpec(*keys), StudySpec(*keys, gait=False)
    here = median_times(
        [lambda: sweep_in_process(with_gait), lambda: sweep_in_process(without)],
        max(3, repeats // 2),
        min_time=0.0,
    )
    with ProcessPoolExecutor(2) as pool:
        pool.submit(int).result()

        def sweep(spec: StudySpec):
            with tempfile.TemporaryDirectory() as out:
                return run_study(spec, out, executor=pool, progress=False)

        table = sweep(with_gait)
        t_with, t_without = median_times(
            [lambda: sweep(with_gait), lambda: sweep(without)], max(3, repeats // 2), min_time=0.0
        )
    name = f"Fig 15 sweep, {len(with_gait.keys())} designs"
    feasible = int(table["gait_feasible"].sum())
    note = f"ratio here: with / without; {feasible} designs walk the default gait"
    return [
        Row(f"{name}, 2 processes", "hexaleg run_study (statics), no walking columns",
            t_without, None, None),
        Row(f"{name}, 2 processes", "hexaleg run_study (statics + walking columns)", t_with,
            t_with / t_without, None, "≤ 2× without", note=note),
        Row(f"{name}, 1 process", "sweep_in_process (statics), no walking columns", here[1],
            None, None),
        Row(f"{name}, 1 process", "sweep_in_process (statics + walking columns)", here[0],
            here[0] / here[1], None, "≤ 2× without", note="ratio here: with / without"),
    ]  # fmt: skip
