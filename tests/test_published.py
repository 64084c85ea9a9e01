"""Robots as their authors publish them: round-off, exporter defaults, a coxa of 0.

Each robot is written by the test (:mod:`published`) from known numbers; the oracles are
those numbers and Pinocchio's own model of the raw file (its total mass, its kinematics).
"""

from __future__ import annotations

import json
import math
import warnings
from dataclasses import replace

import numpy as np
import pinocchio as pin
import pytest
from conftest import run_cli
from published import ROUND_OFF_HEIGHT, Spider, write_package

from hexaleg.robot.imported import import_robot
from hexaleg.robot.robot_design import robot_design

GRAVITY = 9.81
RATED = Spider(limits=(-1.5, 1.5), effort=2.0, velocity=5.0)
"""A written hexapod with limits and ratings in its file."""


def _json(capsys, argv):
    """A command's JSON, and its warnings' messages joined (one a line)."""
    capsys.readouterr()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert run_cli([*argv, "--json"]) == 0, capsys.readouterr().err
    said = "\n".join(str(w.message) for w in caught)
    return json.loads(capsys.readouterr().out), said


def _file_mass(urdf) -> float:
    model = pin.buildModelFromUrdf(str(urdf), pin.JointModelFreeFlyer())
    return float(pin.computeTotalMass(model))


@pytest.mark.parametrize("raised", [1e-9, ROUND_OFF_HEIGHT])
def test_a_mount_off_by_round_off_stands_and_says_so(tmp_path, capsys, raised):
    heights = (0.0, 0.0, 0.0, raised, 0.0, 0.0)
    urdf = write_package(tmp_path, replace(RATED, heights=heights))
    shown, err = _json(capsys, ["loads", "--urdf", str(urdf)])
    vertical = sum(force[2] for force in shown["nominal"]["foot_forces"].values())
    assert vertical == pytest.approx(_file_mass(urdf) * GRAVITY, rel=1e-12)
    # leg4 (hexaleg's rr) is the raised one: named with its offset from the mean plane
    assert "leg roots' heights differ" in err and "within 1 mm" in err
    offset = f"rr {1e6 * raised * 5 / 6:+.3g}"
    assert offset in err, err


def test_segments_differ_only_beyond_a_tenth_of_a_millimetre(tmp_path):
    close = write_package(tmp_path / "a", replace(RATED, longer=(0, 0, 0, 5e-5, 0, 0)))
    far = write_package(tmp_path / "b", replace(RATED, longer=(0, 0, 0, 3e-4, 0, 0)))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        robot_design(import_robot(close))
    assert not [w for w in caught if "differ from leg" in str(w.message)]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        robot_design(import_robot(far))
    said = [str(w.message) for w in caught if "differ from leg" in str(w.message)]
    assert len(said) == 1
    # the two triples printed differ where the legs do: femur 60.0 mm against 60.3 mm
    shown = said[0].split("(")[1:3]
    assert shown[0].split(",")[1] != shown[1].split(",")[1], said[0]


def test_a_coxa_of_zero_is_a_hexapod(tmp_path, capsys):
    urdf = write_package(tmp_path, replace(RATED, coxa=0.0))
    shown, _ = _json(capsys, ["design", "show", "--urdf", str(urdf)])
    assert shown["design"]["l1"] == 0.0
    assert shown["design"]["l2"] == pytest.approx(0.06, abs=1e-9)
    loads, _ = _json(capsys, ["loads", "--urdf", str(urdf)])
    vertical = sum(force[2] for force in loads["nominal"]["foot_forces"].values())
    assert vertical == pytest.approx(_file_mass(urdf) * GRAVITY, rel=1e-12)
    flexibility, _ = _json(capsys, ["flexibility", "--urdf", str(urdf)])
    assert flexibility["fb"] > 0


