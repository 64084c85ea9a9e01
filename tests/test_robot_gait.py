"""``gait --urdf FILE``: an imported robot walking, against Pinocchio on the raw file.

Oracles: Pinocchio's inverse dynamics (RNEA) on the file as written, at the configuration,
velocity and acceleration the CSV gives mapped onto the file's joints by the signs and
offsets ``design show`` reads (q = s·θ + o), with the CSV's foot forces applied at the
file's own foot points: its free-flyer rows must vanish (the forces carry the robot) and
its leg rows must be the reported torques about the file's joints, while every standing
foot's velocity and acceleration there (Pinocchio's, of the file) vanish; Pinocchio's forward
kinematics of the raw file at the solved joint angles, which must put every foot on the
planned path, standing feet fixed on the ground; and the template's own URDF imported
back, which must walk as the design does to 1e-9.
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pinocchio as pin
import pytest
from conftest import run_cli
from robots import KRABY, robot_json, robot_under_test

from hexaleg import HexapodDesign
from hexaleg.exceptions import RobotImportWarning
from hexaleg.gait.analysis import analyze_gait
from hexaleg.gait.spec import Gait
from hexaleg.limits import LEG_JOINTS, STANCE_LIMITS
from hexaleg.robot.feet import FootSearch
from hexaleg.robot.imported import import_robot, robot_from_text
from hexaleg.robot.imported_model import ImportedHexapodModel
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.urdf import render_hexapod

G = 9.81
SMALL = ["--stride", "0.03", "--step-height", "0.02", "--period", "0.8", "--samples", "60"]
"""A gait every robot here walks: short strides, a low step, quick enough for inertia."""


class _RawFile:
    """The raw file in Pinocchio on a free flyer, each foot a point on its last link."""

    def __init__(self, path, offset, shown):
        self.robot = import_robot(path, foot=FootSearch(offset=offset))
        self.model = pin.buildModelFromXML(self.robot.text, pin.JointModelFreeFlyer())
        self.model.gravity.linear = np.array([0.0, 0.0, -G])
        self.legs = {leg["name"]: leg for leg in shown["design"]["legs"]}
        self.feet = {}  # a frame at each foot point, on its knee joint
        for leg in self.robot.legs:
            knee = self.model.getJointId(leg.joint_names[2])
            link = self.model.frames[self.model.getFrameId(leg.chain.segments[2][0])].placement
            point = link * pin.SE3(np.eye(3), np.asarray(leg.reading.foot.point))
            frame = pin.Frame(f"test_{leg.name}_foot", knee, point, pin.FrameType.OP_FRAME)
            self.feet[leg.name] = (knee, self.model.addFrame(frame))
        self.data = self.model.createData()

    def joints(self, name):
        return [self.model.joints[self.model.getJointId(j)] for j in self.legs[name]["joints"]]

    def state(self, row, base_velocity):
        """q, v, a of the raw file at a CSV row: θ mapped by the file's signs and offsets."""
        q, v, a = pin.neutral(self.model), np.zeros(self.model.nv), np.zeros(self.model.nv)
        v[:3] = base_velocity  # the root link turns with the body frame: it never rotates
        for name, leg in self.legs.items():
            signs, offsets = np.asarray(leg["joint_signs"]), np.asarray(leg["joint_offsets"])
            for k, (joint, part) in enumerate(zip(self.joints(name), LEG_JOINTS, strict=True)):
                q[joint.idx_q] = signs[k] * row[f"{name}_{part}_q"] + offsets[k]
                v[joint.idx_v] = signs[k] * row[f"{name}_{part}_qd"]
                a[joint.idx_v] = signs[k] * row[f"{name}_{part}_qdd"]
        return q, v, a

    def foot(self, name):
        """Leg ``name``'s knee joint, and its foot point's position, velocity and (classical)
        acceleration, world frame, at the last forward kinematics (q, v, a).
        """
        knee, frame = self.feet[name]
        model, data, world = self.model, self.data, pin.LOCAL_WORLD_ALIGNED
        position = pin.updateFramePlacement(model, data, frame).translation.copy()
        velocity = pin.getFrameVelocity(model, data, frame, world).linear
        acceleration = pin.getFrameClassicalAcceleration(model, data, frame, world).linear
        return knee, position, velocity, acceleration


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize(
    ("path", "extra"),
    [
        (KRABY, []),
        (KRABY, ["--payload", "0.8", "--payload-at", "0.02", "-0.01", "0.03", "--heading", "0.7"]),
        (KRABY, ["--distribution", "min-torque", "--samples", "24"]),
        ("ochs", []),
        ("drawn:3", ["--payload", "0.3"]),
        ("drawn:5", ["--pattern", "wave", "--heading", "-2.0"]),
    ],
)
def test_gait_torques_equal_pinocchio_rnea_on_the_file(capsys, tmp_path, path, extra):
    path, options, offset = robot_under_test(path, tmp_path)
    csv = tmp_path / "gait.csv"
    argv = ["--urdf", path, *options]
    summary = robot_json(capsys, ["gait", *argv, *SMALL, *extra, "--csv", str(csv), "--json"])
    shown = robot_json(capsys, ["design", "show", *argv, "--json"])
    raw = _RawFile(path, offset, shown)
    balance = 1e-5 if "min-torque" in extra else 1e-9  # ProxQP's own tolerance on A f = b
    payload = summary["payload"]
    # the payload's point is in the design's body frame: the mounts' plane above the root
    plane = shown["design"]["legs"][0]["mount"]["z"] - shown["design"]["mounts"][0]["z"]
    at = np.asarray(payload["position"]) + np.array([0.0, 0.0, plane])
    weight = np.array([0.0, 0.0, -payload["mass"] * G])
    table = pd.read_csv(csv)
    gait = summary["gait"]
    velocity = gait["speed"] * np.array([np.cos(gait["heading"]), np.sin(gait["heading"]), 0.0])
    torque_seen, inertia_seen = 0.0, 0.0
    for k in range(0, len(table), 7):
        row = table.iloc[k]
        q, v, a = raw.state(row, velocity)
        pin.forwardKinematics(raw.model, raw.data, q, v, a)
        fext = [pin.Force.Zero() for _ in range(raw.model.njoints)]
        fext[1] += raw.data.oMi[1].actInv(pin.Force(weight, np.cross(at + q[:3], weight)))
        for name in raw.legs:
            force = np.array([row[f"{name}_f{axis}"] for axis in "xyz"])
            if not row[f"{name}_stance"]:
                assert np.all(force == 0.0)
                continue
            knee, foot, foot_velocity, foot_acceleration = raw.foot(name)
            # a standing foot neither slips nor starts to: the joint rates are exact
            np.testing.assert_allclose(foot_velocity, 0.0, atol=1e-9)
            np.testing.assert_allclose(foot_acceleration, 0.0, atol=1e-9)
            world = pin.Force(force, np.cross(foot, force))
            fext[knee] += raw.data.oMi[knee].actInv(world)
        tau = pin.rnea(raw.model, raw.data, q, v, a, fext)
        np.testing.assert_allclose(tau[:6], 0.0, atol=balance)  # the feet carry the robot
        for name, leg in raw.legs.items():
            columns = [j.idx_v for j in raw.joints(name)]
            file_tau = [row[f"{name}_{part}_urdf_tau"] for part in LEG_JOINTS]
            np.testing.assert_allclose(file_tau, tau[columns], atol=1e-9)
            on_theta = [row[f"{name}_{part}_tau"] for part in LEG_JOINTS]
            np.testing.assert_allclose(np.asarray(leg["joint_signs"]) * on_theta, file_tau)
            file_q = [row[f"{name}_{part}_urdf_q"] for part in LEG_JOINTS]
            np.testing.assert_allclose(file_q, q[[j.idx_q for j in raw.joints(name)]], atol=1e-12)
        torque_seen = max(torque_seen, float(np.abs(tau[6:]).max()))
        inertial = pin.rnea(raw.model, raw.data, q, v, a) - pin.computeGeneralizedGravity(
            raw.model, raw.data, q
        )
        inertia_seen = max(inertia_seen, float(np.abs(inertial[6:]).max()))
    assert torque_seen > 1e-3 and inertia_seen > 1e-5  # the check saw loads and motion
    peak = summary["peak_torque"]["hip"]
    assert peak == pytest.approx(np.abs(table.filter(like="_hip_tau")).to_numpy().max())


