"""Manipulability: indices, Table 6, w_A kernel against a Pinocchio loop, the Fig 11 map;
the command's optimum for each kind of robot against Pinocchio on its raw URDF."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest
from robots import KINDS, KRABY, robot_argv, robot_json
from scipy import optimize

from hexaleg import MANIPULABILITY_LIMITS, HexapodDesign, LegModel, manipulability
from hexaleg.paper import TABLE6, TABLE6_PRINTED_DIGITS
from hexaleg.robot.imported import import_robot
from hexaleg.robot.urdf import render_hexapod
from hexaleg.swing.manipulability import (
    analyze_manipulability,
    average_manipulability,
    average_manipulability_map,
    indices_from_jacobian,
    joint_grid,
    optimum_pose,
    pose_indices,
    rectangular_and_improved,
)


def test_indices_from_pinocchio_match_the_closed_form(leg_model, default_design):
    rng = np.random.default_rng(31)
    for theta in rng.uniform(-2.5, 0.5, size=(30, 3)):
        indices = pose_indices(leg_model, theta)
        assert indices.w == pytest.approx(
            float(manipulability(default_design.lengths, theta[1], theta[2])), abs=1e-13
        )
        jac = leg_model.foot_jacobian(theta)
        assert indices.condition_number == pytest.approx(np.linalg.cond(jac), rel=1e-9)
        assert indices.min_singular_value == pytest.approx(
            np.sqrt(np.linalg.eigvalsh(jac.T @ jac).min()), rel=1e-6, abs=1e-9
        )


def test_singular_pose_has_infinite_condition_number(leg_model):
    indices = pose_indices(leg_model, [0.0, 0.3, 0.0])  # knee straight: θ3 = 0
    assert indices.w == pytest.approx(0.0, abs=1e-15)
    assert indices.condition_number > 1e12 or math.isinf(indices.condition_number)
    assert indices_from_jacobian(np.zeros((3, 3))).condition_number == math.inf


def _exact_optimum(l1, l2, l3):
    """Independent oracle for Table 6: for fixed θ3, the best hip aligns the 2R chain with the
    coxa (θ2 = -atan2(l3 sin θ3, l2 + l3 cos θ3)), leaving a 1-D problem in θ3 solved to 1e-12."""

    def w_of_knee(t3):
        return (
            l2
            * l3
            * abs(math.sin(t3))
            * (l1 + math.hypot(l2 + l3 * math.cos(t3), l3 * math.sin(t3)))
        )

    res = optimize.minimize_scalar(
        lambda t3: -w_of_knee(t3),
        bounds=(-3 * math.pi / 4, -math.pi / 12),
        method="bounded",
        options={"xatol": 1e-12},
    )
    t3 = res.x
    t2 = -math.atan2(l3 * math.sin(t3), l2 + l3 * math.cos(t3))
    return t2, t3, w_of_knee(t3)


@pytest.mark.parametrize("row", TABLE6, ids=lambda r: f"l1={r.l1_mm:g}mm")
def test_table6_optimum_pose(row):
    lengths = (row.l1_mm / 1000, row.l2_mm / 1000, row.l3_mm / 1000)
    pose = optimum_pose(lengths, MANIPULABILITY_LIMITS)
    assert pose.converged
    # angles to 0.001° of the paper (printed to 0.0001°)
    assert math.degrees(pose.theta2) == pytest.approx(row.theta2_deg, abs=1e-3)
    assert math.degrees(pose.theta3) == pytest.approx(row.theta3_deg, abs=1e-3)
    # w to 0.01 % of the exact optimum
    t2, t3, w_exact = _exact_optimum(*lengths)
    assert pose.w == pytest.approx(w_exact, rel=1e-4)
    assert math.degrees(pose.theta2) == pytest.approx(math.degrees(t2), abs=1e-4)
    assert math.degrees(pose.theta3) == pytest.approx(math.degrees(t3), abs=1e-4)


@pytest.mark.parametrize("row", TABLE6, ids=lambda r: f"l1={r.l1_mm:g}mm")
def test_table6_printed_w_against_eq25_at_the_papers_own_angles(row):
    """The paper's printed w agrees with eq 25 at its own angles except row 1 (digits swapped)."""
    lengths_mm = (row.l1_mm, row.l2_mm, row.l3_mm)
    w_eq25 = float(
        manipulability(lengths_mm, math.radians(row.theta2_deg), math.radians(row.theta3_deg))
    )
    printed_precision = 10 ** (math.floor(math.log10(row.w_mm3)) - TABLE6_PRINTED_DIGITS + 1)
    agrees = abs(w_eq25 - row.w_mm3) <= printed_precision / 2 + 1e-6 * row.w_mm3
    if row.l1_mm == 50:
        assert not agrees  # printed 1.7576e8; eq 25 gives 1.75665e8 → 1.7567e8
        assert f"{w_eq25:.4e}" == "1.7567e+08"
    else:
        assert agrees