def test_hexaleg_urdf_reads_its_own_output_back(tmp_path, capsys):
    urdf = write_package(tmp_path, RATED)
    first, second = tmp_path / "feet.urdf", tmp_path / "again.urdf"
    assert run_cli(["urdf", "--urdf", str(urdf), "-o", str(first)]) == 0
    assert run_cli(["urdf", "--urdf", str(first), "-o", str(second)]) == 0
    assert second.read_text() == first.read_text()
    # each added <leg>_foot sits where the drawn tibia ends: 0.1 m straight below the knee
    model = pin.buildModelFromUrdf(str(second))
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    for leg in import_robot(second).legs:
        knee = data.oMi[model.getJointId(leg.joint_names[2])].translation
        foot = data.oMf[model.getFrameId(f"{leg.name}_foot")].translation
        np.testing.assert_allclose(foot - knee, (0.0, 0.0, -0.1), atol=1e-7)
    assert math.isclose(_file_mass(second), _file_mass(urdf), rel_tol=1e-12)
    assert not [w for w in capsys.readouterr().err.splitlines() if "already has" in w]


# the paper's joint-limit sets (Table 2, Table 4, eq 26, §6): their envelope on θ [rad]
PAPER_ENVELOPE = ((-math.pi / 4, -math.pi / 3, -5 * math.pi / 6), (math.pi / 4, math.pi / 3, 0.0))


@pytest.mark.parametrize("limits", [(0.0, 0.0), (0.3, -0.3)])
def test_joints_without_limits_get_hexalegs_sets_said_once(tmp_path, capsys, limits):
    urdf = write_package(tmp_path, replace(RATED, limits=limits))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        robot = import_robot(urdf)
    said = [str(w.message) for w in caught if "no limits in the file" in str(w.message)]
    assert len(said) == 1 and "leg1_coxa_joint" in said[0], said
    for leg in robot.legs:
        np.testing.assert_allclose(leg.theta_limits, PAPER_ENVELOPE, atol=1e-12)
    # the file written back carries them on q: the knee's zero is θ3 = −π/2 (q = θ3 + π/2)
    written = tmp_path / "written.urdf"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert run_cli(["urdf", "--urdf", str(urdf), "-o", str(written)]) == 0
    model = pin.buildModelFromUrdf(str(written))
    knee = model.joints[model.getJointId("leg1_tibia_joint")].idx_q
    assert model.lowerPositionLimit[knee] == pytest.approx(-5 * math.pi / 6 + math.pi / 2)
    assert model.upperPositionLimit[knee] == pytest.approx(math.pi / 2)
    loads, _ = _json(capsys, ["loads", "--urdf", str(urdf)])
    assert len(loads["extremes"]) == 12  # the robot stands and moves within them


def test_a_foot_contact_sensor_is_locked_naming_it(tmp_path, capsys):
    urdf = write_package(tmp_path, replace(RATED, sensor=True))
    loads, said = _json(capsys, ["loads", "--urdf", str(urdf)])
    locked = [line for line in said.splitlines() if "beyond the legs' knees" in line]
    assert len(locked) == 1 and "leg6_contact_joint" in locked[0] and "prismatic" in locked[0]
    vertical = sum(force[2] for force in loads["nominal"]["foot_forces"].values())
    assert vertical == pytest.approx(_file_mass(urdf) * GRAVITY, rel=1e-12)
    shown, _ = _json(capsys, ["design", "show", "--urdf", str(urdf)])
    feet = {leg["foot"]["source"] for leg in shown["design"]["legs"]}
    assert feet == {f"link leg{k}_foot_sensor" for k in range(1, 7)}


