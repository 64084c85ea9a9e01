"""The one robot type: hexaleg's template and a robot file built, derived and described alike.

Oracles, each computed here independently of :class:`~hexaleg.robot.robot.Robot`: Pinocchio's
total mass of the raw URDF (the template's rendered by Xacro, the robot file's as it lies on
disk) and its forward kinematics (the footholds ``design show`` prints), the SHA-256 of the
file's bytes, the segment lengths read again from a design file the robot writes, and the
design's own fields.
"""

from __future__ import annotations

import hashlib
import math
import pickle
import sys
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from conftest import run_cli
from robots import KINDS, KRABY, OCHS, OCHS_OFFSET, robot_argv, robot_json, robot_of

from hexaleg.design import SEGMENTS, HexapodDesign
from hexaleg.exceptions import ParameterError
from hexaleg.robot.recipe import RobotSource, SegmentLength
from hexaleg.robot.robot import SEGMENT_SPAN, Robot
from hexaleg.robot.robot_table import table_source
from hexaleg.robot.urdf import render_hexapod

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


def source_of(kind: str) -> RobotSource:
    """The recipe of a kind of robot."""
    return RobotSource() if kind == "template" else RobotSource.of(KRABY)


def raw_model(kind: str) -> pin.Model:
    """Pinocchio's model of the robot's own URDF text, built here (no hexaleg model)."""
    text = render_hexapod(HexapodDesign()) if kind == "template" else Path(KRABY).read_text()
    return pin.buildModelFromXML(text, pin.JointModelFreeFlyer())  # the root link weighs too


@pytest.fixture(params=KINDS)
def kind(request: pytest.FixtureRequest) -> str:
    return str(request.param)


def built(kind: str) -> Robot:
    return robot_of(kind)


def test_the_mass_is_pinocchios_of_what_the_robot_is_built_from(kind):
    robot = built(kind)
    expected = pin.computeTotalMass(raw_model(kind))
    assert robot.model.total_mass == pytest.approx(expected, rel=1e-12)
    assert robot.record()["derived"]["total_mass"] == pytest.approx(expected, rel=1e-12)


def _raw_nominal(kind: str, shown: dict) -> dict[str, tuple[list[str], list[float], str]]:
    """Each leg's raw-URDF joints, their values at the nominal posture and its foot frame, as
    ``design show --json`` names them (the template's joints are θ, named by its Xacro)."""
    if kind == "template":
        theta = shown["design"]["nominal_angles"]
        joints = ("root", "hip", "knee")
        return {
            mount["name"]: (
                [f"{mount['name']}_{j}_joint" for j in joints],
                theta,
                f"{mount['name']}_foot",
            )
            for mount in shown["design"]["mounts"]
        }
    return {
        leg["name"]: (
            leg["joints"],
            leg["nominal"]["urdf_joint_angles"],
            leg["foot"]["source"].split()[-1],
        )
        for leg in shown["design"]["legs"]
    }


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
def test_design_show_weighs_the_raw_urdf_and_puts_the_feet_where_it_does(kind, capsys):
    # the oracle: Pinocchio on the raw URDF, its root link on a free flyer: the total of its
    # links, and each foot in the root link's frame at the nominal posture (body frame: the
    # mounts' plane is its origin)
    raw = raw_model(kind)
    mass = pin.computeTotalMass(raw)
    shown = robot_json(capsys, ["design", "show", *robot_argv(kind), "--json"])
    assert shown["derived"]["total_mass"] == pytest.approx(mass, rel=1e-12)
    assert run_cli(["design", "show", *robot_argv(kind)]) == 0
    printed = capsys.readouterr().out
    assert f"mass                 {mass:.4g} kg" in printed, printed
    data = raw.createData()
    q = pin.neutral(raw)
    nominal = _raw_nominal(kind, shown)
    for joints, values, _ in nominal.values():
        for name, value in zip(joints, values, strict=True):
            q[raw.joints[raw.getJointId(name)].idx_q] = value
    pin.framesForwardKinematics(raw, data, q)
    base = data.oMf[raw.getFrameId(raw.frames[2].name)]  # the root link's frame
    assert raw.frames[2].type == pin.FrameType.BODY
    mounts = shown["derived"]["mounts"]
    written = shown["design"]["mounts" if kind == "template" else "legs"]  # the root link's
    plane = np.mean([m["z"] if kind == "template" else m["mount"]["z"] for m in written])
    assert sorted(nominal) == sorted(mounts) == ["lf", "lm", "lr", "rf", "rm", "rr"]
    for leg, (_, _, foot) in nominal.items():
        expected = base.actInv(data.oMf[raw.getFrameId(foot)].translation) - [0.0, 0.0, plane]
        assert mounts[leg]["foothold"] == pytest.approx(list(expected), abs=1e-9)