def test_optimum_is_not_beaten_by_any_grid_point():
    rng = np.random.default_rng(41)
    for lengths in rng.uniform(0.05, 0.6, size=(10, 3)):
        pose = optimum_pose(tuple(lengths), MANIPULABILITY_LIMITS)
        hip, knee = joint_grid(MANIPULABILITY_LIMITS, step=math.radians(0.25))
        grid = manipulability(tuple(lengths), hip[:, None], knee[None, :])
        assert pose.w >= grid.max() * (1 - 1e-12)
        assert MANIPULABILITY_LIMITS.theta2[0] <= pose.theta2 <= MANIPULABILITY_LIMITS.theta2[1]
        assert MANIPULABILITY_LIMITS.theta3[0] <= pose.theta3 <= MANIPULABILITY_LIMITS.theta3[1]


def test_grid_is_121_by_121_one_degree_steps():
    hip, knee = joint_grid(MANIPULABILITY_LIMITS)
    assert hip.shape == knee.shape == (121,)
    np.testing.assert_allclose(np.degrees(np.diff(hip)), 1.0)
    assert math.degrees(hip[0]) == pytest.approx(-60) and math.degrees(knee[-1]) == pytest.approx(
        -15
    )


@pytest.mark.parametrize("coupled", [False, True])
def test_average_kernel_equals_a_pinocchio_loop_on_a_coarse_grid(coupled):
    design = HexapodDesign.from_ratios(0.1, 0.45)
    leg = LegModel(design)
    rect, improved = rectangular_and_improved(design.manipulability_limits)
    domain = improved if coupled else rect
    step = math.radians(5.0)
    hip, knee = joint_grid(domain, step)
    values = [
        abs(np.linalg.det(leg.foot_jacobian([0.0, t2, t3])))
        for t2 in hip
        for t3 in knee
        if domain.contains([0.0, t2, t3], tol=1e-12)
    ]
    kernel = average_manipulability(design.lengths, domain, step)
    assert float(kernel) == pytest.approx(np.mean(values), rel=1e-12)


def test_average_kernel_vectorizes_over_designs():
    lengths = np.array([[0.05, 0.475, 0.475], [0.2, 0.4, 0.4], [0.1, 0.2, 0.7]])
    many = average_manipulability(lengths, MANIPULABILITY_LIMITS)
    one_by_one = [float(average_manipulability(row, MANIPULABILITY_LIMITS)) for row in lengths]
    np.testing.assert_allclose(many, one_by_one, rtol=1e-14)


def test_average_map_peaks_and_trends():
    l3 = np.linspace(0.1, 0.75, 40)
    result = average_manipulability_map([0.05, 0.10, 0.15, 0.20], l3)
    # w_A falls as the coxa ratio grows (paper §5.4), at every tibia ratio
    assert np.all(np.diff(result.rectangular, axis=0) < 0)
    # refined peaks are true maxima: no grid point beats them
    for i, r1 in enumerate(result.l1_ratios):
        for peak, domain_values, domain in (
            (
                result.peak_rectangular[i],
                result.rectangular[i],
                rectangular_and_improved(MANIPULABILITY_LIMITS)[0],
            ),
            (
                result.peak_improved[i],
                result.improved[i],
                rectangular_and_improved(MANIPULABILITY_LIMITS)[1],
            ),
        ):
            at_peak = float(average_manipulability((r1, 1 - r1 - peak, peak), domain))
            assert at_peak >= np.nanmax(domain_values) * (1 - 1e-12)
    # where the paper's "≈ 0.45" holds: not on the rectangle, roughly on the improved domain
    assert np.all(result.peak_rectangular < 0.36)
    assert np.all((result.peak_improved > 0.36) & (result.peak_improved < 0.45))


