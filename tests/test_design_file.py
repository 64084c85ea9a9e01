"""Design files: TOML written and read back, JSON designs reproducing results, bad files refused."""

from __future__ import annotations

import json
import math
import sys

import pinocchio as pin
import pytest
from conftest import run_cli
from robots import KRABY

from hexaleg import HexapodDesign, HexapodModel, LegMount
from hexaleg.design_file import design_from_mapping, load_design
from hexaleg.design_text import design_toml
from hexaleg.exceptions import DesignError
from hexaleg.kinematics import foot_position
from hexaleg.limits import STANCE_LIMITS

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

DESIGNS = {
    "default": HexapodDesign(),
    "rectangle variant": HexapodDesign(
        l1=0.15, middle_leg_offset=0.1, front_yaw=0.6, rear_yaw=2.4, body_mass=40.0
    ),
    "hexagon": HexapodDesign(layout="hexagon", body_radius=0.35, rated_torques=(50, 120, 90)),
    "custom": HexapodDesign(
        mounts=tuple(
            LegMount(n, 0.4 * math.cos(a), 0.4 * math.sin(a), 0.02, a)
            for n, a in zip("abcdef", (0.5, 1.6, 2.6, -0.5, -1.6, -2.6), strict=True)
        )
    ),
}


@pytest.mark.parametrize("design", DESIGNS.values(), ids=DESIGNS.keys())
def test_toml_file_reads_back_the_same_design(tmp_path, design):
    path = tmp_path / "robot.toml"
    path.write_text(design_toml(design))
    assert load_design(path) == design
    assert ("\n[[mount]]" in path.read_text()) == (design.layout == "custom")


def test_every_design_field_has_a_key_in_the_file():
    from dataclasses import fields

    from hexaleg.design_file import TOP_KEYS

    assert {f.name for f in fields(HexapodDesign)} <= set(TOP_KEYS)


def test_angles_in_degrees_only_where_the_key_says_deg():
    design = design_from_mapping(
        {
            "layout": "hexagon",
            "first_leg_angle_deg": 20,
            "nominal_angles_deg": [0, 10, -100],
            "stance_limits": {"theta2_deg": [-40, 40]},
        }
    )
    assert design.first_leg_angle == pytest.approx(math.radians(20))
    assert design.nominal_angles == pytest.approx(tuple(map(math.radians, (0, 10, -100))))
    assert design.stance_limits.theta2 == pytest.approx((math.radians(-40), math.radians(40)))
    # a partial limits table keeps the other joints' default bounds
    assert design.stance_limits.theta1 == STANCE_LIMITS.theta1
    with pytest.raises(DesignError, match="not both"):
        design_from_mapping({"front_yaw": 0.5, "front_yaw_deg": 30})
    with pytest.raises(DesignError, match="only angle keys"):
        design_from_mapping({"body_radius_deg": 30})


def _one_line_exit_2(capsys, argv, *fragments):
    assert run_cli(argv) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    assert "Traceback" not in err
    for fragment in fragments:
        assert fragment in err, err
    return err


BAD_FILES = {
    "unknown key": ("l1 = 0.2\nbody_radus = 0.3\n", ["line 2", "body_radus", "body_radius"]),
    "string for a number": ('layout = "hexagon"\nl1 = "0.2"\n', ["line 2", "l1", "number"]),
    "negative radius": ('layout = "hexagon"\nbody_radius = -0.2\n', ["line 2", "body_radius"]),
    "two legs on one spot": (
        'layout = "custom"\n'
        + "".join(
            f'[[mount]]\nname = "{n}"\nx = {x}\ny = {y}\nz = 0.0\nyaw = {w}\n'
            for n, x, y, w in (
                ("a", 0.5, 0.3, 0.8),
                ("b", 0.0, 0.3, 1.6),
                ("c", -0.5, 0.3, 2.4),
                ("d", 0.5, -0.3, -0.8),
                ("e", 0.0, -0.3, -1.6),
                ("f", 0.5, -0.3, -2.4),  # where d is
            )
        ),
        ["line 2", "d and f", "apart"],
    ),
    "nominal footholds overlap": (
        'layout = "hexagon"\nbody_radius = 0.1\nl1 = 0.01\nl2 = 0.2\nl3 = 1.0\n'
        "nominal_angles = [0.0, 0.5, -2.35]\n",
        ["nominal footholds", "apart"],
    ),
    "bad TOML": ("l1 = \n", ["not valid TOML", "line 1"]),
    "unknown layout": ('layout = "octagon"\n', ["line 1", "octagon", "hexagon"]),
    "wrong table": ("[stance_limits]\ntheta2 = [0.5]\n", ["line 2", "stance_limits.theta2"]),
}


