"""``loads --urdf FILE``: the statics of an imported robot, against Pinocchio on the raw file.

Oracles: Pinocchio's inverse dynamics (RNEA, zero velocity and acceleration) on the file
as written, with the reported foot forces applied as external forces at the file's own
foot points — its free-flyer rows must vanish (the forces balance the robot's weight and
moment) and its leg rows must be the reported torques in the file's joint convention;
the sum of the foot forces against the file's total mass; and the template's own URDF
imported back, whose statics at the nominal stance must be the design's to 1e-9.
"""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from conftest import run_cli
from robot_files import draw_hexapod

from hexaleg import HexapodDesign
from hexaleg.exceptions import RobotImportWarning
from hexaleg.robot.feet import FootSearch
from hexaleg.robot.imported import import_robot
from hexaleg.robot.urdf import render_hexapod

ROBOTS = Path(__file__).parent / "data" / "robots"
KRABY = str(ROBOTS / "kraby" / "hexapod.urdf")
OCHS = str(ROBOTS / "phantomx_kevinochs" / "urdf" / "phantomX_model.xacro")
OCHS_FOOT = ["--foot-offset", "0", "0.133", "0"]
G = 9.81


def _json(capsys, argv):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        assert run_cli(argv) == 0
    return json.loads(capsys.readouterr().out)


def _rnea_check(path, offset, loads, shown, payload_mass):
    """RNEA on the raw file with the reported foot forces: residual and torques in q's terms."""
    robot = import_robot(path, foot=FootSearch(offset=offset))
    model = pin.buildModelFromXML(robot.text, pin.JointModelFreeFlyer())
    data = model.createData()
    q = pin.neutral(model)  # the root link level at the origin: gravity torques need no height
    legs = {leg["name"]: leg for leg in shown["design"]["legs"]}
    for name, leg in legs.items():
        for joint, value in zip(leg["joints"], loads["urdf_joint_angles"][name], strict=True):
            q[model.joints[model.getJointId(joint)].idx_q] = value
    pin.framesForwardKinematics(model, data, q)
    fext = [pin.Force.Zero() for _ in range(model.njoints)]
    for name, force in loads["nominal"]["foot_forces"].items():
        leg = next(r for r in robot.legs if r.name == name)
        knee = model.getJointId(leg.joint_names[2])
        link = model.frames[model.getFrameId(leg.chain.segments[2][0])].placement
        foot = data.oMi[knee] * link * pin.SE3(np.eye(3), np.asarray(leg.reading.foot.point))
        world = pin.Force(np.asarray(force), np.cross(foot.translation, force))
        fext[knee] += data.oMi[knee].actInv(world)
    if payload_mass:
        # the payload's point is in the design's body frame: the mounts' plane above the root
        first = shown["design"]["legs"][0]
        plane = first["mount"]["z"] - loads["design"]["mounts"][0]["z"]
        point = np.asarray(loads["payload"]["position"]) + np.array([0.0, 0.0, plane])
        weight = np.array([0.0, 0.0, -payload_mass * G])
        fext[1] += data.oMi[1].actInv(pin.Force(weight, np.cross(point, weight)))
    model.gravity.linear = np.array([0.0, 0.0, -G])
    tau = pin.rnea(model, data, q, np.zeros(model.nv), np.zeros(model.nv), fext)
    for name, leg in legs.items():
        reported = loads["nominal"]["joint_torques"][name]
        on_theta = np.array([reported["root"], reported["hip"], reported["knee"]])
        signs = np.asarray(leg["joint_signs"])
        columns = [model.joints[model.getJointId(j)].idx_v for j in leg["joints"]]
        np.testing.assert_allclose(signs * on_theta, tau[columns], atol=1e-9)
    return model, tau[:6]


@pytest.mark.parametrize(
    ("path", "options", "offset"),
    [(KRABY, [], None), (OCHS, OCHS_FOOT, (0.0, 0.133, 0.0)), ("drawn", [], None)],
)
@pytest.mark.parametrize("payload", [0.0, 1.5])
def test_torques_and_forces_equal_pinocchio_rnea_on_the_file(
    capsys, tmp_path, path, options, offset, payload
):
    if path == "drawn":  # six equal general legs, each in its own frames: mixed signs, h, e
        path = str(tmp_path / "drawn.urdf")
        Path(path).write_text(draw_hexapod(3, same_legs=True)[0])
    argv = ["--urdf", path, *options]
    loads = _json(capsys, ["loads", *argv, "--payload", str(payload), "--json"])
    shown = _json(capsys, ["design", "show", *argv, "--json"])
    model, residual = _rnea_check(path, offset, loads, shown, payload)
    np.testing.assert_allclose(residual, 0.0, atol=1e-9)  # the forces hold the robot still
    mass = pin.computeTotalMass(model)
    total = np.sum(list(loads["nominal"]["foot_forces"].values()), axis=0)
    np.testing.assert_allclose(total, [0.0, 0.0, (mass + payload) * G], atol=1e-9)
    assert loads["mass"] == pytest.approx(mass + payload, abs=1e-12)
    assert len(loads["extremes"]) == 12 and loads["extremes_mode"] == "axis"


