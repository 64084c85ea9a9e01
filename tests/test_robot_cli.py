"""``--urdf FILE`` and ``design import`` on real robot files, against closed forms and Pinocchio."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from conftest import run_cli

from hexaleg.exceptions import RobotImportWarning
from hexaleg.kinematics import foot_position
from hexaleg.robot.imported import import_robot

ROBOTS = Path(__file__).parent / "data" / "robots"
KRABY = str(ROBOTS / "kraby" / "hexapod.urdf")
OCHS = str(ROBOTS / "phantomx_kevinochs" / "urdf" / "phantomX_model.xacro")
HUMA = str(ROBOTS / "phantomx_humarobotics" / "urdf" / "phantomx.xacro")
HUMA_ARGS = ["--package", f"phantomx_description={ROBOTS / 'phantomx_humarobotics'}"]


def _json(capsys, argv):
    assert run_cli(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_design_show_lists_the_legs(capsys):
    out = _json(capsys, ["design", "show", "--urdf", KRABY, "--json"])
    legs = {leg["name"]: leg for leg in out["design"]["legs"]}
    assert sorted(legs) == ["lf", "lm", "lr", "rf", "rm", "rr"]
    rf = legs["rf"]
    assert rf["joints"] == ["servomotor_0", "servomotor_1", "servomotor_2"]
    # by hand from the file: coxa 0.049, femur 0.0495 + 0.0107, tibia 0.088 (the endcap link)
    assert (rf["coxa"], rf["femur"], rf["tibia"]) == pytest.approx((0.049, 0.0602, 0.088))
    assert rf["foot"] == {"rule": "frame", "source": "link endcap_0"}
    assert rf["mount"]["yaw"] == pytest.approx(-0.78539)
    assert rf["effort"] == [1.18] * 3 and rf["velocity"] == [6.308] * 3
    assert out["design"]["rated_torques"] == [1.18] * 3
    assert out["design"]["l2"] == pytest.approx(0.0602)


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
def test_workspace_per_leg_against_eq16_and_reach(capsys):
    out = _json(capsys, ["workspace", *HUMA_ARGS, "--urdf", HUMA, "--foot-offset", "0", "-0.1", "0",
                         "--samples", "3000", "--json"])  # fmt: skip
    femur, tibia, coxa = math.hypot(0.0645, 0.0145), 0.1, 0.054
    for leg in out["legs"].values():
        area = leg["area"]
        assert area["improved"] == pytest.approx(2 * math.pi * femur * tibia / 3, rel=1e-4)
        reach = coxa + femur + tibia
        bounds = np.array([leg["monte_carlo"]["lower_bound"], leg["monte_carlo"]["upper_bound"]])
        assert np.all(np.abs(bounds) <= reach + 1e-3)


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
def test_design_import_round_trip(tmp_path, capsys):
    target = tmp_path / "robot.toml"
    with pytest.warns(RobotImportWarning, match="body weighs 0.00013 kg"):
        imported = run_cli(
            ["design", "import", OCHS, "--foot-offset", "0", "0.133", "0", "-o", str(target)]
        )
    assert imported == 0
    capsys.readouterr()
    via_file = _json(capsys, ["workspace", "--design", str(target), "--samples", "500", "--json"])
    direct = _json(capsys, ["workspace", "--urdf", OCHS, "--foot-offset", "0", "0.133", "0",
                            "--samples", "500", "--json"])  # fmt: skip
    assert via_file["legs"] == direct["legs"]
    shown = _json(capsys, ["design", "show", "--design", str(target), "--json"])
    assert [leg["joints"][0] for leg in shown["design"]["legs"]][:1] == ["coxa_joint_LF"]
    assert shown["design"]["l1"] == pytest.approx(0.052)


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["workspace", "--urdf", KRABY, "--plot", "out"], "--plot with --urdf is not supported"),
        (["actuators", "--urdf", KRABY], "unrecognized arguments: --urdf"),
        (["workspace", "--foot-offset", "0", "0", "0"], "--foot-offset only applies together"),
        (
            ["workspace", "--urdf", KRABY, "--ratios", "0.2", "0.4", "--total", "0.2"],
            "--ratios with --urdf: give --l1 --l2 --l3",
        ),
        (["workspace", "--urdf", OCHS], "give foot_offset X Y Z (--foot-offset)"),
        (["manipulability", "--urdf", "missing.urdf"], "no such file"),
        (["workspace", "--urdf", HUMA], "tibia_l_coll.STL was not found or not readable"),
        (["workspace", "--urdf", KRABY, "--xacro-arg", "x=1"], "expected NAME:=VALUE"),
    ],
)
def test_refusals_are_one_line(capsys, argv, expected):
    assert run_cli(argv) == 2
    err = capsys.readouterr().err.strip()
    lines = [line for line in err.splitlines() if "redefining global symbol" not in line]
    lines = [line for line in lines if not line.startswith("when processing file")]
    assert len(lines) == 1 and expected in lines[0], err


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
def test_an_imported_design_file_is_the_robot_to_every_command(tmp_path, capsys):
    target = tmp_path / "kraby.toml"
    assert run_cli(["design", "import", KRABY, "-o", str(target)]) == 0
    capsys.readouterr()
    via_file = _json(capsys, ["flexibility", "--design", str(target), "--json"])
    assert via_file == _json(capsys, ["flexibility", "--urdf", KRABY, "--json"]) | {
        "robot": via_file["robot"]
    }
    # design init of the robot writes its design file, as design import does
    again = tmp_path / "again.toml"
    assert run_cli(["design", "init", str(again), "--design", str(target)]) == 0
    assert _json(capsys, ["design", "show", "--design", str(again), "--json"]) == _json(
        capsys, ["design", "show", "--design", str(target), "--json"]
    )
    # a failed import writes nothing
    bad = tmp_path / "ochs.toml"
    assert run_cli(["design", "import", OCHS, "-o", str(bad)]) == 2
    assert not bad.exists()


def test_urdf_of_an_imported_robot_moves_and_weighs_like_it(tmp_path, capsys):
    target = tmp_path / "ochs_feet.urdf"
    argv = ["urdf", "--urdf", OCHS, "--foot-offset", "0", "0.133", "0", "-o", str(target)]
    assert run_cli(argv) == 0
    from hexaleg.robot.feet import FootSearch

    original = import_robot(OCHS, foot=FootSearch(offset=(0.0, 0.133, 0.0)))
    ours = pin.buildModelFromXML(target.read_text())
    theirs = pin.buildModelFromXML(original.text)
    assert [ours.names[i] for i in range(ours.njoints)] == list(theirs.names)
    assert pin.computeTotalMass(ours) == pytest.approx(pin.computeTotalMass(theirs), rel=1e-12)
    q = np.random.default_rng(8).uniform(-1, 1, ours.nq)
    data = ours.createData()
    pin.framesForwardKinematics(ours, data, q)
    for leg in original.legs:
        frame = ours.getFrameId(f"{leg.name}_foot")
        assert frame < ours.nframes
        angles = [q[ours.joints[ours.getJointId(n)].idx_q] for n in leg.joint_names]
        theta = leg.reading.joint_map.from_file(angles)
        mount = leg.reading.mount
        expected = mount[:3, :3] @ foot_position(leg.reading.geometry, theta) + mount[:3, 3]
        np.testing.assert_allclose(data.oMf[frame].translation, expected, atol=1e-12)
    # read back without a foot option, the feet are the new links, the legs the same
    again = import_robot(target)
    for before, after in zip(original.legs, again.legs, strict=True):
        assert after.reading.foot.source == f"link {before.name}_foot"
        np.testing.assert_allclose(
            list(after.reading.geometry.as_dict().values()),
            list(before.reading.geometry.as_dict().values()),
            atol=1e-12,
        )


def test_nominal_posture_in_both_conventions(capsys):
    argv = ["design", "show", "--urdf", KRABY, "--json", "--nominal-angles", "0", "0.5", "-2.356"]
    for leg in _json(capsys, argv)["design"]["legs"]:
        nominal = leg["nominal"]
        # the file's knee turns θ3 = 0 into q = π/4 and allows q ≥ −1.57: θ3 ≥ −1.57 − π/4
        assert nominal["joint_angles"] == pytest.approx([0, 0.5, -1.57 - math.pi / 4])
        assert nominal["moved_into_limits"] == ["knee"]
        # q = θ + (0, π/4, π/4) on every Kraby joint (signs +1)
        assert nominal["urdf_joint_angles"] == pytest.approx([0, 0.5 + math.pi / 4, -1.57])


def test_what_if_a_longer_femur_equals_the_file_drawn_so(tmp_path, capsys):
    # Kraby's knee sits 0.0495 + 0.0107 from the hip along servomotor_1's −y; drawing the fixed
    # joint between them at 0.0693 makes the femur 0.08 m, bend and offsets unchanged
    drawn = (
        Path(KRABY)
        .read_text()
        .replace(
            'origin xyz="0 -0.0495 0" rpy="0 0 3.141592653589793"',
            'origin xyz="0 -0.0693 0" rpy="0 0 3.141592653589793"',
        )
    )
    longer = tmp_path / "kraby_long_femur.urdf"
    longer.write_text(drawn)
    common = ["--samples", "400", "--json"]
    asked = _json(capsys, ["workspace", "--urdf", KRABY, "--l2", "0.08", *common])["legs"]
    built = _json(capsys, ["workspace", "--urdf", str(longer), *common])["legs"]
    for name, leg in built.items():
        np.testing.assert_allclose(
            asked[name]["monte_carlo"]["lower_bound"], leg["monte_carlo"]["lower_bound"], atol=1e-12
        )
        np.testing.assert_allclose(
            asked[name]["monte_carlo"]["upper_bound"], leg["monte_carlo"]["upper_bound"], atol=1e-12
        )
        assert asked[name]["area"]["improved"] == pytest.approx(2 * math.pi * 0.08 * 0.088 / 3)
    # and its general legs are the same legs in closed form
    theta = np.random.default_rng(3).uniform(-1, 1, (20, 3))
    original, redrawn = import_robot(KRABY), import_robot(longer)
    for a, b in zip(original.legs, redrawn.legs, strict=True):
        changed = a.reading.geometry.with_lengths(femur=0.08)
        np.testing.assert_allclose(
            foot_position(changed, theta), foot_position(b.reading.geometry, theta), atol=1e-12
        )
        assert a.reading.joint_map.signs == b.reading.joint_map.signs
        np.testing.assert_allclose(a.reading.joint_map.offsets, b.reading.joint_map.offsets)
