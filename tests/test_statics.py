"""Statics against independent oracles: least squares, moments by hand, a hand-built polygon;
each kind of robot weighed by Pinocchio on its raw URDF."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest
from robots import KINDS, KRABY, robot_argv, robot_json, robot_of

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.robot.imported import import_robot
from hexaleg.robot.urdf import render_hexapod
from hexaleg.stance import StanceGeometry, stance_configuration
from hexaleg.statics import (
    Payload,
    Statics,
    payload_capacity,
    slope_gravity,
    slope_limits,
    stability_margin,
)

G = np.array([0.0, 0.0, -9.81])


def _poses(model, legs, count, seed):
    """Random feasible stance configurations around the nominal stance."""
    geometry = StanceGeometry.from_model(model, legs)
    rng = np.random.default_rng(seed)
    found = []
    while len(found) < count:
        x, y, z, roll, pitch, yaw = rng.uniform(-1, 1, 6) * [0.08, 0.08, 0.05, 0.1, 0.1, 0.15]
        body = pin.SE3(
            pin.rpy.rpyToMatrix(roll, pitch, yaw), np.array([x, y, geometry.nominal_height + z])
        )
        q, solution = stance_configuration(model, geometry, body)
        if solution.reachable.all():
            found.append(q)
    return found


@pytest.fixture(scope="module", params=KINDS)
def model(request):
    """Each kind of robot's model: the template's at the default design, a robot file's."""
    return robot_of(request.param).model


@pytest.fixture(scope="module")
def template_model():
    """The template's model at the default design (its rods' weights are known by hand)."""
    return HexapodModel(HexapodDesign())


@pytest.mark.parametrize("legs", [("lf", "lm", "lr", "rf", "rm", "rr"), ("lf", "rm", "lr")])
def test_min_norm_forces_equal_a_least_squares_solve(model, legs):
    statics = Statics(model, legs, Payload(15.0, (0.1, -0.05, 0.05)))
    for q in _poses(model, legs, 5, seed=1):
        state = statics.state(q)
        # the test's own equilibrium: total mass and centre of mass from Pinocchio's
        # per-body inertias, the payload added by hand
        data = model.model.createData()
        pin.forwardKinematics(model.model, data, q)
        masses = [inertia.mass for inertia in model.model.inertias[1:]]
        centres = [
            data.oMi[i].act(model.model.inertias[i].lever) for i in range(1, model.model.njoints)
        ]
        body = data.oMi[1]
        payload_point = body.act(np.array([0.1, -0.05, 0.05]))
        mass = sum(masses) + 15.0
        com = (
            sum(m * c for m, c in zip(masses, centres, strict=True)) + 15.0 * payload_point
        ) / mass
        pin.framesForwardKinematics(model.model, data, q)
        feet = [data.oMf[model.foot_frame_id(leg)].translation for leg in legs]
        rows = np.zeros((6, 3 * len(legs)))
        for i, foot in enumerate(feet):
            rows[:3, 3 * i : 3 * i + 3] = np.eye(3)
            r = foot - com
            rows[3:, 3 * i : 3 * i + 3] = [[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]]
        rhs = np.concatenate([-mass * G, np.zeros(3)])
        expected = np.linalg.pinv(rows) @ rhs
        np.testing.assert_allclose(state.foot_forces.ravel(), expected, atol=1e-9)
        assert state.mass == pytest.approx(mass, rel=1e-12)
        np.testing.assert_allclose(state.com, com, atol=1e-12)


