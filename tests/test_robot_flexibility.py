"""``flexibility --urdf FILE``: an imported robot's axis-locked extremes, rebuilt with Pinocchio.

Oracles: at each reported extreme the closed chain is rebuilt on the raw file — the body
at the reported pose, each stance foot brought back to its nominal foothold by Gauss–Newton
on Pinocchio's forward kinematics of the file (no hexaleg closed form) — and must be within
the file's joint limits with the body above the ground, while a step further along the
same axis must break the named constraint; and the template's own URDF imported back must
give the design's own extremes to 1e-9 (the design's limit sets being the file's).
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
from hexaleg.limits import STANCE_LIMITS
from hexaleg.robot.feet import FootSearch
from hexaleg.robot.imported import import_robot, robot_from_text
from hexaleg.robot.imported_model import ImportedHexapodModel
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.urdf import render_hexapod
from hexaleg.stance.flexibility import flexibility
from hexaleg.statics.loads import loads_at_extremes

ROBOTS = Path(__file__).parent / "data" / "robots"
KRABY = str(ROBOTS / "kraby" / "hexapod.urdf")
OCHS = str(ROBOTS / "phantomx_kevinochs" / "urdf" / "phantomX_model.xacro")
AXES = ("x", "y", "z", "roll", "pitch", "yaw")
STEP = 1e-5
"""How much further than an extreme the body is moved to break its constraint [m or rad]."""


def _json(capsys, argv):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        assert run_cli(argv) == 0
    return json.loads(capsys.readouterr().out)


class _Chain:
    """The raw file in Pinocchio, each foot a point on its last link (the file's own)."""

    def __init__(self, path, offset, shown):
        self.robot = import_robot(path, foot=FootSearch(offset=offset))
        self.model = pin.buildModelFromXML(self.robot.text, pin.JointModelFreeFlyer())
        self.data = self.model.createData()
        self.legs = {leg["name"]: leg for leg in shown["design"]["legs"]}
        first = shown["design"]["legs"][0]
        self.plane = first["mount"]["z"] - shown["design"]["mounts"][0]["z"]
        design = shown["design"]
        self.half = np.array([design["body_length"], design["body_width"], design["body_height"]])
        self.half /= 2

    def _joints(self, name):
        return [self.model.joints[self.model.getJointId(j)] for j in self.legs[name]["joints"]]

    def foot(self, name, q):
        """The foot of leg ``name`` (world) and its Jacobian in the leg's joints."""
        leg = next(r for r in self.robot.legs if r.name == name)
        model, data = self.model, self.data
        pin.computeJointJacobians(model, data, q)
        knee = model.getJointId(leg.joint_names[2])
        link = model.frames[model.getFrameId(leg.chain.segments[2][0])].placement
        point = data.oMi[knee] * link * pin.SE3(np.eye(3), np.asarray(leg.reading.foot.point))
        jac = pin.getJointJacobian(model, data, knee, pin.LOCAL_WORLD_ALIGNED)
        arm = point.translation - data.oMi[knee].translation
        linear = jac[:3] - pin.skew(arm) @ jac[3:]
        return point.translation.copy(), linear[:, [j.idx_v for j in self._joints(name)]]

    def configuration(self, body, angles):
        """q with the design's body frame at ``body`` and each leg's file values ``angles``."""
        q = pin.neutral(self.model)
        root = body * pin.SE3(np.eye(3), np.array([0.0, 0.0, -self.plane]))
        q[:7] = pin.SE3ToXYZQUAT(root)
        for name, values in angles.items():
            for joint, value in zip(self._joints(name), values, strict=True):
                q[joint.idx_q] = value
        return q

    def solve(self, q, name, target):
        """Gauss–Newton on leg ``name``'s joints to put its foot at ``target``: (q, residual)."""
        q = q.copy()
        columns = [j.idx_q for j in self._joints(name)]
        for _ in range(100):
            foot, jac = self.foot(name, q)
            error = target - foot
            if np.linalg.norm(error) < 1e-13:
                break
            q[columns] += np.linalg.lstsq(jac, error, rcond=None)[0]
        return q, float(np.linalg.norm(target - self.foot(name, q)[0]))

    def broken(self, q, name, target):
        """What the closed chain breaks for leg ``name`` at q: reach, joint, or nothing."""
        q, residual = self.solve(q, name, target)
        if residual > 1e-9:
            return "reach", q
        leg = self.legs[name]
        values = np.array([q[j.idx_q] for j in self._joints(name)])
        lower, upper = (
            np.asarray(leg["file_limits"]["lower"]),
            np.asarray(leg["file_limits"]["upper"]),
        )
        if np.any(values < lower - 1e-9) or np.any(values > upper + 1e-9):
            return "joint", q
        return None, q

    def clearance(self, body):
        """The design's body box's lowest point above the ground [m]."""
        return body.translation[2] - np.abs(body.rotation[2]) @ self.half


def _drawn(folder, seed):
    """A synthetic hexapod of six equal general legs, each in its own frames, as a file."""
    text, _ = draw_hexapod(seed, same_legs=True)
    path = folder / f"drawn{seed}.urdf"
    path.write_text(text)
    return path


def _body(pose, height):
    return pin.SE3(pin.rpy.rpyToMatrix(*pose[3:]), np.array([pose[0], pose[1], pose[2] + height]))


@pytest.mark.parametrize(
    ("path", "options", "offset"),
    [
        (KRABY, [], None),
        (OCHS, ["--foot-offset", "0", "0.133", "0"], (0.0, 0.133, 0.0)),
        ("drawn:3", [], None),  # hip height, lateral offset, mixed signs, bends
        ("drawn:5", [], None),
    ],
)
def test_each_extreme_is_the_last_feasible_closed_chain_in_pinocchio(
    capsys, tmp_path, path, options, offset
):
    if path.startswith("drawn:"):
        path = str(_drawn(tmp_path, int(path.split(":")[1])))
    argv = ["--urdf", path, *options]
    result = _json(capsys, ["flexibility", *argv, "--json"])
    chain = _Chain(path, offset, _json(capsys, ["design", "show", *argv, "--json"]))
    nominal = {name: leg["nominal"]["urdf_joint_angles"] for name, leg in chain.legs.items()}
    q0 = chain.configuration(pin.SE3.Identity(), nominal)
    feet = {name: chain.foot(name, q0)[0] for name in result["stance"]}
    height = -np.mean([f[2] for f in feet.values()])
    footholds = {name: f + np.array([0.0, 0.0, height]) for name, f in feet.items()}
    assert chain.clearance(_body(np.zeros(6), height)) > 0
    for extreme in result["extremes"]:
        pose = np.asarray(extreme["pose"])
        body = _body(pose, height)
        q = chain.configuration(body, extreme["urdf_joint_angles"])
        for name in result["stance"]:
            why, solved = chain.broken(q, name, footholds[name])
            assert why is None, (extreme["description"], name, why)
            values = [solved[j.idx_q] for j in chain._joints(name)]
            np.testing.assert_allclose(values, extreme["urdf_joint_angles"][name], atol=1e-6)
        assert chain.clearance(body) >= -1e-9
        further = pose.copy()
        further[AXES.index(extreme["axis"])] += extreme["sign"] * STEP
        body = _body(further, height)
        q = chain.configuration(body, extreme["urdf_joint_angles"])
        cause = extreme["limited_by"]
        if cause["kind"] == "ground":
            assert chain.clearance(body) < 0, extreme["description"]
        else:
            why, _ = chain.broken(q, cause["leg"], footholds[cause["leg"]])
            assert why == cause["kind"], (extreme["description"], why)


@pytest.mark.parametrize("layout", ["rectangle", "hexagon"])
def test_the_template_urdf_imported_back_has_the_designs_extremes(layout):
    limits = STANCE_LIMITS  # every limit set the same, so the URDF's limits are the stance's
    design = HexapodDesign(
        layout=layout,
        workspace_limits=limits,
        improved_limits=limits,
        manipulability_limits=limits,
        stance_limits=limits,
    )
    own = flexibility(design, "axis", "all", HexapodModel(design))
    model = ImportedHexapodModel(robot_from_text(render_hexapod(design)), design)
    back = flexibility(model.design, "axis", "all", model)
    assert back.fb == pytest.approx(own.fb, abs=1e-9)
    for mine, theirs in zip(back.extremes, own.extremes, strict=True):
        assert mine.value == pytest.approx(theirs.value, abs=1e-9)
        assert mine.limited_by == theirs.limited_by
        for leg, angles in theirs.joint_angles.items():
            np.testing.assert_allclose(mine.joint_angles[leg], angles, atol=1e-9)
    # and the statics there: the file's masses and joints hold each extreme as the design's
    loads = loads_at_extremes(model, back), loads_at_extremes(HexapodModel(design), own)
    for mine, theirs in zip(*(a.extremes for a in loads), strict=True):
        np.testing.assert_allclose(mine.state.foot_forces, theirs.state.foot_forces, atol=1e-9)
        np.testing.assert_allclose(mine.state.joint_torques, theirs.state.joint_torques, atol=1e-9)


def test_free_mode_and_collisions_are_refused_in_one_line(capsys):
    for extra, expected in (
        (["--mode", "free"], "--mode free"),
        (["--collisions"], "--collisions"),
    ):
        assert run_cli(["flexibility", "--urdf", KRABY, *extra]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and expected in err
    assert run_cli(["loads", "--urdf", KRABY, "--mode", "free"]) == 2
    assert "--mode free" in capsys.readouterr().err
