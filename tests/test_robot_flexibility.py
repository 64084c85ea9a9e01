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
import pytest
from conftest import run_cli
from raw_chain import RawChain, body_pose
from robot_files import draw_hexapod
from robots import equal_limits_design

from hexaleg.exceptions import RobotImportWarning
from hexaleg.robot.imported import robot_from_text
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


def _drawn(folder, seed):
    """A synthetic hexapod of six equal general legs, each in its own frames, as a file."""
    text, _ = draw_hexapod(seed, same_legs=True)
    path = folder / f"drawn{seed}.urdf"
    path.write_text(text)
    return path


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
    chain = RawChain(path, offset, _json(capsys, ["design", "show", *argv, "--json"]))
    height, footholds = chain.standing(result["stance"])
    assert chain.clearance(body_pose(np.zeros(6), height)) > 0
    for extreme in result["extremes"]:
        pose = np.asarray(extreme["pose"])
        body = body_pose(pose, height)
        q = chain.configuration(body, extreme["urdf_joint_angles"])
        for name in result["stance"]:
            why, solved = chain.broken(q, name, footholds[name])
            assert why is None, (extreme["description"], name, why)
            values = [solved[j.idx_q] for j in chain.joints(name)]
            np.testing.assert_allclose(values, extreme["urdf_joint_angles"][name], atol=1e-6)
        assert chain.clearance(body) >= -1e-9
        further = pose.copy()
        further[AXES.index(extreme["axis"])] += extreme["sign"] * STEP
        body = body_pose(further, height)
        q = chain.configuration(body, extreme["urdf_joint_angles"])
        cause = extreme["limited_by"]
        if cause["kind"] == "ground":
            assert chain.clearance(body) < 0, extreme["description"]
        else:
            why, _ = chain.broken(q, cause["leg"], footholds[cause["leg"]])
            assert why == cause["kind"], (extreme["description"], why)


@pytest.mark.parametrize("layout", ["rectangle", "hexagon"])
def test_the_template_urdf_imported_back_has_the_designs_extremes(layout):
    design = equal_limits_design(layout)
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
