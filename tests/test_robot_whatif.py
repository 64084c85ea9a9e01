"""An imported robot's segments changed along their own lines, re-measured on the changed URDF.

Oracles, each computed here with NumPy from Pinocchio on the changed URDF text (the one
``hexaleg urdf --urdf FILE --l2 X`` writes): the axis lines of each leg's joints (origins
and the angular columns of the joint Jacobians) and its foot frame give the coxa (distance
between the yaw and hip axis lines), femur (hip to knee axis), tibia (knee axis to foot),
the offsets along the axes and the segments' directions; Pinocchio's RNEA gives the gravity
torques, its lumped joint inertias the masses; the stretch rule of the masses is applied
here by hand to the original file's inertias.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from conftest import run_cli
from robot_files import draw_hexapod

from hexaleg.exceptions import RobotImportWarning
from hexaleg.leg_frames import gravity_torques
from hexaleg.robot.feet import FootSearch
from hexaleg.robot.imported import import_robot, robot_from_text, urdf_with_feet
from hexaleg.robot.resize import resize_robot

ROBOTS = Path(__file__).parent / "data" / "robots"
KRABY = str(ROBOTS / "kraby" / "hexapod.urdf")
OCHS = str(ROBOTS / "phantomx_kevinochs" / "urdf" / "phantomX_model.xacro")
OCHS_FOOT = (0.0, 0.133, 0.0)
SEGMENTS = ("coxa", "femur", "tibia")


def _configuration(model: pin.Model, rng: np.random.Generator | None) -> np.ndarray:
    """Neutral, or every joint at a random angle in [-1, 1] rad, set by joint name order."""
    q = pin.neutral(model)
    if rng is None:
        return q
    for joint in list(model.joints)[1:]:
        angle = rng.uniform(-1.0, 1.0)
        if joint.nq == 1:
            q[joint.idx_q] = angle
        else:  # continuous: (cos, sin)
            q[joint.idx_q : joint.idx_q + 2] = (np.cos(angle), np.sin(angle))
    return q


def _measure(text: str, legs: dict[str, tuple[str, str, str]], seed: int | None) -> dict:
    """Per leg, from Pinocchio FK on ``text``: lengths, offsets, directions, axes (world)."""
    model = pin.buildModelFromXML(text)
    data = model.createData()
    q = _configuration(model, None if seed is None else np.random.default_rng(seed))
    pin.computeJointJacobians(model, data, q)
    pin.framesForwardKinematics(model, data, q)
    out = {}
    for name, joints in legs.items():
        ids = [model.getJointId(j) for j in joints]
        c1, c2, c3 = (data.oMi[i].translation.copy() for i in ids)
        u1, u2, u3 = (
            pin.getJointJacobian(model, data, i, pin.WORLD)[3:, model.joints[i].idx_v] for i in ids
        )
        foot = data.oMf[model.getFrameId(f"{name}_foot")].translation.copy()
        normal = np.cross(u1, u2)
        hip = c2 - c1
        coxa_line = hip - (hip @ u1) * u1 - (hip @ u2) * u2
        femur_line = (c3 - c2) - ((c3 - c2) @ u2) * u2
        tibia_line = (foot - c3) - ((foot - c3) @ u3) * u3
        out[name] = {
            "coxa": abs(hip @ normal) / np.linalg.norm(normal),
            "femur": np.linalg.norm(femur_line),
            "tibia": np.linalg.norm(tibia_line),
            "offsets": np.array(
                [hip @ u1, hip @ u2, (c3 - c2) @ u2, (foot - c3) @ u3, (foot - c1) @ u2]
            ),
            "directions": np.array(
                [v / np.linalg.norm(v) for v in (coxa_line, femur_line, tibia_line)]
            ),
            "axes": np.array([u1, u2, u3]),
            "roots": np.array([c1, c2, c3]),
        }
    return out


def _legs(robot) -> dict[str, tuple[str, str, str]]:
    return {leg.name: leg.joint_names for leg in robot.legs}


def _assert_changed_as_asked(original, changed_text, asked, seeds=(None, 11)):
    """The changed URDF's measured lengths are ``asked``'s; offsets, bends, axes the original's."""
    legs = _legs(original)
    for seed in seeds:
        before = _measure(urdf_with_feet(original), legs, seed)
        after = _measure(changed_text, legs, seed)
        for name in legs:
            for segment in SEGMENTS:
                expected = asked.get(name, {}).get(segment, before[name][segment])
                assert after[name][segment] == pytest.approx(expected, abs=1e-9), (name, segment)
            for key in ("offsets", "directions", "axes"):
                np.testing.assert_allclose(after[name][key], before[name][key], atol=1e-9)
            # the yaw joint is where the file puts it; the next ones moved only along segments
            np.testing.assert_allclose(
                after[name]["roots"][0], before[name]["roots"][0], atol=1e-12
            )