def test_lock_joint_holds_a_joint_the_file_moves(tmp_path, capsys):
    urdf = write_package(tmp_path, replace(RATED, sensor=True))
    turned = urdf.read_text().replace('type="prismatic"', 'type="revolute"')
    turned = turned.replace('lower="-0.0001" upper="0.0001"', 'lower="-1.0" upper="1.0"')
    (urdf.parent / "turned.urdf").write_text(turned)
    argv = ["loads", "--urdf", str(urdf.parent / "turned.urdf")]
    assert run_cli(argv) == 2
    assert "--lock-joint NAME" in capsys.readouterr().err
    loads, _ = _json(capsys, [*argv, "--lock-joint", "leg?_contact_joint"])
    vertical = sum(force[2] for force in loads["nominal"]["foot_forces"].values())
    assert vertical == pytest.approx(_file_mass(urdf) * GRAVITY, rel=1e-12)
    saved = tmp_path / "turned.toml"
    lock = ["--lock-joint", "leg?_contact_joint"]
    assert run_cli(["design", "import", argv[2], *lock, "-o", str(saved)]) == 0
    assert 'lock_joints = [\n    "leg?_contact_joint",\n]' in saved.read_text() or (
        'lock_joints = ["leg?_contact_joint"]' in saved.read_text()
    )
    again, _ = _json(capsys, ["loads", "--design", str(saved)])
    assert again["nominal"] == loads["nominal"]


def test_a_robot_sent_to_a_worker_keeps_its_locked_joints(tmp_path):
    """A study's or a decision's worker builds the robot from its recipe, the lock included.

    Oracle: the count of the robot's moving joints, six legs of three on a free flyer.
    """
    import pickle

    from hexaleg.exceptions import RobotImportError
    from hexaleg.robot.recipe import RobotSource
    from hexaleg.robot.robot import Robot

    urdf = write_package(tmp_path, replace(RATED, sensor=True))
    turned = urdf.read_text().replace('type="prismatic"', 'type="revolute"')
    turned = turned.replace('lower="-0.0001" upper="0.0001"', 'lower="-1.0" upper="1.0"')
    (urdf.parent / "turned.urdf").write_text(turned)
    path = str(urdf.parent / "turned.urdf")
    with pytest.raises(RobotImportError, match="--lock-joint NAME"):
        Robot.build(RobotSource.of(path))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        robot = Robot.build(RobotSource.of(path, lock=["leg?_contact_joint"]))
        sent = pickle.loads(pickle.dumps(robot))
    assert sent.source.lock == ("leg?_contact_joint",) and sent == robot
    assert sent.model.model.nq == 7 + 6 * 3
    assert sent.fingerprint()["robot"]["lock"] == ["leg?_contact_joint"]


def test_a_locked_joints_name_cannot_end_the_note_hexaleg_writes(tmp_path, capsys):
    """A name holding ``-->`` and markup stays a name in the rewritten text (XML's own parse)."""
    import xml.etree.ElementTree as ET

    urdf = write_package(tmp_path, replace(RATED, sensor=True))
    hostile = "leg6_contact---&gt;&lt;link name=&quot;evil&quot;/&gt;&lt;!--"
    text = urdf.read_text().replace('"leg6_contact_joint"', f'"{hostile}"')
    assert text.count(hostile) == 1
    (urdf.parent / "hostile.urdf").write_text(text)
    robot = import_robot(urdf.parent / "hostile.urdf")
    root = ET.fromstring(robot.text)
    assert not any(link.get("name") == "evil" for link in root.iter("link"))
    fixed = {j.get("name") for j in root.iter("joint") if j.get("type") == "fixed"}
    assert 'leg6_contact---><link name="evil"/><!--' in fixed
    loads, _ = _json(capsys, ["loads", "--urdf", str(urdf.parent / "hostile.urdf")])
    vertical = sum(force[2] for force in loads["nominal"]["foot_forces"].values())
    assert vertical == pytest.approx(_file_mass(urdf) * GRAVITY, rel=1e-12)


UNRATED = replace(RATED, effort=0.0, velocity=0.0)
"""The written hexapod with the exporter's effort="0" velocity="0"."""