def test_torques_equal_moments_of_foot_forces_and_rod_weights_by_hand(template_model):
    model = template_model
    """τ_joint = −axis·[(p_foot − o) × f + Σ_rods beyond the joint (c_k − o) × m_k g]."""
    design = model.design
    legs = model.leg_names
    statics = Statics(model, legs)
    for q in _poses(model, legs, 4, seed=2):
        state = statics.state(q)
        data = model.model.createData()
        pin.framesForwardKinematics(model.model, data, q)
        pin.computeJointJacobians(model.model, data, q)
        for n, leg in enumerate(legs):
            names = [f"{leg}_{j}_joint" for j in ("root", "hip", "knee")]
            joints = [model.model.getJointId(name) for name in names]
            origins = [data.oMi[j].translation for j in joints]
            axes = [  # each joint's axis in the world: the angular part of its motion
                pin.getJointJacobian(model.model, data, j, pin.WORLD)[3:, model.model.idx_vs[j]]
                for j in joints
            ]
            foot = data.oMf[model.foot_frame_id(leg)].translation
            # each rod: from its joint to the next joint (or the foot), mass density × length
            ends = [*origins[1:], foot]
            lengths = (design.l1, design.l2, design.l3)
            rods = [
                (design.link_linear_density * length, 0.5 * (start + end))
                for length, start, end in zip(lengths, origins, ends, strict=True)
            ]
            foot_mass = 1e-3  # hexaleg's foot link
            for k in range(3):
                moment = np.cross(foot - origins[k], state.foot_forces[n])
                for mass, centre in rods[k:]:
                    moment += np.cross(centre - origins[k], mass * G)
                moment += np.cross(foot - origins[k], foot_mass * G)
                assert state.joint_torques[n, k] == pytest.approx(-axes[k] @ moment, abs=1e-9)


@pytest.mark.parametrize("distribution", ["min-norm", "min-torque"])
def test_free_flyer_rows_vanish(model, distribution):
    # 30 kg at (0.2, 0.1, 0.05) m on the template's 84 kg, 1 m body; as much on a small robot
    size = model.design.body_length
    payload = Payload(model.total_mass * 30.0 / 84.006, (0.2 * size, 0.1 * size, 0.05 * size))
    statics = Statics(model, model.leg_names, payload)
    if distribution == "min-torque" and model.own_legs is not None:
        pytest.skip("the QP's tolerance below is absolute, set for the template's 824 N weight")
    tolerance = 1e-9 if distribution == "min-norm" else 1e-6  # the QP's own tolerance
    for q in _poses(model, model.leg_names, 5, seed=3):
        assert statics.state(q, distribution).free_flyer_residual <= tolerance


def test_min_torque_never_has_a_higher_peak_ratio_than_min_norm(model):
    statics = Statics(model, model.leg_names, friction=0.8)
    rated = np.array(model.design.rated_torques)
    for q in _poses(model, model.leg_names, 8, seed=4):
        norm = statics.state(q, "min-norm")
        torque = statics.state(q, "min-torque")
        assert (
            np.sum(torque.torque_ratios(rated) ** 2)
            <= np.sum(norm.torque_ratios(rated) ** 2) + 1e-9
        )
        assert torque.torque_ratios(rated).max() <= norm.torque_ratios(rated).max() + 1e-9
        forces = torque.foot_forces
        assert np.all(forces[:, 2] >= -1e-7)
        assert np.all(np.abs(forces[:, :2]) <= 0.8 * forces[:, 2:3] + 1e-6)  # in the cone


def test_stability_margin_on_a_hand_built_square():
    square = np.array([[0, 0], [2, 0], [2, 2], [0, 2], [1, 1]])  # a foot inside is ignored
    assert stability_margin(square, np.array([1.0, 1.0])) == pytest.approx(1.0)
    assert stability_margin(square, np.array([0.5, 1.0])) == pytest.approx(0.5)
    assert stability_margin(square, np.array([3.0, 1.0])) == pytest.approx(-1.0)
    assert stability_margin(square, np.array([3.0, 3.0])) == pytest.approx(-math.sqrt(2))