@pytest.mark.parametrize("seed", [1, 4])
@pytest.mark.parametrize("segments", [("coxa",), ("femur",), ("tibia",), SEGMENTS])
def test_synthetic_legs_get_the_asked_segments_and_keep_offsets_and_bends(seed, segments):
    text, _ = draw_hexapod(seed)
    original = robot_from_text(text)
    rng = np.random.default_rng(seed + 100)
    asked = {
        leg.name: {s: getattr(leg.reading.geometry, s) * rng.uniform(0.6, 1.6) for s in segments}
        for leg in original.legs
    }
    changed = resize_robot(original, asked)
    _assert_changed_as_asked(original, urdf_with_feet(changed), asked)
    # the changed robot's own reading agrees with what was measured
    for leg in changed.legs:
        for segment, value in asked[leg.name].items():
            assert getattr(leg.reading.geometry, segment) == pytest.approx(value, abs=1e-9)


REAL = [
    (KRABY, None, {"coxa": 0.06, "femur": 0.08, "tibia": 0.07}),
    (OCHS, OCHS_FOOT, {"coxa": 0.04, "femur": 0.09, "tibia": 0.15}),
]


@pytest.mark.parametrize(("path", "offset", "values"), REAL)
@pytest.mark.parametrize("flag", ["--l1", "--l2", "--l3"])
def test_real_robots_through_hexaleg_urdf(tmp_path, capsys, path, offset, values, flag):
    segment = SEGMENTS[int(flag[-1]) - 1]
    target = tmp_path / "changed.urdf"
    feet = [] if offset is None else ["--foot-offset", *map(str, offset)]
    argv = ["urdf", "--urdf", path, *feet, flag, str(values[segment]), "-o", str(target)]
    assert run_cli(argv) == 0
    err = capsys.readouterr().err
    note = [line for line in err.splitlines() if line.startswith("hexaleg: note:")]
    assert note == [
        f"hexaleg: note: the {segment} of every leg changed from the file's: drawn as "
        f"cylinders in place of their meshes"
    ]
    text = target.read_text()
    assert "hexaleg: segments changed from the file's" in text
    assert text.count(f"hexaleg: {segment} of leg ") == 6
    original = import_robot(path, foot=FootSearch(offset=offset))
    asked = {leg.name: {segment: values[segment]} for leg in original.legs}
    _assert_changed_as_asked(original, text, asked)
    # the changed segments' links draw no mesh any more: a cylinder each
    changed = robot_from_text(text)
    for leg in original.legs:
        k = SEGMENTS.index(segment)
        shapes = [
            c.shape
            for name in leg.chain.segments[k]
            for c in changed.description.links[name].collisions
        ]
        assert shapes == ["cylinder"]


def _stretched(inertia: pin.Inertia, origin, direction, ratio):
    """The documented rule by hand: mass × k; centre of mass and second moments stretched."""
    s = np.eye(3) + (ratio - 1) * np.outer(direction, direction)
    com = origin + s @ (inertia.lever - origin)
    second = np.trace(inertia.inertia) / 2 * np.eye(3) - inertia.inertia
    second = ratio * s @ second @ s
    return ratio * inertia.mass, com, np.trace(second) * np.eye(3) - second


def _total_mass(text: str) -> float:
    """Every link's mass, the root link's too (on a free flyer) [kg]."""
    return pin.computeTotalMass(pin.buildModelFromXML(text, pin.JointModelFreeFlyer()))


def _world_inertias(text, joints, q_seed):
    model = pin.buildModelFromXML(text)
    data = model.createData()
    q = _configuration(model, np.random.default_rng(q_seed))
    pin.forwardKinematics(model, data, q)
    return model, {
        j: data.oMi[model.getJointId(j)].act(model.inertias[model.getJointId(j)]) for j in joints
    }