def _imported(path, offset=None):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        return ImportedHexapodModel(import_robot(path, foot=FootSearch(offset=offset)))


@pytest.mark.parametrize("path", [KRABY, "ochs", "drawn:5"])
def test_feet_follow_the_planned_paths_in_pinocchio_on_the_file(tmp_path, path):
    path, _, offset = robot_under_test(path, tmp_path)
    model = _imported(path, offset)
    gait = Gait(stride=0.03, step_height=0.02, period=0.8, samples=48)
    analysis = analyze_gait(model.design, gait, model=model, limits=False)
    assert analysis.walkable
    raw = pin.buildModelFromXML(model.robot.text, pin.JointModelFreeFlyer())
    data = raw.createData()
    records = {leg.name: leg for leg in model.robot.legs}
    height = model.nominal_base_pose().translation[2]  # the body origin over the ground
    # the file's root link lies the mounts' plane below the body frame (robot_design)
    root_offset = model.design.legs[0].z - model.robot.legs[0].reading.mount[2, 3]

    def feet_at(q_file, base):
        """Every foot (6, 3), world frame, with the body frame's origin at ``base``."""
        q = pin.neutral(raw)
        q[:3] = base + np.array([0.0, 0.0, root_offset])
        for name, values in q_file.items():
            for joint, value in zip(records[name].joint_names, values, strict=True):
                q[raw.joints[raw.getJointId(joint)].idx_q] = value
        pin.framesForwardKinematics(raw, data, q)
        feet = []
        for name in model.leg_names:
            leg = records[name]
            link = raw.getFrameId(leg.chain.segments[2][0])
            point = data.oMf[link] * pin.SE3(np.eye(3), np.asarray(leg.reading.foot.point))
            feet.append(point.translation)
        return np.array(feet)

    signs = {leg.name: np.array(leg.reading.joint_map.signs) for leg in model.robot.legs}
    offsets = {leg.name: np.array(leg.reading.joint_map.offsets) for leg in model.robot.legs}
    nominal = {n: signs[n] * model.nominal_angles(n) + offsets[n] for n in model.leg_names}
    footholds = feet_at(nominal, np.array([0.0, 0.0, height]))
    travel = gait.speed * gait.period * np.array([1.0, 0.0, 0.0])
    planted: dict[int, np.ndarray] = {}
    for k in range(gait.samples):
        theta = analysis.joint_angles[k]
        q_file = {n: signs[n] * theta[i] + offsets[n] for i, n in enumerate(model.leg_names)}
        base = k / gait.samples * travel + np.array([0.0, 0.0, height])
        feet = feet_at(q_file, base)
        planned = analysis.feet[k] + base  # the plan, body frame, moved with the body
        np.testing.assert_allclose(feet, planned, atol=1e-9)
        for i in range(6):
            if analysis.stance[k, i]:  # a standing foot stays where it was put down
                start = planted.setdefault(i, feet[i])
                np.testing.assert_allclose(feet[i], start, atol=1e-9)
                assert feet[i][2] == pytest.approx(footholds[i][2], abs=1e-12)
            else:
                planted.pop(i, None)
                lift = feet[i][2] - footholds[i][2]
                assert -1e-12 <= lift <= gait.step_height + 1e-12
    heights = analysis.feet[..., 2] - analysis.frames.footholds[:, 2]
    assert heights.max() == pytest.approx(gait.step_height, rel=0.02)  # the swings lift