def test_slope_limits_tip_or_slide_as_geometry_says():
    feet = np.array([[1.0, 0.5], [-1.0, 0.5], [-1.0, -0.5], [1.0, -0.5]])
    com = np.array([0.0, 0.0, 0.5])
    ahead, left, behind, right = slope_limits(feet, com, friction=10.0)
    assert ahead.max_slope == pytest.approx(math.atan2(1.0, 0.5)) and ahead.limited_by.kind == "tip"
    assert left.max_slope == pytest.approx(math.atan2(0.5, 0.5)) and left.limited_by.kind == "tip"
    assert (behind.max_slope, right.max_slope) == pytest.approx((ahead.max_slope, left.max_slope))
    slide = slope_limits(feet, com, friction=0.3)[0]
    assert slide.max_slope == pytest.approx(math.atan(0.3)) and slide.limited_by.kind == "slide"
    gravity = slope_gravity(0.3, 0.0)
    assert np.linalg.norm(gravity) == pytest.approx(9.81) and gravity[0] < 0


def test_exit_distances_reach_a_square_boundary_as_trigonometry_says():
    from hexaleg.statics import SupportPolygon

    square = SupportPolygon.of_feet([[-1, -1], [1, -1], [1, 1], [-1, 1]])
    angles = np.linspace(-math.pi, math.pi, 37)
    directions = np.column_stack([np.cos(angles), np.sin(angles)])
    # from the centre, the side x = ±1 or y = ±1 met first: 1 / max(|cos|, |sin|)
    expected = 1 / np.maximum(np.abs(np.cos(angles)), np.abs(np.sin(angles)))
    got = square.exit_distances(np.zeros(2), directions)
    assert got == pytest.approx(expected, rel=1e-12)
    # off centre, toward +x: 1 − 0.25 away
    assert square.exit_distance(np.array([0.25, 0.5]), np.array([1.0, 0.0])) == pytest.approx(0.75)


@pytest.mark.parametrize("count", [3, 4, 5, 6])
def test_the_support_polygon_is_qhulls_hull_counter_clockwise(count):
    # oracle: SciPy's qhull on seeded random feet; the edges run vertex to vertex
    from scipy.spatial import ConvexHull

    from hexaleg.statics import SupportPolygon

    rng = np.random.default_rng(count)
    for _ in range(50):
        feet = rng.uniform(-1, 1, (count, 2))
        polygon = SupportPolygon.of_feet(feet)
        expected = ConvexHull(feet).vertices  # counter-clockwise for 2-D input
        start = int(np.flatnonzero(expected == np.flatnonzero(
            (feet == polygon.vertices[0]).all(axis=1))[0])[0])  # fmt: skip
        np.testing.assert_array_equal(polygon.vertices, feet[np.roll(expected, -start)])
        np.testing.assert_allclose(
            polygon.edges, np.roll(polygon.vertices, -1, axis=0) - polygon.vertices
        )
        np.testing.assert_allclose(polygon.lengths, np.linalg.norm(polygon.edges, axis=1))


@pytest.mark.parametrize("distribution", ["min-norm", "min-torque"])
def test_states_of_many_poses_equal_each_pose_alone(model, distribution):
    legs = ("lf", "rm", "lr")
    statics = Statics(model, legs, Payload(12.0, (0.05, 0.02, 0.05)), friction=0.8)
    poses = _poses(model, legs, 5, seed=11)
    together = statics.states(poses, distribution)
    # min-norm is a direct solve; min-torque is ProxQP's iterate, which stops at its own
    # tolerance (1e-9): round-off in its inputs (BLAS kernels follow memory alignment)
    # moves the answer within it, by ~1e-10 of the forces
    relative = 1e-12 if distribution == "min-norm" else 1e-8
    for q, state in zip(poses, together, strict=True):
        alone = statics.state(q, distribution)
        assert state.joint_torques == pytest.approx(alone.joint_torques, rel=relative, abs=1e-9)
        assert state.foot_forces == pytest.approx(alone.foot_forces, rel=relative, abs=1e-9)
        assert state.com == pytest.approx(alone.com, abs=1e-15)
        assert state.stability_margin == pytest.approx(alone.stability_margin, abs=1e-15)