@pytest.mark.parametrize("source", ["drawn", "kraby"])
def test_masses_follow_the_stretch_rule_and_gravity_torques_equal_rnea(source):
    if source == "drawn":
        original = robot_from_text(draw_hexapod(2)[0])
    else:
        original = import_robot(KRABY)
    rng = np.random.default_rng(5)
    asked = {
        leg.name: {s: getattr(leg.reading.geometry, s) * rng.uniform(0.5, 1.8) for s in SEGMENTS}
        for leg in original.legs
    }
    changed = resize_robot(original, asked)
    before_text, after_text = urdf_with_feet(original), urdf_with_feet(changed)
    joints = [j for leg in original.legs for j in leg.joint_names]
    _, old = _world_inertias(before_text, joints, 9)
    new_model, new = _world_inertias(after_text, joints, 9)
    measured = _measure(before_text, _legs(original), 9)
    moved = _measure(after_text, _legs(original), 9)
    added = 0.0
    for leg in original.legs:
        for k, joint in enumerate(leg.joint_names):
            segment = SEGMENTS[k]
            ratio = asked[leg.name][segment] / measured[leg.name][segment]
            direction = measured[leg.name]["directions"][k]
            origin = measured[leg.name]["roots"][k]
            mass, com, inertia = _stretched(old[joint], origin, direction, ratio)
            assert new[joint].mass == pytest.approx(mass, rel=1e-12)
            shift = moved[leg.name]["roots"][k] - origin  # the segments before it changed too
            np.testing.assert_allclose(new[joint].lever, com + shift, atol=1e-12)
            np.testing.assert_allclose(new[joint].inertia, inertia, atol=1e-12)
            added += (ratio - 1) * old[joint].mass
    total = _total_mass(before_text) + added
    assert _total_mass(after_text) == pytest.approx(total, rel=1e-12)
    # hexaleg's gravity torques of the changed legs (closed form, the changed reading)
    data = new_model.createData()
    q = _configuration(new_model, np.random.default_rng(21))
    tau = pin.rnea(new_model, data, q, np.zeros(new_model.nv), np.zeros(new_model.nv))
    for leg in changed.legs:
        joints_ = [new_model.joints[new_model.getJointId(n)] for n in leg.joint_names]
        values = [
            q[j.idx_q] if j.nq == 1 else np.arctan2(q[j.idx_q + 1], q[j.idx_q]) for j in joints_
        ]
        theta = leg.reading.joint_map.from_file(values)
        gravity = leg.reading.mount[:3, :3].T @ np.array([0.0, 0.0, -9.81])
        closed = gravity_torques(
            leg.reading.geometry,
            theta,
            [m.mass for m in leg.masses],
            [m.com for m in leg.masses],
            gravity,
        )
        file = leg.reading.joint_map.torques_to_file(closed)
        np.testing.assert_allclose(file, tau[[j.idx_v for j in joints_]], atol=1e-9)


def _json(capsys, argv):
    assert run_cli(argv) == 0, capsys.readouterr().err
    return json.loads(capsys.readouterr().out)