def _template_design():
    limits = STANCE_LIMITS  # every limit set the same, so the URDF's limits are the stance's
    return HexapodDesign(
        workspace_limits=limits,
        improved_limits=limits,
        manipulability_limits=limits,
        stance_limits=limits,
    )


@pytest.mark.parametrize("distribution", ["min-norm", "min-torque"])
def test_the_template_urdf_imported_back_walks_as_the_design(distribution):
    design = _template_design()
    gait = Gait(samples=60) if distribution == "min-norm" else Gait(samples=24)
    own = analyze_gait(design, gait, distribution=distribution, model=HexapodModel(design))
    model = ImportedHexapodModel(robot_from_text(render_hexapod(design)), design)
    back = analyze_gait(model.design, gait, distribution=distribution, model=model)
    tol = 1e-9 if distribution == "min-norm" else 1e-6  # a QP's own tolerance
    mine, theirs = back.to_dict(), own.to_dict()
    for key in ("peak_torque", "rms_torque", "peak_speed", "peak_power"):
        for joint in LEG_JOINTS:
            assert mine[key][joint] == pytest.approx(theirs[key][joint], rel=tol, abs=1e-12)
    for key in ("mass", "positive_work", "mechanical_cost_of_transport", "max_stride"):
        assert mine[key] == pytest.approx(theirs[key], rel=tol)
    assert mine["min_zmp_margin"] == pytest.approx(theirs["min_zmp_margin"], rel=tol)
    assert mine["max_speed"]["value"] == pytest.approx(theirs["max_speed"]["value"], rel=tol)
    assert mine["max_speed"]["limited_by"] == theirs["max_speed"]["limited_by"]
    assert mine["feasible"] == theirs["feasible"]
    np.testing.assert_allclose(back.joint_torques, own.joint_torques, rtol=0, atol=tol)
    np.testing.assert_allclose(back.joint_angles, own.joint_angles, rtol=0, atol=1e-12)