def test_effort_zero_is_no_rating_and_never_a_number(tmp_path, capsys):
    urdf = write_package(tmp_path / "unrated", UNRATED)
    loads, said = _json(capsys, ["loads", "--urdf", str(urdf)])
    assert loads["payload_capacity"] is None and loads["walking_payload_capacity"] is None
    assert loads["design"]["rated_torques"] is None and loads["over_rating"] == []
    warned = [line for line in said.splitlines() if "have no effort" in line]
    assert len(warned) == 1 and "leg1_coxa_joint" in warned[0]
    assert "--rated-torques ROOT HIP KNEE" in warned[0] and "rated_torques" in warned[0]
    capsys.readouterr()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert run_cli(["loads", "--urdf", str(urdf)]) == 0
    text = capsys.readouterr().out
    assert "payload capacity                   needs a rating" in text
    assert "walking payload capacity           needs a rating" in text
    assert "60" not in text.split("peak |τ| root")[1].split("\n")[0]  # no invented rating
    # the ratings given as options are the file's own: the same capacity as the rated file
    given = ["--rated-torques", "2", "2", "2", "--rated-speeds", "5", "5", "5"]
    by_options, _ = _json(capsys, ["loads", "--urdf", str(urdf), *given])
    by_file, _ = _json(capsys, ["loads", "--urdf", str(write_package(tmp_path / "rated", RATED))])
    assert by_options["payload_capacity"] == by_file["payload_capacity"]
    assert by_file["payload_capacity"]["mass"] > 0