def test_a_change_of_zero_is_the_file(tmp_path, capsys):
    original = import_robot(KRABY)
    same = {
        leg.name: dict(zip(SEGMENTS, leg.reading.geometry.lengths, strict=True))
        for leg in original.legs
    }
    assert resize_robot(original, same) is original
    target = tmp_path / "same.urdf"
    femur = repr(original.legs[0].reading.geometry.femur)
    assert run_cli(["urdf", "--urdf", KRABY, "--l2", femur, "-o", str(target)]) == 0
    assert "note" not in capsys.readouterr().err
    ours, theirs = pin.buildModelFromXML(target.read_text()), pin.buildModelFromXML(original.text)
    assert _total_mass(target.read_text()) == pytest.approx(_total_mass(original.text), abs=1e-12)
    for a, b in zip(ours.inertias, theirs.inertias, strict=True):
        assert a.mass == pytest.approx(b.mass, abs=1e-12)
    q = _configuration(theirs, np.random.default_rng(3))
    d1, d2 = ours.createData(), theirs.createData()
    pin.framesForwardKinematics(ours, d1, q)
    pin.framesForwardKinematics(theirs, d2, q)
    for j, frame in enumerate(theirs.frames):
        i = ours.getFrameId(frame.name, frame.type)
        np.testing.assert_allclose(d1.oMf[i].homogeneous, d2.oMf[j].homogeneous, atol=1e-12)
    shown = _json(capsys, ["design", "show", "--urdf", KRABY, "--l2", femur, "--json"])
    assert shown["robot"]["changed_segments"] == []


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
def test_design_show_and_the_design_files_segments(tmp_path, capsys):
    shown = _json(capsys, ["design", "show", "--urdf", KRABY, "--l2", "0.08", "--json"])
    assert [leg["femur"] for leg in shown["design"]["legs"]] == pytest.approx([0.08] * 6, abs=1e-12)
    assert shown["design"]["l2"] == pytest.approx(0.08, abs=1e-12)
    ratio = 0.08 / 0.0602
    original = import_robot(KRABY)
    for leg, before in zip(shown["design"]["legs"], original.legs, strict=True):
        assert leg["segment_masses"][1] == pytest.approx(ratio * before.masses[1].mass, rel=1e-12)
    assert {c["segment"] for c in shown["robot"]["changed_segments"]} == {"femur"}
    # the design file: every leg's femur, then one leg's tibia; the command line over it
    design = tmp_path / "kraby.toml"
    assert run_cli(["design", "import", KRABY, "-o", str(design)]) == 0
    capsys.readouterr()
    base = design.read_text()
    design.write_text(base + "\n[robot.segments]\nfemur = 0.08\n")
    shown = _json(capsys, ["design", "show", "--design", str(design), "--json"])
    assert [leg["femur"] for leg in shown["design"]["legs"]] == pytest.approx([0.08] * 6, abs=1e-12)
    shown = _json(capsys, ["design", "show", "--design", str(design), "--l2", "0.07", "--json"])
    assert [leg["femur"] for leg in shown["design"]["legs"]] == pytest.approx([0.07] * 6, abs=1e-12)
    design.write_text(base + "\n[robot.segments.lf]\ntibia = 0.1\n")
    target = tmp_path / "one_leg.urdf"
    assert run_cli(["urdf", "--design", str(design), "-o", str(target)]) == 0
    capsys.readouterr()
    _assert_changed_as_asked(original, target.read_text(), {"lf": {"tibia": 0.1}}, seeds=(None,))
    # legs that differ: the design's l1 l2 l3 are leg lf's, said in one warning
    with pytest.warns(RobotImportWarning, match="differ from leg"):
        shown = _json(capsys, ["design", "show", "--design", str(design), "--json"])
    tibias = {leg["name"]: leg["tibia"] for leg in shown["design"]["legs"]}
    assert tibias["lf"] == pytest.approx(0.1, abs=1e-12) and tibias["rf"] != pytest.approx(0.1)


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
def test_legs_changed_apart_stand_as_the_changed_file_does(tmp_path, capsys):
    """The middle legs' femurs longer: the whole robot's statics take each leg's own.

    Oracle: the changed robot written out by ``hexaleg urdf`` and read again as a plain
    robot file, whose legs then simply differ.
    """
    design = tmp_path / "kraby.toml"
    assert run_cli(["design", "import", KRABY, "-o", str(design)]) == 0
    middle = "".join(f"\n[robot.segments.{leg}]\nfemur = 0.075\n" for leg in ("lm", "rm"))
    design.write_text(design.read_text() + middle)  # the femurs level: the feet stay level
    written = tmp_path / "middle_legs.urdf"
    assert run_cli(["urdf", "--design", str(design), "-o", str(written)]) == 0
    capsys.readouterr()
    changed = _json(capsys, ["loads", "--design", str(design), "--json"])
    plain = _json(capsys, ["loads", "--urdf", str(written), "--json"])
    torques = changed["nominal"]["joint_torques"]
    for leg, values in plain["nominal"]["joint_torques"].items():
        assert torques[leg] == pytest.approx(values, rel=1e-9, abs=1e-12), leg
    uniform = _json(capsys, ["loads", "--urdf", KRABY, "--json"])["nominal"]["joint_torques"]
    assert torques["lm"] != pytest.approx(uniform["lm"], rel=1e-3)  # the longer femurs count


ZERO_COXA = (
    Path(KRABY)
    .read_text()
    .replace(
        'origin xyz="0.049 0 0" rpy="1.5707963267948966 -0.7853981633974483 0"',
        'origin xyz="0 0 0" rpy="1.5707963267948966 -0.7853981633974483 0"',
    )
)


