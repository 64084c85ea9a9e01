"""``view --urdf FILE``: the scene of an imported robot drawn with the file's own visuals.

Oracles: the file itself, read in the test with ElementTree (its ``<visual>`` elements,
which link each joint moves and which links are fixed to it) and with Pinocchio on the
raw file (every visual's placement at the same joint values); the mesh files on disk.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import warnings
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from conftest import run_cli

from hexaleg.exceptions import RobotImportWarning
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.viewer.stage import Stage
from hexaleg.robot.feet import FootSearch
from hexaleg.robot.imported import import_robot
from hexaleg.robot.imported_model import ImportedHexapodModel

ROBOTS = Path(__file__).parent / "data" / "robots"
KRABY = ROBOTS / "kraby" / "hexapod.urdf"
OCHS = ROBOTS / "phantomx_kevinochs" / "urdf" / "phantomX_model.xacro"
OCHS_FOOT = FootSearch(offset=(0.0, 0.133, 0.0))


def _model(path: Path, **options) -> ImportedHexapodModel:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        return ImportedHexapodModel(import_robot(path, **options))


def _visual_meshes(text: str) -> list[tuple[str, str]]:
    """(link, mesh reference) of every visual mesh the file draws, in file order."""
    root = ET.fromstring(text)
    return [
        (link.get("name"), mesh.get("filename"))
        for link in root.iter("link")
        for mesh in link.findall("visual/geometry/mesh")
    ]


def _carried(text: str, joint: str) -> set[str]:
    """The links ``joint`` moves directly: its child, and every link fixed below that."""
    joints = ET.fromstring(text).findall("joint")
    carried, frontier = set(), [next(j for j in joints if j.get("name") == joint)]
    while frontier:
        child = frontier.pop().find("child").get("link")
        carried.add(child)
        frontier += [
            j for j in joints if j.get("type") == "fixed" and j.find("parent").get("link") == child
        ]
    return carried


class _Scene:
    """Stands in for a meshcat viewer: Stage.set_up only deletes and sets objects on it."""

    def __getitem__(self, _path: str) -> _Scene:
        return self

    def __getattr__(self, _name: str):
        return lambda *args, **kwargs: None


def test_the_scene_draws_every_visual_of_the_file_from_its_mesh_files():
    model = _model(KRABY)
    visual = Stage.set_up(_Scene(), model, "all").visual
    meshes = [obj for obj in visual.geometryObjects if obj.meshPath.endswith(".stl")]
    written = _visual_meshes(model.robot.text)
    assert len(meshes) == len(written) > 0 and not model.missing_meshes
    expected = sorted(str((KRABY.parent / ref).resolve()) for _, ref in written)
    assert sorted(obj.meshPath for obj in meshes) == expected
    assert all(Path(obj.meshPath).is_file() for obj in meshes)
    assert all(np.allclose(obj.meshScale, 0.001) for obj in meshes)  # the file's mm scale


def test_each_visual_sits_where_the_raw_file_puts_it():
    model = _model(KRABY)
    visual = model.visual_model()
    raw = pin.buildModelFromUrdf(str(KRABY), pin.JointModelFreeFlyer())
    raw_visual = pin.buildGeomFromUrdf(
        raw, str(KRABY), pin.GeometryType.VISUAL, package_dirs=[str(KRABY.parent)]
    )
    q = model.nominal_configuration()
    q_raw = pin.neutral(raw)
    for leg in model.robot.legs:
        values = model.joint_values(leg.name, model.nominal_angles(leg.name))
        for name, value in zip(leg.joint_names, values, strict=True):
            q_raw[raw.joints[raw.getJointId(name)].idx_q] = value
    data, raw_data = model.model.createData(), raw.createData()
    placed, raw_placed = visual.createData(), raw_visual.createData()
    pin.framesForwardKinematics(model.model, data, q)
    pin.framesForwardKinematics(raw, raw_data, q_raw)
    pin.updateGeometryPlacements(model.model, data, visual, placed)
    pin.updateGeometryPlacements(raw, raw_data, raw_visual, raw_placed)
    root = model.robot.description.root
    body, raw_body = data.oMf[model.model.getFrameId(root)], raw_data.oMf[raw.getFrameId(root)]
    names = [obj.name for obj in raw_visual.geometryObjects]
    assert sorted(obj.name for obj in visual.geometryObjects) == sorted(names)
    for k, obj in enumerate(visual.geometryObjects):
        relative = body.actInv(placed.oMg[k])  # in the root link's frame, as the file draws it
        raw_relative = raw_body.actInv(raw_placed.oMg[names.index(obj.name)])
        assert np.allclose(relative.homogeneous, raw_relative.homogeneous, atol=1e-12), obj.name


def _ochs_meshes(folder: Path) -> dict[str, Path]:
    """A stand-in ``hexapod_description`` package: any STL at each mesh path the file names."""
    package = folder / "hexapod_description"
    for _, ref in _visual_meshes(_model(OCHS, foot=OCHS_FOOT).robot.text):
        target = package / ref.removeprefix("package://hexapod_description/")
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(KRABY.parent / "meshes" / "box.stl", target)
    return {"hexapod_description": package}


@pytest.mark.parametrize("path", [KRABY, OCHS])
def test_each_joint_colours_the_links_its_file_joint_moves(path, tmp_path):
    options = {} if path == KRABY else {"foot": OCHS_FOOT, "packages": _ochs_meshes(tmp_path)}
    model = _model(path, **options)
    stage = Stage.set_up(_Scene(), model, "all")
    frames = model.model.frames
    drawn = {frames[obj.parentFrame].name for obj in stage.visual.geometryObjects}
    for leg in model.robot.legs:
        for joint, file_joint in zip(LEG_JOINTS, leg.joint_names, strict=True):
            moved = stage.joint_objects(leg.name, (joint,))
            links = {frames[obj.parentFrame].name for obj in moved}
            assert links == _carried(model.robot.text, file_joint) & drawn
            assert links  # every segment of these files draws something


def test_meshes_not_found_are_named_once_and_found_when_their_package_is_given(tmp_path):
    model = _model(OCHS, foot=OCHS_FOOT)
    written = {ref for _, ref in _visual_meshes(model.robot.text)}
    assert set(model.missing_meshes) == written and len(model.missing_meshes) == len(written)
    assert not [o for o in model.visual_model().geometryObjects if o.meshPath.endswith(".stl")]
    found = _model(OCHS, foot=OCHS_FOOT, packages=_ochs_meshes(tmp_path))
    assert not found.missing_meshes
    meshes = [o for o in found.visual_model().geometryObjects if o.meshPath.endswith(".stl")]
    assert len(meshes) == len(_visual_meshes(model.robot.text))


@pytest.mark.slow  # about 5 s
def test_view_writes_the_scene_of_an_imported_robot(tmp_path, capsys):
    out = tmp_path / "kraby.html"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        assert run_cli(["view", "--urdf", str(KRABY), "--html", str(out)]) == 0
    assert out.stat().st_size > 1_000_000  # the file's meshes are in it
    walk = tmp_path / "gait.html"
    small = ["--design", str(_kraby_gait(tmp_path))]
    assert run_cli(["view", "--urdf", str(KRABY), *small, "--gait", "--html", str(walk)]) == 0
    assert walk.stat().st_size > 1_000_000
    refused = tmp_path / "refused.html"  # a 10 cm step (the template's): no stride walks it
    tall = tmp_path / "tall.toml"
    tall.write_text("[gait]\nstep_height = 0.1\n")
    argv = ["view", "--urdf", str(KRABY), "--design", str(tall), "--gait", "--html", str(refused)]
    assert run_cli(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert "no stride walks at step height 0.1 m" in err and not refused.exists()
    own = tmp_path / "own.html"  # without a [gait] table: its own default gait, sized to it
    assert run_cli(["view", "--urdf", str(KRABY), "--gait", "--html", str(own)]) == 0


def _kraby_gait(folder: Path) -> Path:
    """A design file of a gait Kraby walks: its [gait] (the file's [robot] from --urdf)."""
    path = folder / "small.toml"
    path.write_text("[gait]\nstride = 0.03\nstep_height = 0.02\nperiod = 0.8\nsamples = 60\n")
    return path


def test_a_warning_is_one_line_naming_the_command():
    found = subprocess.run(
        [sys.executable, "-m", "hexaleg", "loads", "--urdf", str(OCHS), "--foot-offset", "0",
         "0.133", "0"],
        capture_output=True, text=True, timeout=300, check=False,
    )  # fmt: skip
    assert found.returncode == 0
    lines = [line for line in found.stderr.splitlines() if "weighs" in line]
    assert lines == [
        "hexaleg loads: warning: the file's body weighs 0.00013 kg: the statics use the "
        "file's masses as given"
    ]
    assert ".py:" not in found.stderr