@pytest.mark.parametrize("payload", [Payload(), Payload(12.0, (0.05, 0.02, 0.05))])
def test_centres_of_mass_are_those_of_the_model_with_the_payload_built_in(model, payload):
    # the oracle: Pinocchio's centre of mass of a copy whose body holds the payload's mass
    legs = ("lf", "rm", "lr")
    statics = Statics(model, legs, payload)
    poses = _poses(model, legs, 4, seed=5)
    loaded = pin.Model(model.model)
    if payload.mass > 0:
        body = loaded.frames[model.base_frame]
        point = body.placement.act(np.asarray(payload.point(model), dtype=float))
        loaded.inertias[body.parentJoint] += pin.Inertia(payload.mass, point, np.zeros((3, 3)))
    expected = [pin.centerOfMass(loaded, loaded.createData(), q) for q in poses]
    np.testing.assert_allclose(statics.centres_of_mass(poses), expected, rtol=0, atol=1e-14)
    assert statics.mass == pytest.approx(pin.computeTotalMass(loaded), rel=1e-15)


def test_extreme_configurations_put_the_body_at_each_pose_and_swing_legs_at_rest(model):
    """Against Pinocchio's own rpy module and the extremes' joint angles, leg by leg."""
    from hexaleg.stance import axis_locked_flexibility, free_flexibility
    from hexaleg.stance.configurations import extreme_configurations

    design = model.design
    for result in (
        axis_locked_flexibility(design, "tripod", model),
        free_flexibility(design, "tripod", model),
    ):
        q = extreme_configurations(model, result.extremes)
        for extreme, qk in zip(result.extremes, q, strict=True):
            pose = np.array(extreme.pose)
            body = pin.XYZQUATToSE3(qk[:7])
            assert body.rotation == pytest.approx(pin.rpy.rpyToMatrix(*pose[3:]), abs=1e-14)
            assert body.translation == pytest.approx(
                pose[:3] + np.array([0.0, 0.0, model.nominal_height]), abs=1e-15
            )
            for leg in model.leg_names:  # in the model's joints: a file's q = s·θ + o
                angles = qk[model.leg_q_indices(leg)]
                expected = extreme.joint_angles.get(leg, model.nominal_angles(leg))
                assert angles == pytest.approx(model.joint_values(leg, expected), abs=0)


def test_payload_capacity_grows_with_the_rated_torques():
    capacities = []
    for scale in (0.5, 1.0, 2.0):
        design = HexapodDesign(rated_torques=tuple(scale * t for t in (60.0, 150.0, 120.0)))
        model = HexapodModel(design)
        statics = Statics(model, model.leg_names)
        capacity = payload_capacity(statics, model.nominal_configuration())
        capacities.append(capacity.mass)
        # at the capacity the limiting joint is at its rating
        state = statics.state(model.nominal_configuration(), payload=Payload(capacity.mass))
        assert state.torque_ratios(np.array(design.rated_torques)).max() == pytest.approx(
            1.0, abs=1e-5
        )
        # and the cause names that joint, by the same Cause type as the extremes
        cause = capacity.limited_by
        ratios = state.torque_ratios(np.array(design.rated_torques))
        leg, joint = state.legs.index(cause.leg), ("root", "hip", "knee").index(cause.joint)
        assert cause.kind == "torque" and ratios[leg, joint] == pytest.approx(1.0, abs=1e-5)
    assert capacities[0] < capacities[1] < capacities[2]


def test_with_design_equals_the_model_built_from_the_urdf(template_model):
    model = template_model
    design = HexapodDesign(
        l1=0.12, l2=0.5, l3=0.33, rated_torques=(20.0, 90.0, 70.0), rated_speeds=(1.0, 2.0, 4.0)
    )
    fast, slow = model.with_design(design), HexapodModel(design)
    for a, b in zip(fast.model.jointPlacements, slow.model.jointPlacements, strict=True):
        np.testing.assert_allclose(a.homogeneous, b.homogeneous, atol=1e-15)
    for a, b in zip(fast.model.inertias, slow.model.inertias, strict=True):
        assert a.mass == pytest.approx(b.mass, abs=1e-15)
        np.testing.assert_allclose(a.lever, b.lever, atol=1e-15)
        np.testing.assert_allclose(a.inertia, b.inertia, atol=1e-15)
    for a, b in zip(fast.model.frames, slow.model.frames, strict=True):
        assert a.name == b.name
        np.testing.assert_allclose(a.placement.homogeneous, b.placement.homogeneous, atol=1e-15)
    np.testing.assert_array_equal(fast.model.effortLimit, slow.model.effortLimit)
    np.testing.assert_array_equal(fast.model.velocityLimit, slow.model.velocityLimit)
    from hexaleg.exceptions import ModelError

    with pytest.raises(ModelError):
        model.with_design(HexapodDesign(body_width=0.8))