def test_analysis_summary_has_the_documented_keys(default_design, leg_model):
    summary = analyze_manipulability(default_design, leg_model).to_dict()
    assert set(summary["optimum"]) >= {"theta2", "theta3", "w"}
    assert set(summary["average"]) == {"rectangular", "improved"}
    assert summary["average"]["improved"] > summary["average"]["rectangular"]


def test_manipulability_surface_is_the_closed_form_on_the_one_degree_grid(default_design):
    from hexaleg.swing.manipulability import manipulability_surface

    l1, l2, l3 = default_design.lengths
    surface = manipulability_surface(default_design.lengths, default_design.manipulability_limits)
    assert surface.w.shape == (121, 121)  # eq 26: 120° of hip and of knee, one value a degree
    t2, t3 = np.meshgrid(surface.theta2, surface.theta3, indexing="ij")
    # |det J| of the 3-DOF leg, by hand: l2·l3·|sin θ3|·|l1 + l2 cos θ2 + l3 cos(θ2 + θ3)|
    expected = l2 * l3 * np.abs(np.sin(t3)) * np.abs(l1 + l2 * np.cos(t2) + l3 * np.cos(t2 + t3))
    np.testing.assert_allclose(surface.w, expected, rtol=1e-12, atol=1e-15)


def _raw_legs(kind: str, shown: dict) -> tuple[str, list[tuple[list[str], np.ndarray, str, dict]]]:
    """The raw URDF's text and, per leg, its joints, their values at the leg's optimum, its
    foot frame and that optimum, as ``manipulability --json`` gives them (one optimum for
    the template's equal legs, whose joints are θ, named by its Xacro)."""
    if kind == "template":
        optimum = shown["optimum"]
        theta = np.array([0.0, optimum["theta2"], optimum["theta3"]])
        names = [mount["name"] for mount in shown["design"]["mounts"]]
        legs = [([f"{n}_{j}_joint" for j in ("root", "hip", "knee")], theta, f"{n}_foot", optimum)
                for n in names]  # fmt: skip
        return render_hexapod(HexapodDesign()), legs
    robot = import_robot(KRABY)
    legs = []
    for leg in robot.legs:
        optimum = shown["legs"][leg.name]["optimum"]
        theta = np.array([0.0, optimum["theta2"], optimum["theta3"]])
        foot = leg.reading.foot.source.removeprefix("link ")
        legs.append((list(leg.joint_names), leg.reading.joint_map.to_file(theta), foot, optimum))
    return robot.text, legs


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_the_commands_optimum_indices_equal_pinocchio_on_the_raw_urdf(capsys, kind):
    # the oracle: the singular values of the foot's translational Jacobian in Pinocchio on
    # the raw URDF, at the optimum's angles put on the file's own joints
    shown = robot_json(capsys, ["manipulability", *robot_argv(kind), "--json"])
    text, legs = _raw_legs(kind, shown)
    model = pin.buildModelFromXML(text)
    data = model.createData()
    assert len(legs) == 6
    for joints, values, foot, optimum in legs:
        q = pin.neutral(model)
        ids = [model.getJointId(name) for name in joints]
        for i, value in zip(ids, values, strict=True):
            q[model.joints[i].idx_q] = value
        frame = model.getFrameId(foot)
        jac = pin.computeFrameJacobian(model, data, q, frame, pin.LOCAL_WORLD_ALIGNED)[:3]
        singular = np.linalg.svd(jac[:, [model.joints[i].idx_v for i in ids]], compute_uv=False)
        assert optimum["w"] == pytest.approx(np.prod(singular), rel=1e-9)
        assert optimum["min_singular_value"] == pytest.approx(singular[-1], rel=1e-9)