@pytest.mark.parametrize(("text", "fragments"), BAD_FILES.values(), ids=BAD_FILES.keys())
def test_bad_design_files_give_one_line_and_write_nothing(tmp_path, capsys, text, fragments):
    path = tmp_path / "robot.toml"
    path.write_text(text)
    out = tmp_path / "robot.urdf"
    _one_line_exit_2(capsys, ["urdf", "--design", str(path), "-o", str(out)], *fragments)
    assert not out.exists()


def test_unreadable_design_paths_are_refused(tmp_path, capsys):
    _one_line_exit_2(capsys, ["design", "show", "--design", str(tmp_path / "no.toml")], "no.toml")
    (tmp_path / "robot.yaml").write_text("l1: 0.2\n")
    _one_line_exit_2(
        capsys, ["design", "show", "--design", str(tmp_path / "robot.yaml")], ".toml or .json"
    )
    (tmp_path / "robot.json").write_text('{"l1": 0.2,\n "l2": }')
    _one_line_exit_2(
        capsys, ["design", "show", "--design", str(tmp_path / "robot.json")], "line 2", "JSON"
    )


ROUND_TRIPS = {
    "flexibility free": (["flexibility", "--mode", "free", "--stance", "tripod"], []),
    "loads": (["loads", "--payload", "20"], []),
    "manipulability": (["manipulability"], []),
    "workspace": (["workspace", "--samples", "2000"], []),
}


@pytest.mark.parametrize(("argv", "_"), ROUND_TRIPS.values(), ids=ROUND_TRIPS.keys())
@pytest.mark.parametrize("start", ["hexagon", "rectangle variant", "custom"])
def test_a_json_design_reproduces_the_result_exactly(tmp_path, capsys, argv, _, start):
    toml = tmp_path / "robot.toml"
    toml.write_text(design_toml(DESIGNS[start]))
    assert run_cli([*argv, "--design", str(toml), "--l1", "0.15", "--l2", "0.45", "--json"]) == 0
    printed = capsys.readouterr().out
    design = tmp_path / "design.json"
    design.write_text(json.dumps(json.loads(printed)["design"]))
    assert run_cli([*argv, "--design", str(design), "--json"]) == 0
    assert capsys.readouterr().out == printed
    whole = tmp_path / "whole.json"  # the whole output works as well
    whole.write_text(printed)
    assert run_cli([*argv, "--design", str(whole), "--json"]) == 0
    assert capsys.readouterr().out == printed


def test_decides_json_reads_as_its_best_design(tmp_path):
    yours, best = HexapodDesign(), HexapodDesign(l1=0.08, l2=0.45, l3=0.47)
    printed = {  # the shape of `hexaleg decide --json` (study.decide.DecideResult.to_dict)
        "requirements": {"payload": {"required": 30.0, "value": 41.2}},
        "best": {"design": best.as_dict(), "objective": {"name": "fb", "value": 0.25}},
        "yours": {"design": yours.as_dict(), "requirements": {}},
        "feasible": True,
    }
    path = tmp_path / "decision.json"
    path.write_text(json.dumps(printed))
    assert load_design(path) == best


def test_options_override_the_file(tmp_path, capsys):
    path = tmp_path / "robot.toml"
    path.write_text(design_toml(DESIGNS["hexagon"]))
    assert run_cli(["design", "show", "--design", str(path), "--body-radius", "0.5", "--json"]) == 0
    shown = json.loads(capsys.readouterr().out)["design"]
    assert shown["body_radius"] == 0.5
    assert shown["rated_torques"] == [50, 120, 90]  # the rest comes from the file
    assert (
        run_cli(["design", "show", "--design", str(path), "--ratios", "0.1", "0.4", "--json"]) == 0
    )
    shown = json.loads(capsys.readouterr().out)["design"]
    assert shown["l1"] + shown["l2"] + shown["l3"] == pytest.approx(DESIGNS["hexagon"].leg_length)
    assert shown["l1"] == pytest.approx(0.1 * DESIGNS["hexagon"].leg_length)