def test_gait_and_decide_need_a_rating(tmp_path, capsys):
    urdf = write_package(tmp_path, UNRATED)
    walked = ["--urdf", str(urdf), "--stride", "0.04", "--step-height", "0.02", "--period", "1"]
    gait, _ = _json(capsys, ["gait", *walked])
    assert gait["max_speed"] is None and gait["max_stride"] > 0 and gait["over_rating"] == []
    assert gait["ratings_not_checked"] == ["torque", "speed"]  # effort="0" velocity="0"
    capsys.readouterr()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert run_cli(["gait", *walked]) == 0
    feasible = next(line for line in capsys.readouterr().out.splitlines() if "feasible" in line)
    assert "NOT checked" in feasible and "--rated-torques, --rated-speeds" in feasible
    assert run_cli(["decide", "--urdf", str(urdf), "--evaluations", "48"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--rated-torques ROOT HIP KNEE" in err[0], err


def test_design_import_writes_no_invented_rating(tmp_path, capsys):
    urdf = write_package(tmp_path, UNRATED)
    saved = tmp_path / "spider.toml"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert run_cli(["design", "import", str(urdf), "-o", str(saved)]) == 0
    written = saved.read_text()
    assert "\nrated_torques" not in written and "# rated_torques = [ROOT, HIP, KNEE]" in written
    assert "150.0," not in written and "60.0," not in written  # hexaleg's default ratings
    loads, _ = _json(capsys, ["loads", "--design", str(saved)])
    assert loads["payload_capacity"] is None
    edited = written.replace("# rated_torques = [ROOT, HIP, KNEE]", "rated_torques = [2, 2, 2]\n#")
    saved.write_text(edited)
    loads, _ = _json(capsys, ["loads", "--design", str(saved)])
    assert loads["payload_capacity"]["mass"] > 0


def test_the_default_gait_of_a_small_robot_is_its_own(tmp_path, capsys):
    urdf = write_package(tmp_path, RATED)  # legs of 0.04 + 0.06 + 0.1 = 0.2 m
    walked, _ = _json(capsys, ["gait", "--urdf", str(urdf)])
    gait, leg = walked["gait"], 0.04 + 0.06 + 0.1
    assert gait["step_height"] == pytest.approx(0.1 * leg, rel=1e-6)  # the STL's float32
    assert gait["stride"] / (0.5 * gait["period"]) == pytest.approx(0.3 * leg, rel=1e-6)
    assert walked["feasible"] and walked["max_speed"] is not None
    # its stride is half its max stride at that step height: twice it is the limit
    twice = 2 * gait["stride"]
    steps = ["--step-height", repr(gait["step_height"]), "--period", repr(gait["period"])]
    below, _ = _json(capsys, ["gait", "--urdf", str(urdf), *steps, "--stride", repr(twice * 0.999)])
    assert below["violations"] == []
    capsys.readouterr()
    beyond = ["gait", "--urdf", str(urdf), *steps, "--stride", repr(twice * 1.001)]
    assert run_cli(beyond) == 2
    assert "stride" in capsys.readouterr().err
    # a [gait] table's keys go over it, the others kept
    table = tmp_path / "walk.toml"
    table.write_text("[gait]\nsamples = 60\n")
    design = ["--design", str(table)]
    tabled, _ = _json(capsys, ["gait", "--urdf", str(urdf), *design, "--stride", "0.01"])
    assert tabled["gait"]["samples"] == 60 and tabled["gait"]["stride"] == 0.01
    assert tabled["gait"]["step_height"] == gait["step_height"]


def test_the_template_keeps_its_default_gait(capsys):
    from hexaleg import HexapodDesign, HexapodModel
    from hexaleg.gait.defaults import default_gait
    from hexaleg.gait.spec import Gait

    assert default_gait(HexapodModel(HexapodDesign())) == Gait()
    assert Gait() == Gait(period=2.0, stride=0.3, step_height=0.1, samples=200)


def test_legs_rooted_on_the_x_axis_are_named_by_where_they_point(tmp_path, capsys):
    # roots along the body's axis, alternating sides, each coxa pointing straight left or right
    xs = (0.15, 0.03, -0.09, 0.09, -0.03, -0.15)
    yaws = (math.pi / 2,) * 3 + (-math.pi / 2,) * 3
    spider = replace(RATED, roots=tuple((x, 0.0) for x in xs), yaws=yaws)
    shown, _ = _json(capsys, ["design", "show", "--urdf", str(write_package(tmp_path, spider))])
    named = {leg["name"]: leg["joints"][0] for leg in shown["design"]["legs"]}
    # left: the coxas pointing +y, front to rear by x; right likewise
    expected = {"lf": 1, "lm": 2, "lr": 3, "rf": 4, "rm": 5, "rr": 6}
    assert named == {name: f"leg{k}_coxa_joint" for name, k in expected.items()}


@pytest.mark.parametrize("seed", range(4))
def test_legs_around_a_turned_body_keep_their_names(tmp_path, capsys, seed):
    # six legs every 60° from a random first angle: lf is the left leg nearest ahead
    first = np.random.default_rng(seed).uniform(0.05, math.pi / 3 - 0.05)
    angles = tuple(first + k * math.pi / 3 for k in range(6))
    shown, _ = _json(
        capsys,
        ["design", "show", "--urdf", str(write_package(tmp_path, replace(RATED, angles=angles)))],
    )
    named = {leg["name"]: int(leg["joints"][0][3]) - 1 for leg in shown["design"]["legs"]}
    # left front to rear, right rear to front: counter-clockwise on each side
    left = sorted(
        (k for k in range(6) if math.sin(angles[k]) > 0), key=lambda k: -math.cos(angles[k])
    )
    right = sorted(
        (k for k in range(6) if math.sin(angles[k]) < 0), key=lambda k: math.cos(angles[k])
    )
    assert [named[n] for n in ("lf", "lm", "lr")] == left
    assert [named[n] for n in ("rr", "rm", "rf")] == right


@pytest.mark.parametrize(
    ("body", "said"),
    [("box", "the body's collision box"), ("mesh", "fitted to the body's collision meshes")],
)
def test_the_body_the_extremes_stop_at_is_the_files(tmp_path, capsys, body, said):
    size = (0.16, 0.12, 0.08)  # centred on the root link, the leg roots' plane
    spider = replace(RATED, limits=(-3.0, 3.0), body=body, body_size=size)
    urdf = write_package(tmp_path, spider)
    shown, _ = _json(capsys, ["design", "show", "--urdf", str(urdf)])
    box = shown["robot"]["body_box"]
    np.testing.assert_allclose(box["size"], size, rtol=1e-6)  # float32 STL vertices
    assert said in box["from"]
    # lowered, the body stops where its bottom, 0.04 m below the roots, meets the ground:
    # the feet stand 0.1 m (the tibia) below the roots
    flexibility, _ = _json(capsys, ["flexibility", "--urdf", str(urdf)])
    lowest = next(e for e in flexibility["extremes"] if e["axis"] == "z" and e["sign"] < 0)
    assert lowest["value"] == pytest.approx(-(0.1 - 0.04), abs=1e-6)
    assert lowest["limited_by"]["kind"] == "ground"


def _stand_height(theta2: np.ndarray, theta3: np.ndarray) -> np.ndarray:
    """How far below its root a drawn leg's foot stands (eq 7's z, negated) [m]."""
    return -(0.06 * np.sin(theta2) + 0.1 * np.sin(theta2 + theta3))


def test_a_robot_whose_default_posture_cannot_stand_stands_after_the_search(tmp_path, capsys):
    # a body reaching 0.12 m below the roots, a 0.1 m tibia: θ = (0, 0, −π/2) puts it 2 cm
    # into the ground
    spider = replace(RATED, body="box", body_size=(0.16, 0.12, 0.24))
    urdf = write_package(tmp_path, spider)
    shown, said = _json(capsys, ["design", "show", "--urdf", str(urdf)])
    assert "20 mm below the ground" in said and "it stands at" in said
    chosen = [leg["nominal"]["joint_angles"] for leg in shown["design"]["legs"]]
    assert all(angles == chosen[0] for angles in chosen)
    _, t2, t3 = chosen[0]
    height = float(_stand_height(np.array(t2), np.array(t3)))
    assert height - 0.12 >= 0.1 * height - 1e-12  # it stands with room
    # no posture on a fine grid that stands with the same room is nearer the paper's
    hips, knees = np.meshgrid(np.linspace(-1.45, 1.45, 600), np.linspace(-3.02, -0.12, 600))
    stands = _stand_height(hips, knees) * 0.9 >= 0.12
    nearest = np.hypot(hips, knees + math.pi / 2)[stands].min()
    assert math.hypot(t2, t3 + math.pi / 2) <= nearest + 0.03  # the search's grid step
    # and every command stands there: the body lowered reaches the ground from that height
    flexibility, _ = _json(capsys, ["flexibility", "--urdf", str(urdf)])
    lowest = next(e for e in flexibility["extremes"] if e["axis"] == "z" and e["sign"] < 0)
    if lowest["limited_by"]["kind"] == "ground":
        assert lowest["value"] == pytest.approx(-(height - 0.12), abs=1e-6)


def test_a_posture_that_cannot_stand_is_refused_naming_what_breaks(tmp_path, capsys):
    # limits q in [0.2, 1.0] on every joint: θ2 ≥ 0.2 lifts the femur, θ3 ≤ −0.57 + ... the
    # paper's θ is moved inside them (θ1, θ2 to 0.2, θ3 to −1.37) and the body is deeper
    spider = replace(RATED, limits=(0.2, 1.0), body="box", body_size=(0.16, 0.12, 0.17))
    urdf = write_package(tmp_path, spider)
    capsys.readouterr()
    assert run_cli(["loads", "--urdf", str(urdf)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    height = float(_stand_height(np.array(0.2), np.array(0.2 - math.pi / 2)))
    below = f"{1000 * (0.085 - height):.3g} mm below the ground"
    assert len(err) == 1 and below in err[0] and "does not stand" in err[0], err
    # not as deep: the posture moved inside the limits stands, and says it moved
    shallow = replace(spider, body_size=(0.16, 0.12, 0.03))
    shown, _ = _json(
        capsys, ["design", "show", "--urdf", str(write_package(tmp_path / "b", shallow))]
    )
    moved = shown["design"]["legs"][0]["nominal"]["moved_into_limits"]
    assert moved == ["root", "hip", "knee"]


@pytest.mark.slow
def test_the_report_of_an_unrated_robot_says_what_needs_a_rating(tmp_path, capsys):
    """No 'nan kg' where a capacity needs the ratings the file does not give."""
    urdf = write_package(tmp_path / "unrated", UNRATED)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert run_cli(["report", "--urdf", str(urdf), "-o", str(tmp_path / "out")]) == 0
    text = (tmp_path / "out" / "report.md").read_text()
    statics = text.split("Payload capacity standing:")[1].split("\n")[0]
    assert statics.count("needs a rating") == 2, statics  # standing and walking
    assert "nan" not in text.lower().replace("nano", "")