def test_the_template_s_step_beyond_this_small_robot_is_said_so(capsys, tmp_path):
    """Kraby's legs are 20 cm long: the template's 10 cm step walks at no stride."""
    csv = tmp_path / "gait.csv"
    assert run_cli(["gait", "--urdf", KRABY, "--step-height", "0.1", "--csv", str(csv)]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and "no stride walks at step height 0.1 m" in lines[0]
    assert not csv.exists()


def test_the_animation_is_drawn_with_the_file_s_meshes(tmp_path, capsys):
    page = tmp_path / "walk.html"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        assert run_cli(["gait", "--urdf", KRABY, *SMALL, "--html", str(page)]) == 0
    assert page.stat().st_size > 1_000_000  # Kraby's STL meshes are in it


def test_a_changed_segment_walks_as_the_changed_file_does(tmp_path, capsys):
    changed = tmp_path / "longer.urdf"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        assert run_cli(["urdf", "--urdf", KRABY, "--l2", "0.07", "-o", str(changed)]) == 0
    via_option = robot_json(capsys, ["gait", "--urdf", KRABY, "--l2", "0.07", *SMALL, "--json"])
    via_file = robot_json(capsys, ["gait", "--urdf", str(changed), *SMALL, "--json"])
    plain = robot_json(capsys, ["gait", "--urdf", KRABY, *SMALL, "--json"])
    assert via_option["design"]["l2"] == pytest.approx(0.07, abs=1e-12)
    for key in ("peak_torque", "rms_torque", "peak_speed"):
        assert via_option[key] == pytest.approx(via_file[key], rel=1e-9)
    assert via_option["peak_torque"] != pytest.approx(plain["peak_torque"], rel=1e-3)


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
def test_the_design_files_robot_table_walks_as_the_file(tmp_path, capsys):
    target = tmp_path / "kraby.toml"
    assert run_cli(["design", "import", KRABY, "-o", str(target)]) == 0
    capsys.readouterr()
    via_file = robot_json(capsys, ["gait", "--design", str(target), *SMALL, "--json"])
    direct = robot_json(capsys, ["gait", "--urdf", KRABY, *SMALL, "--json"])
    assert via_file == direct | {"robot": via_file["robot"]}
    assert direct["urdf_joint_angles"]["lf"] != direct["joint_angles"]["lf"]  # the file's zeros