def test_design_init_writes_a_file_that_reads_back(tmp_path, capsys):
    path = tmp_path / "robot.toml"
    argv = ["design", "init", str(path), "--layout", "hexagon", "--body-radius", "0.3"]
    assert run_cli(argv) == 0
    assert load_design(path) == HexapodDesign(layout="hexagon", body_radius=0.3)
    text = path.read_text()
    assert "# coxa length [m]" in text and "(30°)" in text
    capsys.readouterr()
    _one_line_exit_2(capsys, argv, "exists", "--force")
    assert run_cli([*argv, "--force", "--body-radius", "0.4"]) == 0
    assert load_design(path).body_radius == 0.4
    capsys.readouterr()
    _one_line_exit_2(capsys, ["design", "init", str(tmp_path / "robot.txt")], ".toml")
    assert not (tmp_path / "robot.txt").exists()


def test_design_init_refuses_an_empty_path_as_empty(tmp_path, capsys, monkeypatch):
    """``design init ""`` names the empty path, not ``.`` (what ``Path("")`` reads as)."""
    monkeypatch.chdir(tmp_path)
    _one_line_exit_2(capsys, ["design", "init", ""], "an empty path")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("design", DESIGNS.values(), ids=DESIGNS.keys())
def test_design_show_derives_height_mass_and_footholds(tmp_path, capsys, design):
    path = tmp_path / "robot.toml"
    path.write_text(design_toml(design))
    assert run_cli(["design", "show", "--design", str(path), "--json"]) == 0
    derived = json.loads(capsys.readouterr().out)["derived"]
    model = HexapodModel(design)
    # oracles: Pinocchio's total mass and foot frames, the closed-form foot position
    assert derived["total_mass"] == pytest.approx(pin.computeTotalMass(model.model), rel=1e-12)
    foot = foot_position(design.lengths, design.nominal_angles)
    assert derived["nominal_height"] == pytest.approx(-foot[2] - design.legs[0].z)
    q = model.configuration(pin.SE3.Identity())
    for leg, position in zip(model.leg_names, model.foot_positions(q), strict=True):
        assert derived["mounts"][leg]["foothold"] == pytest.approx(list(position), abs=1e-12)
    assert run_cli(["design", "show", "--design", str(path)]) == 0
    text = capsys.readouterr().out
    assert design.layout in text and all(leg in text for leg in model.leg_names)


def test_a_study_of_a_design_file_sweeps_its_leg_length_and_body(tmp_path, capsys):
    design = HexapodDesign(layout="hexagon", l1=0.15, l2=0.5, l3=0.55)
    (tmp_path / "robot.toml").write_text(design_toml(design))
    out = tmp_path / "study"
    argv = ["study", "-o", str(out), "--design", str(tmp_path / "robot.toml")]
    assert run_cli([*argv, "--l1-ratios", "0.1", "--l3-points", "2", "--workers", "1"]) == 0
    spec = json.loads((out / "study.json").read_text())["spec"]
    assert spec["total"] == pytest.approx(1.2)
    assert spec["base"]["layout"] == "hexagon"


def test_an_unknown_key_error_survives_pickling():
    """Errors cross process pools; the typo's hint must arrive intact."""
    import pickle

    with pytest.raises(DesignError) as info:
        design_from_mapping({"body_radus": 0.3})
    again = pickle.loads(pickle.dumps(info.value))
    assert str(again) == str(info.value) == "unknown key 'body_radus': did you mean 'body_radius'?"


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("robot", [False, True])
@pytest.mark.parametrize(
    "command", [["design", "show"], ["urdf", "-o", "-"], ["manipulability"], ["gait"]]
)
def test_a_run_parses_the_design_file_once(tmp_path, capsys, monkeypatch, robot, command):
    target = tmp_path / "robot.toml"
    if robot:
        assert run_cli(["design", "import", KRABY, "-o", str(target)]) == 0
        extra = "[robot.segments]\nfemur = 0.07\n[gait]\nstride = 0.03\nstep_height = 0.02\n"
    else:
        target.write_text(design_toml(HexapodDesign()))
        extra = "[gait]\nstride = 0.3\n[requirements]\npayload = 5.0\n"
    target.write_text(target.read_text() + "\n" + extra)
    calls = []
    loads = tomllib.loads
    monkeypatch.setattr(tomllib, "loads", lambda text: calls.append(1) or loads(text))
    capsys.readouterr()
    assert run_cli([*command, "--design", str(target)]) == 0
    assert len(calls) == 1
