"""ROS packages found as ROS finds them: given folders, the file's ancestors, ROS_PACKAGE_PATH.

The oracle is the package tree each test writes: the folder it put a ``package.xml`` in.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from conftest import run_cli
from published import Spider, write_package

from hexaleg.exceptions import RobotImportError, RobotImportWarning
from hexaleg.robot.imported import import_robot
from hexaleg.robot.packages import ROS_PACKAGE_PATH, PackageFolders, ros_package_path
from hexaleg.robot.source import read_robot_text

STANDING = Spider(limits=(-1.5, 1.5), effort=2.0, velocity=5.0)
"""A written hexapod with limits and ratings: only its packages are under test here."""


def _manifest(folder: Path, name: str) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(f"<package format='2'><name> {name} </name></package>")


def test_ancestors_manifest_names_the_package_not_its_folder(tmp_path):
    package = tmp_path / "ws" / "src" / "checkout-2"  # a folder named unlike its package
    _manifest(package, "spider_description")
    _manifest(tmp_path / "ws" / "src" / "other", "other_description")
    (package / "urdf" / "deep").mkdir(parents=True)
    folders = PackageFolders.of({}, package / "urdf" / "deep", search_path=())
    assert folders.find("spider_description") == package.resolve()
    # a sibling package is no ancestor: not found without ROS_PACKAGE_PATH
    assert folders.find("other_description") is None
    assert folders.find("checkout-2") is None  # its manifest names it otherwise
    named = tmp_path / "plain" / "my_robot" / "urdf"  # no manifest: the folder's name
    named.mkdir(parents=True)
    assert PackageFolders.of({}, named, search_path=()).find("my_robot") == named.parent.resolve()


def test_given_folder_first_then_ancestors_then_ros_package_path(tmp_path, monkeypatch):
    ancestor = tmp_path / "a" / "spider_description"
    _manifest(ancestor, "spider_description")
    given = tmp_path / "given"
    workspace = tmp_path / "ws"
    _manifest(workspace / "src" / "group" / "spider_gazebo", "spider_gazebo")
    _manifest(workspace / "src" / "spider_description", "spider_description")
    _manifest(workspace / "src" / "spider_description" / "nested", "nested")  # not crawled into
    start = ancestor / "urdf"
    start.mkdir()
    monkeypatch.setenv(ROS_PACKAGE_PATH, os.pathsep.join([str(tmp_path / "none"), str(workspace)]))
    assert ros_package_path() == (str(tmp_path / "none"), str(workspace))
    folders = PackageFolders.of({"spider_description": given}, start)
    assert folders.find("spider_description") == given
    folders = PackageFolders.of({}, start)
    assert folders.find("spider_description") == ancestor.resolve()
    assert folders.find("spider_gazebo") == workspace / "src" / "group" / "spider_gazebo"
    assert folders.find("nested") is None
    monkeypatch.delenv(ROS_PACKAGE_PATH)
    assert ros_package_path() == ()


def test_a_published_package_tree_reads_without_options(tmp_path):
    urdf = write_package(tmp_path / "ws" / "src", STANDING, folder="spider_pkg")
    robot = import_robot(urdf)
    # every foot is on its tibia mesh's tip: found through package://spider_description/
    assert {leg.reading.foot.rule for leg in robot.legs} == {"mesh"}
    assert robot.packages.find("spider_description") == urdf.parent.parent.resolve()
    given = import_robot(urdf, packages={"spider_description": str(urdf.parent.parent)})
    assert [leg.reading.foot.point for leg in given.legs] == [
        leg.reading.foot.point for leg in robot.legs
    ]


def test_a_missing_package_is_named_once_with_the_option(tmp_path, capsys):
    urdf = write_package(tmp_path / "ws" / "src", STANDING, folder="spider_pkg")
    (urdf.parent.parent / "package.xml").unlink()  # the folder's name is not the package's
    with pytest.raises(RobotImportError) as caught:
        import_robot(urdf)
    message = str(caught.value)
    assert "spider_description not found" in message and message.count("spider_description") == 3
    assert "--package spider_description=DIR" in message
    assert run_cli(["design", "show", "--urdf", str(urdf)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].count("--package spider_description=DIR") == 1, err


def test_xacro_find_is_answered_or_named_in_one_plain_line(tmp_path, capsys):
    urdf = write_package(tmp_path / "src", STANDING, folder="spider")
    xacro = urdf.parent / "spider.urdf.xacro"
    xacro.write_text(
        '<robot name="spider" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:property name="pi" value="3.1415926535897931"/>'
        '<xacro:include filename="$(find spider_description)/urdf/legs.xacro"/></robot>'
    )
    body = urdf.read_text().split('<robot name="spider">')[1].split("</robot>")[0]
    (urdf.parent / "legs.xacro").write_text(
        f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">{body}</robot>'
    )
    assert "leg6_tibia_joint" in read_robot_text(xacro)
    assert run_cli(["design", "show", "--urdf", str(xacro), "--json"]) == 0
    captured = capsys.readouterr()
    assert "redefining" not in captured.err and "when processing" not in captured.err
    (urdf.parent.parent / "package.xml").write_text("<package><name>renamed</name></package>")
    with pytest.raises(RobotImportError) as caught:
        read_robot_text(xacro)
    message = str(caught.value)
    assert "$(find spider_description)" in message and "--package spider_description=DIR" in message
    assert "class" not in message and "Error" not in message


INTERBOTIX = (
    Path(__file__).parent
    / "data/robots/interbotix_pxmark4s/interbotix_xshexapod_descriptions/urdf/pxmark4s.urdf.xacro"
)


def test_a_public_description_package_reads_as_published(capsys):
    import json
    import math
    import warnings

    import pinocchio as pin

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert run_cli(["design", "show", "--urdf", str(INTERBOTIX), "--json"]) == 0
    shown = json.loads(capsys.readouterr().out)
    # by hand from the Xacro: the hip 52.9 mm along the coxa, the knee (60, −15) mm from
    # the hip, the foot link (95, −90) mm from the knee; effort 3 N·m, velocity π rad/s
    for leg in shown["design"]["legs"]:
        assert leg["coxa"] == pytest.approx(0.052907539, abs=1e-9)
        assert leg["femur"] == pytest.approx(math.hypot(0.06, 0.015), abs=1e-9)
        assert leg["tibia"] == pytest.approx(math.hypot(0.095, 0.09), abs=1e-9)
        assert leg["foot"]["rule"] == "frame"
    assert shown["design"]["rated_torques"] == [3.0, 3.0, 3.0]
    assert "fitted to the body's collision meshes" in shown["robot"]["body_box"]["from"]
    # its masses, standing: the feet carry what Pinocchio weighs the expanded file at
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert run_cli(["loads", "--urdf", str(INTERBOTIX), "--json"]) == 0
    loads = json.loads(capsys.readouterr().out)
    model = pin.buildModelFromXML(read_robot_text(INTERBOTIX), pin.JointModelFreeFlyer())
    vertical = sum(force[2] for force in loads["nominal"]["foot_forces"].values())
    assert vertical == pytest.approx(9.81 * pin.computeTotalMass(model), rel=1e-12)


def test_xacro_warnings_come_back_from_its_process_but_pi(tmp_path):
    """Oracle: the two warnings the file is written to draw (xacro's own texts); pi's dropped."""
    xacro = tmp_path / "w.urdf.xacro"
    xacro.write_text(
        '<robot name="w" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:property name="pi" value="3.14159"/>'
        '<xacro:property name="a" value="1" colour="red"/>'
        '<xacro:property name="b" value="2" shade="dark"/>'
        '<link name="base_${a + b}"/></robot>'
    )
    with pytest.warns(RobotImportWarning) as caught:
        text = read_robot_text(xacro)
    assert '<link name="base_3"/>' in text
    said = sorted(str(w.message) for w in caught if issubclass(w.category, RobotImportWarning))
    assert said == [
        "xacro on w.urdf.xacro: xacro:property: unknown attribute(s): colour",
        "xacro on w.urdf.xacro: xacro:property: unknown attribute(s): shade",
    ]
