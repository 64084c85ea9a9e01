"""The URDF loads whole where users drop it: PyBullet and Gazebo's parser (libsdformat).

Both once mishandled massless frame-only links: sdformat dropped each with its whole
subtree (all six legs vanished), PyBullet weighed each 1 kg. Each tool runs in its own
process, as a user's would, and reports what it kept.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from hexaleg import HexapodDesign, write_urdf

CHECKER = Path(__file__).with_name("sdformat_joints.cc")
DESIGNS = [HexapodDesign(), HexapodDesign(l1=0.1, l2=0.5, l3=0.35, body_mass=30.0)]

PYBULLET_SCRIPT = """
import json, sys
import pybullet as p
p.connect(p.DIRECT)
robot = p.loadURDF(sys.argv[1])
n = p.getNumJoints(robot)
masses = [p.getDynamicsInfo(robot, j)[0] for j in range(-1, n)]
revolute = sum(p.getJointInfo(robot, j)[2] == p.JOINT_REVOLUTE for j in range(n))
print(json.dumps({"links": n + 1, "revolute": revolute, "mass": sum(masses)}))
"""


def _required(what: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(f"{what} is not installed: .ci/run must install it")
    pytest.skip(f"{what} is not installed")


@pytest.mark.parametrize("design", DESIGNS, ids=["default", "custom"])
def test_pybullet_keeps_every_link_with_the_designs_mass(tmp_path, design):
    if not os.environ.get("CI"):
        pytest.importorskip("pybullet")
    urdf = write_urdf(design, tmp_path / "robot.urdf")
    result = subprocess.run(
        [sys.executable, "-c", PYBULLET_SCRIPT, str(urdf)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 0, result.stderr
    assert "No inertial data" not in result.stdout + result.stderr
    report = json.loads(result.stdout.strip().splitlines()[-1])
    assert report["revolute"] == 18
    assert report["links"] == 1 + 6 * 4  # body; coxa, femur, tibia, foot per leg
    assert report["mass"] == pytest.approx(design.total_mass, rel=1e-12)


@pytest.fixture(scope="module")
def sdformat_checker(tmp_path_factory):
    pkg_config = shutil.which("pkg-config")
    found = pkg_config and subprocess.run([pkg_config, "--exists", "sdformat12"]).returncode == 0
    if not found or shutil.which("g++") is None:
        _required("libsdformat-dev (Gazebo's SDFormat parser) with g++ and pkg-config")
    flags = subprocess.run(
        [pkg_config, "--cflags", "--libs", "sdformat12"], capture_output=True, text=True
    ).stdout.split()
    binary = tmp_path_factory.mktemp("sdformat") / "sdformat_joints"
    subprocess.run(
        ["g++", "-std=c++17", str(CHECKER), *flags, "-o", str(binary)],
        check=True,
        capture_output=True,
        timeout=300,
    )
    return binary


@pytest.mark.slow  # compiles and runs a C++ SDFormat checker
@pytest.mark.parametrize("design", DESIGNS, ids=["default", "custom"])
def test_gazebo_sdformat_keeps_all_eighteen_joints(tmp_path, sdformat_checker, design):
    urdf = write_urdf(design, tmp_path / "robot.urdf")
    result = subprocess.run(
        [str(sdformat_checker), str(urdf)], capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 0, result.stderr
    kept = dict(line.split() for line in result.stdout.splitlines())
    assert int(kept["revolute"]) == 18
    assert int(kept["links"]) == 1 + 6 * 4  # the feet are kept, not lumped
    assert float(kept["mass"]) == pytest.approx(design.total_mass, rel=1e-12)
