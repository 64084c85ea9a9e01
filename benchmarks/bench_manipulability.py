"""Workloads on manipulability: w on a grid, w_A over the Fig 11 designs, the optimum pose."""

from __future__ import annotations

import math

import numpy as np
from alternatives import rtb_leg
from harness import Row, check_agree, median_time, missing
from scipy import optimize

from hexaleg import MANIPULABILITY_LIMITS, HexapodDesign, LegModel, manipulability
from hexaleg.design import l3_ratio_grid
from hexaleg.paper import L1_RATIOS
from hexaleg.swing.manipulability import average_manipulability, joint_grid, optimum_pose


def bench_manipulability_grid(l3_points: int, repeats: int) -> list[Row]:
    """W on the 121 × 121 grid of one design, and w_A of the 4 × N sweep, vs robotics-toolbox."""
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
    robot = rtb_leg(design.lengths)
    sweep = bench_average_manipulability(l3_points, repeats)
    if robot is None:
        return [*rows, missing(name, "robotics-toolbox manipulability"), *sweep]
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


def bench_average_manipulability(l3_points: int, repeats: int) -> list[Row]:
    """w_A over the Fig 11 design grid: vectorized kernel vs a per-configuration Pinocchio loop."""
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


def bench_optimum_pose(repeats: int) -> list[Row]:
    """Table 6's first row: hexaleg's optimum vs a single scipy run on the plain closed form."""
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
