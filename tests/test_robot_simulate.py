"""``simulate --urdf FILE``: an imported robot in MuJoCo, against Pinocchio on the raw file.

Oracles: MuJoCo's inverse dynamics of the model hexaleg builds (``mj_inverse``, in the air)
against Pinocchio's RNEA on the file as written, at random joint angles, rates and
accelerations mapped onto the file's joints by the signs and offsets ``design show``
reads, and each contact sphere's centre against Pinocchio's forward kinematics of the
file's foot point; then the walk itself: it must not fall, must cover most of the planned
distance, and the robot standing on a tripod must press each foot on the floor with the
force the statics give (the statics held to RNEA on the raw file in ``test_robot_loads``):
here a drawn file of general legs through the command, the template and Kraby in
``test_sim_simulate`` (the same test for each kind of robot).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from conftest import run_cli
from robots import KRABY, robot_json, robot_under_test

from hexaleg.robot.feet import FootSearch
from hexaleg.robot.imported import import_robot
from hexaleg.robot.imported_model import ImportedHexapodModel

mujoco = pytest.importorskip("mujoco")

from hexaleg.sim.model import SimModel  # noqa: E402 (needs MuJoCo)

SMALL = ["--stride", "0.03", "--step-height", "0.02", "--period", "0.8", "--cycles", "3"]
"""A short walk every robot here takes: two measured periods."""


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("path", [KRABY, "ochs", "drawn:3"])
def test_mujoco_model_is_the_file_in_pinocchio(capsys, tmp_path, path):
    path, options, offset = robot_under_test(path, tmp_path)
    shown = robot_json(capsys, ["design", "show", "--urdf", path, *options, "--json"])
    legs = {leg["name"]: leg for leg in shown["design"]["legs"]}
    robot = import_robot(path, foot=FootSearch(offset=offset))
    sim = SimModel(ImportedHexapodModel(robot))
    raw = pin.buildModelFromXML(robot.text, pin.JointModelFreeFlyer())
    raw.gravity.linear = np.array([0.0, 0.0, -9.81])
    data_pin, data = raw.createData(), mujoco.MjData(sim.mj)
    names = [leg.name for leg in robot.legs]
    rng = np.random.default_rng(7)
    for _ in range(5):
        theta = np.array([legs[n]["nominal"]["joint_angles"] for n in names])
        theta += rng.uniform(-0.2, 0.2, theta.shape)
        rates, accelerations = rng.uniform(-2, 2, (2, *theta.shape))
        q, v, a = pin.neutral(raw), np.zeros(raw.nv), np.zeros(raw.nv)
        q[2] = 2.0  # in the air: no contact
        data.qpos[:] = 0.0
        data.qpos[2], data.qpos[3] = 2.0, 1.0
        data.qvel[:], data.qacc[:] = 0.0, 0.0
        for i, name in enumerate(names):
            signs, offsets = np.asarray(legs[name]["joint_signs"]), legs[name]["joint_offsets"]
            joints = [raw.joints[raw.getJointId(j)] for j in legs[name]["joints"]]
            for k, joint in enumerate(joints):
                q[joint.idx_q] = signs[k] * theta[i, k] + offsets[k]
                v[joint.idx_v] = signs[k] * rates[i, k]
                a[joint.idx_v] = signs[k] * accelerations[i, k]
                data.qpos[sim.qpos[i, k]] = q[joint.idx_q]
                data.qvel[sim.dof[i, k]] = v[joint.idx_v]
                data.qacc[sim.dof[i, k]] = a[joint.idx_v]
        mujoco.mj_inverse(sim.mj, data)
        assert data.ncon == 0
        tau = pin.rnea(raw, data_pin, q, v, a)
        scale = max(1.0, float(np.abs(tau).max()))
        for i, name in enumerate(names):
            columns = [raw.joints[raw.getJointId(j)].idx_v for j in legs[name]["joints"]]
            np.testing.assert_allclose(
                data.qfrc_inverse[sim.dof[i]], tau[columns], atol=1e-9 * scale
            )
        # the body's linear rows: the same force whatever the point (the body is level)
        np.testing.assert_allclose(data.qfrc_inverse[:3], tau[:3], atol=1e-9 * scale)
        # each contact sphere on the file's foot point (both bodies at the same place)
        pin.framesForwardKinematics(raw, data_pin, q)
        root = mujoco.mj_name2id(sim.mj, mujoco.mjtObj.mjOBJ_BODY, robot.description.root)
        shift = data.xpos[root] - q[:3]  # the file's root link in MuJoCo and in Pinocchio
        for i, leg in enumerate(robot.legs):
            link = raw.getFrameId(leg.chain.segments[2][0])
            foot = data_pin.oMf[link] * pin.SE3(np.eye(3), np.asarray(leg.reading.foot.point))
            centre = data.geom_xpos[sim.contacts[i]] - shift
            np.testing.assert_allclose(centre, foot.translation, atol=1e-9)


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("path", ["drawn:3"])  # Kraby's walk is test_sim_simulate's, for each kind
def test_a_drawn_robot_walks_and_stands_as_the_statics_say(capsys, tmp_path, path):
    path, options, _ = robot_under_test(path, tmp_path)
    result = robot_json(capsys, ["simulate", "--urdf", path, *options, *SMALL, "--json"])
    assert result["robot"] == path and "urdf_joint_angles" in result
    assert not result["fell"]
    assert result["distance"] > 0.9 * result["planned_distance"]
    assert result["tracking_rms"] < 0.05
    standing = result["standing"]
    for leg, force in standing["foot_forces_z"].items():
        assert force == pytest.approx(standing["statics_foot_forces_z"][leg], rel=0.03)
    planned, measured = result["peak_torque_planned"], result["peak_torque_measured"]
    assert measured["hip"] == pytest.approx(planned["hip"], rel=0.2)


@pytest.mark.slow
def test_the_simulated_walk_is_drawn_with_the_files_visuals(capsys, tmp_path):
    page = tmp_path / "walk.html"
    argv = ["simulate", "--urdf", KRABY, "--step-height", "0.02", "--stride", "0.03",
            "--cycles", "2", "--html", str(page)]  # fmt: skip
    assert run_cli(argv) == 0
    text = page.read_text()
    assert "meshcat" in text.lower() and len(text) > 100_000  # the file's STL meshes inside


@pytest.mark.parametrize(
    ("extra", "expected"),
    [
        (["--video", "out.gif"], "--video with --urdf is not supported yet"),
    ],
)
def test_simulate_refusals_are_one_line(capsys, tmp_path, extra, expected):
    argv = ["simulate", "--urdf", KRABY, "--step-height", "0.02", "--stride", "0.03", *extra]
    assert run_cli(argv) == 2
    out, err = capsys.readouterr()
    lines = err.strip().splitlines()
    assert out == "" and len(lines) == 1 and expected in lines[0], err
    assert not (tmp_path / "out.html").exists()