def test_loads_json_has_every_documented_field(capsys):
    import json

    from hexaleg.cli import main

    argv = ["loads", "--payload", "20", "--payload-at", "0.1", "0", "0.05", "--friction", "0.5"]
    assert main([*argv, "--stance", "tripod", "--distribution", "min-torque", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["design"]["rated_torques"] == [60.0, 150.0, 120.0]
    assert data["payload"] == {"mass": 20.0, "position": [0.1, 0.0, 0.05]}
    assert data["friction"] == 0.5 and data["distribution"] == "min-torque"
    assert data["mass"] == pytest.approx(HexapodDesign().total_mass + 20.0)
    assert len(data["com"]) == 3
    assert set(data["nominal"]["foot_forces"]) == {"lf", "rm", "lr"}
    assert set(data["nominal"]["joint_torques"]["lf"]) == {"root", "hip", "knee"}
    assert "stability_margin" in data["nominal"]
    assert len(data["extremes"]) == 12
    assert {"axis", "sign", "value", "joint_torques", "peak_torque", "stability_margin"} <= set(
        data["extremes"][0]
    )
    assert [s["heading"] for s in data["slopes"]] == pytest.approx(
        [0, math.pi / 2, math.pi, -math.pi / 2]
    )
    assert {s["limited_by"]["kind"] for s in data["slopes"]} <= {"tip", "slide"}
    assert set(data["payload_capacity"]) == {"mass", "limited_by", "tips_over"}
    total = sum(np.array(f) for f in data["nominal"]["foot_forces"].values())
    np.testing.assert_allclose(total, [0, 0, data["mass"] * 9.81], atol=1e-5)


def test_loads_bad_input_is_one_line(capsys, tmp_path):
    from conftest import run_cli

    assert run_cli(["loads", "--payload", "-5"]) == 2
    assert run_cli(["loads", "--friction", "0"]) == 2
    assert run_cli(["loads", "--distribution", "cheapest"]) == 2
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 3 and "payload" in lines[0] and "friction" in lines[1]


def test_study_rows_carry_the_statics(tmp_path):
    from concurrent.futures import ThreadPoolExecutor

    from hexaleg.statics.loads import analyze_loads
    from hexaleg.study import StudySpec, run_study

    table = run_study(StudySpec((0.1,), (0.3, 0.45)), tmp_path, executor=ThreadPoolExecutor(1))
    for column in (
        "peak_hip_torque_nominal",
        "peak_knee_torque",
        "stability_margin",
        "worst_max_slope",
        "payload_capacity",
        "payload_limited_by",
    ):
        assert column in table
    row = table.iloc[1]
    single = analyze_loads(HexapodDesign.from_ratios(0.1, 0.45))
    assert row["payload_capacity"] == pytest.approx(single.capacity.mass, rel=1e-9)
    assert row["peak_hip_torque"] == pytest.approx(single.peak_torques["hip"], rel=1e-9)


@pytest.mark.parametrize("com_xy", [(3.0, 0.0), (1.0, 0.5), (-2.0, 4.0)])
def test_slope_limits_are_zero_when_the_centre_of_mass_is_outside_the_support(com_xy):
    feet = np.array([[1.0, 0.5], [-1.0, 0.5], [-1.0, -0.5], [1.0, -0.5]])
    for limit in slope_limits(feet, np.array([*com_xy, 0.5]), friction=0.6):
        assert limit.max_slope == 0.0 and limit.limited_by.kind == "tip"


def _tipping_loads(capsys, *extra):
    from hexaleg.cli import main

    assert main(["loads", "--payload", "30", "--payload-at", "10", "0", "0", *extra]) == 0
    return capsys.readouterr().out


def test_loads_says_a_payload_that_tips_the_robot_over_does(capsys):
    import json

    # by hand: 30 kg at x = 10 m puts the centre of mass near x = 300 / (M + 30) > 2 m,
    # beyond every foot of the default design (the feet lie within 1.3 m of the centre)
    data = json.loads(_tipping_loads(capsys, "--json"))
    assert data["com"][0] > 2.0 and data["nominal"]["stability_margin"] < 0
    assert [s["max_slope"] for s in data["slopes"]] == [0.0] * 4
    assert {s["limited_by"]["kind"] for s in data["slopes"]} == {"tip"}
    assert data["payload_capacity"]["tips_over"] is True
    assert data["payload_capacity"]["mass"] < 30.0
    text = _tipping_loads(capsys).lower()
    assert text.count("tips over on level ground") >= 5  # the margin and each heading
    assert "30 kg payload tips the robot over" in text
    assert "limited by slide" not in text


def test_loads_says_a_payload_inside_the_support_does_not_tip(capsys):
    import json

    from hexaleg.cli import main

    assert main(["loads", "--payload", "30", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["payload_capacity"]["tips_over"] is False
    assert all(s["max_slope"] > 0 for s in data["slopes"])


@pytest.mark.parametrize("position", [["1000", "0", "0"], ["0", "-100.5", "0"], ["0", "0", "nan"]])
def test_payload_at_out_of_range_is_one_line_naming_the_option(capsys, position):
    from conftest import run_cli

    assert run_cli(["loads", "--payload", "30", "--payload-at", *position]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--payload-at" in err
    assert "[-100, 100] [m]" in err or "finite" in err


def test_payload_at_help_gives_its_range(capsys):
    from conftest import run_cli

    assert run_cli(["loads", "--help"]) == 0
    help_text = " ".join(capsys.readouterr().out.split())
    assert "each coordinate in [-100, 100]" in help_text


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_loads_table_names_the_robot_its_torques_and_capacity(capsys, kind):
    from hexaleg.cli import main

    assert main(["loads", *robot_argv(kind)]) == 0
    out = capsys.readouterr().out
    title = out.splitlines()[0]
    assert title.startswith("Statics") and ("kraby" in title) == (kind == "kraby")
    assert "payload capacity" in out and "peak |τ| hip: nominal / extremes" in out


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_loads_weighs_the_robot_at_a_longer_tibia(capsys, kind):
    """The oracle: Pinocchio's total of the raw URDF at its own lengths plus each tibia's
    mass stretched with its length (the template's rods weigh by length, a file's tibia
    is stretched so), the tibias' masses read from the raw URDF's links or the file."""
    if kind == "template":
        design = HexapodDesign()
        text, tibia, longer = render_hexapod(design), design.l3, 0.45
        links = ET.fromstring(text).iter("link")
        tibias = [float(link.find("inertial/mass").get("value"))
                  for link in links if link.get("name").endswith("_tibia")]  # fmt: skip
        added = sum((longer / tibia - 1) * mass for mass in tibias)
    else:
        original = import_robot(KRABY)
        text, longer = original.text, 0.1
        tibias = [leg.masses[2].mass for leg in original.legs]
        added = sum(
            (longer / leg.reading.geometry.tibia - 1) * leg.masses[2].mass for leg in original.legs
        )
    assert len(tibias) == 6 and all(mass > 0 for mass in tibias)
    loads = robot_json(capsys, ["loads", *robot_argv(kind), "--l3", str(longer), "--json"])
    raw = pin.computeTotalMass(pin.buildModelFromXML(text, pin.JointModelFreeFlyer()))
    assert loads["mass"] == pytest.approx(raw + added, rel=1e-12)