def test_the_nominal_footholds_are_where_the_models_feet_stand(kind):
    robot = built(kind)
    model = robot.model
    feet = model.foot_positions(model.nominal_configuration())  # world, body at its height
    derived = robot.record()["derived"]
    assert all(abs(z) < 2e-3 for z in feet[:, 2])  # on the ground
    for (name, mount), foot in zip(derived["mounts"].items(), feet, strict=True):
        assert name in robot.leg_names
        expected = [foot[0], foot[1], foot[2] - derived["nominal_height"]]
        assert mount["foothold"] == pytest.approx(expected, abs=1e-9)


def test_a_source_is_a_small_value_that_crosses_processes(kind):
    source = source_of(kind)
    again = pickle.loads(pickle.dumps(source))
    assert again == source and hash(again) == hash(source)
    assert len(pickle.dumps(source)) < 1000


def test_the_fingerprint_names_the_file_and_hashes_its_text(kind):
    found = built(kind).fingerprint()
    if kind == "template":
        assert found == {}  # the design is the whole of the template
        return
    digest = hashlib.sha256(Path(KRABY).read_bytes()).hexdigest()
    assert found["robot"]["urdf"] == KRABY and found["robot"]["sha256"] == digest


@pytest.mark.parametrize("name", SEGMENTS)
def test_at_other_lengths_every_leg_has_them(kind, name):
    robot = built(kind)
    index = SEGMENTS.index(name)
    wanted = 1.25 * robot.lengths[index]
    derived = robot.at(**{name: wanted})
    assert derived.lengths[index] == pytest.approx(wanted, rel=1e-12)
    for leg in derived.leg_names:  # each leg's own geometry, read from its model
        assert derived.model.leg_geometry(leg).lengths[index] == pytest.approx(wanted, rel=1e-9)
    others = [i for i in range(3) if i != index]
    assert [derived.lengths[i] for i in others] == pytest.approx([robot.lengths[i] for i in others])
    assert robot.lengths[index] != pytest.approx(wanted)  # the robot itself is unchanged


def test_at_the_same_lengths_is_the_same_robot(kind):
    robot = built(kind)
    same = robot.at(**dict(zip(SEGMENTS, robot.lengths, strict=True)))
    assert same.model.total_mass == pytest.approx(robot.model.total_mass, rel=1e-12)
    assert same.design == robot.design


def test_a_robot_file_at_a_changed_femur_equals_the_file_changed_by_its_recipe():
    robot = built("kraby")
    derived = robot.at(l2=0.08)
    changed = RobotSource.of(
        KRABY, segments=tuple(SegmentLength(leg, "femur", 0.08) for leg in robot.leg_names)
    )
    direct = Robot.build(changed)
    assert derived.model.total_mass == pytest.approx(direct.model.total_mass, rel=1e-12)
    assert derived.design == direct.design


def test_a_robot_file_fixes_its_body_and_takes_its_segments_and_posture():
    robot = built("kraby")
    assert all(robot.takes(name) for name in (*SEGMENTS, "nominal_angles"))
    assert not robot.takes("body_length") and not robot.body_sweepable
    with pytest.raises(ParameterError, match=r"body_length = 0\.3 is not valid: not for a robot"):
        robot.at(body_length=0.3)
    template = built("template")
    assert template.takes("body_length") and template.body_sweepable
    assert template.at(body_length=0.7).design.body_length == 0.7