def test_mirrored_legs_get_torques_on_hexaleg_angles(capsys):
    # Kevin Ochs's left legs turn their pitch joints the other way (signs −1): on θ the
    # mirror-image legs hold the same hip torque, in the file's joints the opposite one
    loads = _json(capsys, ["loads", "--urdf", OCHS, *OCHS_FOOT, "--payload", "2", "--json"])
    torques = loads["nominal"]["joint_torques"]
    assert torques["lf"]["hip"] == pytest.approx(torques["rf"]["hip"], rel=1e-9)
    assert abs(torques["lf"]["hip"]) > 0.1


@pytest.mark.parametrize("distribution", ["min-norm", "min-torque"])
def test_the_template_urdf_imported_back_has_the_designs_statics(tmp_path, capsys, distribution):
    design = HexapodDesign()
    urdf = tmp_path / "template.urdf"
    urdf.write_text(render_hexapod(design))
    common = ["--payload", "3", "--payload-at", "0.05", "-0.02", "0.1", "--json"]
    common += ["--distribution", distribution]
    own = _json(capsys, ["loads", *common])
    back = _json(capsys, ["loads", "--urdf", str(urdf), *common])
    tol = 1e-9 if distribution == "min-norm" else 1e-6  # a QP's own tolerance
    assert back["stance"] == own["stance"]
    assert back["mass"] == pytest.approx(own["mass"], abs=1e-9)
    np.testing.assert_allclose(back["com"], own["com"], atol=1e-9)
    for leg in own["stance"]:
        np.testing.assert_allclose(
            back["nominal"]["foot_forces"][leg], own["nominal"]["foot_forces"][leg], atol=tol
        )
        for joint, value in own["nominal"]["joint_torques"][leg].items():
            assert back["nominal"]["joint_torques"][leg][joint] == pytest.approx(value, abs=tol)
    margin = own["nominal"]["stability_margin"]
    assert back["nominal"]["stability_margin"] == pytest.approx(margin, abs=1e-9)
    for mine, theirs in zip(back["slopes"], own["slopes"], strict=True):
        assert mine["max_slope"] == pytest.approx(theirs["max_slope"], abs=1e-9)
        assert mine["limited_by"] == theirs["limited_by"]
    capacity = own["payload_capacity"]["mass"]
    assert back["payload_capacity"]["mass"] == pytest.approx(capacity, rel=tol)
    assert back["payload_capacity"]["limited_by"] == own["payload_capacity"]["limited_by"]


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
def test_a_design_file_s_own_ratings_override_the_file_s(tmp_path, capsys):
    """Oracle: the robot file itself with its joints' efforts edited to the same ratings."""
    design = tmp_path / "kraby.toml"
    assert run_cli(["design", "import", KRABY, "-o", str(design)]) == 0
    text = design.read_text()
    assert "rated_torques = [1.18, 1.18, 1.18]" in text  # what was read: the file's efforts
    design.write_text(
        text.replace("rated_torques = [1.18, 1.18, 1.18]", "rated_torques = [2.0, 2.0, 2.0]", 1)
    )
    edited = tmp_path / "hexapod.urdf"
    edited.write_text(Path(KRABY).read_text().replace('effort="1.18"', 'effort="2.0"'))
    capsys.readouterr()
    found = _json(capsys, ["loads", "--design", str(design), "--json"])
    expected = _json(capsys, ["loads", "--urdf", str(edited), "--json"])
    assert found["design"]["rated_torques"] == [2.0, 2.0, 2.0]
    assert found["payload_capacity"] == expected["payload_capacity"]
    assert found["walking_payload_capacity"] == expected["walking_payload_capacity"]
    plain = _json(capsys, ["loads", "--urdf", KRABY, "--json"])
    assert plain["payload_capacity"]["mass"] < found["payload_capacity"]["mass"]