@pytest.mark.parametrize(
    ("argv", "table", "expected"),
    [
        (["--l2", "0"], "", "--l2 = 0 is not valid: must lie in [0.001, 100] [m]"),
        (["--l3", "200"], "", "--l3 = 200 is not valid: must lie in [0.001, 100] [m]"),
        (
            [],
            "[robot.segments.lf]\nfemur = -1\n",
            "robot.segments.lf.femur = -1 is not valid: must lie in [0.001, 100] [m]",
        ),
        ([], "[robot.segments]\ntibia = 'long'\n", "robot.segments.tibia = 'long' is not valid"),
        ([], "[robot.segments.lf]\nfemr = 0.1\n", "a leg's segments are coxa, femur, tibia"),
        ([], "[robot.segments.xx]\nfemur = 0.1\n", "known keys: coxa, femur, tibia, lf, lm"),
        (
            ["--ratios", "0.2", "0.4", "--total", "0.2"],
            "",
            "--ratios with --urdf: give --l1 --l2 --l3",
        ),
        (["zero", "--l1", "0.05"], "", "--l1 = 0.05 is not valid: leg lf's coxa is 0 m"),
    ],
)
def test_refusals(tmp_path, capsys, argv, table, expected):
    source = KRABY
    if argv[:1] == ["zero"]:
        source = str(tmp_path / "zero_coxa.urdf")
        Path(source).write_text(ZERO_COXA)
        argv = argv[1:]
    robot = ["--urdf", source]
    if table:
        design = tmp_path / "kraby.toml"
        assert run_cli(["design", "import", KRABY, "-o", str(design)]) == 0
        design.write_text(design.read_text() + "\n" + table)
        robot = ["--design", str(design)]
    target = tmp_path / "out.urdf"
    capsys.readouterr()
    assert run_cli(["urdf", *robot, *argv, "-o", str(target)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and expected in err[0], err
    assert not target.exists()


def test_an_edited_top_level_length_of_an_imported_design_is_refused(tmp_path, capsys):
    design = tmp_path / "kraby.toml"
    assert run_cli(["design", "import", KRABY, "-o", str(design)]) == 0
    lines = design.read_text().splitlines()
    edited = [("l2 = 0.08" if line.startswith("l2 = ") else line) for line in lines]
    design.write_text("\n".join(edited) + "\n")
    target = tmp_path / "out.urdf"
    capsys.readouterr()
    assert run_cli(["urdf", "--design", str(design), "-o", str(target)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "l2 = 0.08 is not the robot file's femur (0.0602 m)" in err[0], err
    assert "[robot.segments]" in err[0] and not target.exists()


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
def test_the_standing_model_of_the_changed_robot_is_the_changed_file():
    from hexaleg.robot.imported_model import ImportedHexapodModel

    original = import_robot(KRABY)
    changed = resize_robot(
        original, {leg.name: {"femur": 0.075, "tibia": 0.1} for leg in original.legs}
    )
    model = ImportedHexapodModel(changed)
    q = model.nominal_configuration()
    ours = pin.rnea(model.model, model.data, q, np.zeros(model.model.nv), np.zeros(model.model.nv))
    raw = pin.buildModelFromXML(urdf_with_feet(changed), pin.JointModelFreeFlyer())
    q_raw = pin.neutral(raw)
    q_raw[3:7] = q[3:7]  # the same body orientation: level
    for leg in changed.legs:
        for name in leg.joint_names:
            q_raw[raw.joints[raw.getJointId(name)].idx_q] = q[
                model.model.joints[model.model.getJointId(name)].idx_q
            ]
    zero = np.zeros(raw.nv)
    theirs = pin.rnea(raw, raw.createData(), q_raw, zero, zero)
    for leg in changed.legs:
        ids = [(model.model.getJointId(n), raw.getJointId(n)) for n in leg.joint_names]
        np.testing.assert_allclose(
            [ours[model.model.joints[a].idx_v] for a, _ in ids],
            [theirs[raw.joints[b].idx_v] for _, b in ids],
            atol=1e-9,
        )
    assert pin.computeTotalMass(model.model) == pytest.approx(
        _total_mass(urdf_with_feet(changed)), rel=1e-12
    )
    expected = _total_mass(original.text) + sum(
        (0.075 / leg.reading.geometry.femur - 1) * leg.masses[1].mass
        + (0.1 / leg.reading.geometry.tibia - 1) * leg.masses[2].mass
        for leg in original.legs
    )
    assert pin.computeTotalMass(model.model) == pytest.approx(expected, rel=1e-12)
