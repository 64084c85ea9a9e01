"""Workloads on one leg's kinematics: forward kinematics, Monte Carlo workspace, IK."""

from __future__ import annotations

import tempfile
import warnings

import numpy as np
import pinocchio as pin
from alternatives import optional, rtb_leg
from harness import Row, check_agree, median_time, median_times, missing

from hexaleg import HexapodDesign, LegModel, foot_position, inverse_kinematics, render_leg
from hexaleg.swing.workspace import monte_carlo_workspace


def bench_forward_kinematics(samples: int, repeats: int) -> list[Row]:
    """FK of random leg configurations: hexaleg vs NumPy, Pinocchio loop, robotics-toolbox."""
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
    robot = rtb_leg(design.lengths)
    if robot is None:
        rows.append(missing(name, "robotics-toolbox ETS.fkine"))
    else:
        ets = robot.ets()

        def rtb_run():
            return np.asarray(ets.fkine(theta).t)

        d = check_agree("fk / robotics-toolbox", reference, rtb_run(), 1e-12)
        t = median_time(rtb_run, repeats)
        rows.append(Row(name, "robotics-toolbox ETS.fkine (compiled)", t, t / t_hex, d))
    return rows


def bench_monte_carlo(samples: int, repeats: int) -> list[Row]:
    """Monte Carlo workspace: hexaleg vs bare NumPy eq 7 vs a Pinocchio loop."""
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


def bench_inverse_kinematics(targets: int, repeats: int) -> list[Row]:
    """IK of reachable foot targets: hexaleg closed form vs robotics-toolbox and ikpy."""
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

    robot = rtb_leg(design.lengths)
    if robot is None:
        rows.append(missing(name, "robotics-toolbox ik_LM"))
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
    ikpy_chain = optional("ikpy.chain")
    if ikpy_chain is None:
        rows.append(missing(name, "ikpy"))
    else:
        with tempfile.NamedTemporaryFile("w", suffix=".urdf", delete=False) as handle:
            handle.write(render_leg(design))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            chain = ikpy_chain.Chain.from_urdf_file(
                handle.name,
                base_elements=["base_link"],
                active_links_mask=[False, True, True, True, False],
            )
        count = min(targets, 200)

        def ikpy_run():
            out = np.empty((count, 3))
            for i in range(count):
                start = np.r_[0.0, truth[i] + 0.1, 0.0]
                out[i] = chain.inverse_kinematics(goal[i], initial_position=start)[1:4]
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