def test_segment_bounds_span_the_leg_or_a_share_of_a_files_own(kind):
    robot = built(kind)
    bounds = robot.segment_bounds(0.01, 1.0)
    for name, own in zip(SEGMENTS, robot.lengths, strict=True):
        lower, upper = bounds[name]
        if kind == "template":
            assert (lower, upper) == (0.01, 1.0)
        else:
            assert lower == pytest.approx(max(0.01, (1 - SEGMENT_SPAN) * own))
            assert upper == pytest.approx((1 + SEGMENT_SPAN) * own)


def test_own_legs_are_the_files_and_none_on_the_template(kind):
    robot = built(kind)
    legs = robot.own_legs
    if kind == "template":
        assert legs is None
        return
    assert legs is not None and tuple(legs) == robot.leg_names
    assert all(not math.isclose(g.hip_height, 0.0) or g.coxa > 0 for g in legs.values())


def test_the_design_file_it_writes_reads_back_as_the_robot(kind, tmp_path):
    robot = built(kind).at(l2=0.07 if kind == "kraby" else 0.45)
    target = tmp_path / "robot.toml"
    target.write_text(robot.design_text(target))
    data = tomllib.loads(target.read_text())
    if kind == "template":
        assert (data["l1"], data["l2"], data["l3"]) == pytest.approx(robot.lengths)
        return
    assert (data["l2"]) == pytest.approx(0.0602)  # the file's own, as read
    again = Robot.build(table_source(data["robot"], tmp_path, str(target)))
    assert again.lengths == pytest.approx(robot.lengths, rel=1e-12)
    assert again.model.total_mass == pytest.approx(robot.model.total_mass, rel=1e-12)


def test_the_template_takes_no_reading_options():
    with pytest.raises(ParameterError, match=r"foot_offset = .* needs a robot file"):
        RobotSource(foot_offset=OCHS_OFFSET)
    with pytest.raises(ParameterError, match="excludes foot_frame"):
        RobotSource.of(OCHS, foot_offset=OCHS_OFFSET, foot_frame="*tibia*")


def test_a_files_posture_is_given_in_both_conventions(kind):
    robot = built(kind)
    posture = robot.posture()
    if kind == "template":
        assert posture == {}
        return
    model = robot.model
    for leg, theta in posture["joint_angles"].items():
        assert posture["urdf_joint_angles"][leg] == pytest.approx(
            list(model.joint_values(leg, theta))
        )


def test_a_relative_path_is_read_as_the_file_it_names_now(tmp_path, monkeypatch):
    # oracle: Pinocchio's total mass of each file's own text, built here; the same relative
    # path in two folders, then the file replaced in place, is each time the file there
    text = Path(KRABY).read_text()
    first, second = (text.replace('<mass value="0.667" />', f'<mass value="{m}" />', 1)
                     for m in ("0.667", "1.5"))  # fmt: skip
    for name, body in (("a", first), ("b", second)):
        (tmp_path / name).mkdir()
        (tmp_path / name / "r.urdf").write_text(body)
    for name, body in (("a", first), ("b", second), ("a", first)):
        monkeypatch.chdir(tmp_path / name)
        expected = pin.computeTotalMass(pin.buildModelFromXML(body, pin.JointModelFreeFlyer()))
        robot = Robot.build(RobotSource.of("r.urdf"))
        assert robot.model.total_mass == pytest.approx(expected, rel=1e-12)
    third = second.replace('<mass value="1.5" />', '<mass value="2.25" />')
    (tmp_path / "a" / "r.urdf").write_text(third)
    changed = pin.buildModelFromXML(third, pin.JointModelFreeFlyer())
    robot = Robot.build(RobotSource.of("r.urdf"))
    assert robot.model.total_mass == pytest.approx(pin.computeTotalMass(changed), rel=1e-12)
