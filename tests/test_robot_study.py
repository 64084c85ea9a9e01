"""``study``, ``decide`` and ``report`` on a robot, held against the single-design path.

Oracles: each row, answer and report number is measured again here with the single-design
commands (``flexibility --urdf FILE --l1 .. --l2 .. --l3 .. --json``, ``loads --urdf ...
--json``), which resize the file and build its model on their own; the decision is also
held against a brute-force grid over the lengths computed here from the robot file with
:func:`~hexaleg.robot.resize.resize_robot`, the imported model and the single-design
analyses (axis-locked flexibility, the statics' payload capacity), not through the
study's or the search's code.
"""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from conftest import run_cli
from robots import KINDS, robot_argv, robot_of

from hexaleg.design import HexapodDesign
from hexaleg.robot.feet import FootSearch
from hexaleg.robot.imported import import_robot
from hexaleg.robot.imported_model import ImportedHexapodModel
from hexaleg.robot.resize import resize_robot
from hexaleg.stance.flexibility import flexibility
from hexaleg.statics.capacity import payload_capacity
from hexaleg.statics.forces import Statics

pytestmark = pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")

KRABY = str(Path(__file__).parent / "data" / "robots" / "kraby" / "hexapod.urdf")
GAIT = "[gait]\nstride = 0.03\nstep_height = 0.02\nperiod = 0.8\nsamples = 60\n"
"""A gait this small robot walks (the default gait's 10 cm step is beyond it)."""


def _json(capsys, argv: list[str]) -> dict:
    capsys.readouterr()
    assert run_cli(argv) == 0, capsys.readouterr().err
    return json.loads(capsys.readouterr().out)


def _gait_file(tmp_path: Path) -> str:
    path = tmp_path / "gait.toml"
    path.write_text(GAIT)
    return str(path)


def _lengths(values) -> list[str]:
    l1, l2, l3 = (repr(float(v)) for v in values)
    return ["--l1", l1, "--l2", l2, "--l3", l3]


def _single(capsys, lengths, gait: str, robot: list[str] | None = None) -> dict[str, float]:
    """FB, standing and walking payload capacity from the single-design commands."""
    robot = ["--urdf", KRABY] if robot is None else robot
    flex = _json(capsys, ["flexibility", *robot, *_lengths(lengths), "--json"])
    argv = ["loads", *robot, "--design", gait, *_lengths(lengths), "--json"]
    loads = _json(capsys, argv)
    return {
        "fb": flex["fb"],
        "payload_capacity": loads["payload_capacity"]["mass"],
        "walking_payload_capacity": loads["walking_payload_capacity"]["mass"],
    }


def _study(tmp_path: Path, name: str, argv: list[str]) -> pd.DataFrame:
    out = tmp_path / name
    base = ["study", *argv, "--l1-ratios", "0.2", "0.25", "--l3-points", "3"]
    assert run_cli([*base, "--workers", "2", "-o", str(out)]) == 0
    return pd.read_csv(out / "study.csv", keep_default_na=False, na_values=[""])


@pytest.mark.parametrize("kind", KINDS)
def test_every_study_row_equals_the_single_design_commands(tmp_path, capsys, kind):
    gait, argv = _gait_file(tmp_path), robot_argv(kind)
    table = _study(tmp_path, "study", [*argv, "--design", gait])
    total = robot_of(kind).design.leg_length  # the robot's own leg length
    measured = table[table["error"].isna()]
    assert len(measured) == 5  # 0.25 + 0.75 leaves no femur: that row is refused
    for row in measured.to_dict(orient="records"):
        lengths = (row["l1"], row["l2"], row["l3"])
        np.testing.assert_allclose(
            lengths,
            [row["l1_ratio"] * total, (1 - row["l1_ratio"] - row["l3_ratio"]) * total,
             row["l3_ratio"] * total],
            rtol=1e-12,
        )  # fmt: skip
        single = _single(capsys, lengths, gait, argv)
        for column, value in single.items():
            assert row[column] == pytest.approx(value, rel=1e-9, abs=1e-12), column
    assert (measured["walking_payload_capacity"] > 0).sum() >= 2  # the file's gait is walked


def test_a_study_of_an_imported_design_file_is_the_robot_files(tmp_path):
    gait = _gait_file(tmp_path)
    table = _study(tmp_path, "study", ["--urdf", KRABY, "--design", gait])
    # the same study from a design file written by `design import` (its [robot] table)
    target = tmp_path / "kraby.toml"
    assert run_cli(["design", "import", KRABY, "-o", str(target)]) == 0
    target.write_text(target.read_text() + "\n" + GAIT)
    again = _study(tmp_path, "again", ["--design", str(target)])
    columns = ["l1", "l2", "l3", "fb", "payload_capacity", "walking_payload_capacity"]
    pd.testing.assert_frame_equal(again[columns], table[columns])


def _grid_oracle(min_fb: float, points: int = 5) -> tuple[float, dict]:
    """The largest standing payload capacity on a grid of the search bounds with FB ≥ min_fb.

    Each grid point is the robot file resized here, its model built, its axis-locked FB
    and payload capacity measured by the single-design analyses; the leg length is at
    most the robot's own (decide's default requirement).
    """
    robot = import_robot(KRABY, foot=FootSearch())
    own = robot.legs[0].reading.geometry.lengths
    axes = [np.linspace(0.5 * length, 1.5 * length, points) for length in own]
    best, where = -math.inf, {}
    for lengths in itertools.product(*axes):
        if sum(lengths) > sum(own) + 1e-12:
            continue
        names = ("coxa", "femur", "tibia")
        changes = {leg: dict(zip(names, lengths, strict=True)) for leg in robot.leg_names}
        model = ImportedHexapodModel(resize_robot(robot, changes), HexapodDesign())
        fb = flexibility(model.design, "axis", "all", model).fb
        if fb < min_fb:
            continue
        statics = Statics(model, model.leg_names)
        capacity = payload_capacity(statics, model.nominal_configuration()).mass
        if capacity > best:
            best, where = capacity, {"lengths": lengths, "fb": fb}
    return best, where


@pytest.mark.parametrize("seed", [1, pytest.param(2, marks=pytest.mark.slow)])
def test_decide_meets_its_requirement_and_beats_a_brute_force_grid(tmp_path, capsys, seed):
    min_fb = float(np.random.default_rng(seed).uniform(0.25, 0.33))
    journal = tmp_path / "journal.jsonl"
    # the oracle's grid points lie off a millimetre's: Kraby's ~3 cm segments on 0.01 mm
    argv = ["decide", "--urdf", KRABY, "--min-fb", repr(min_fb), "--maximize",
            "payload_capacity", "--evaluations", "300", "--workers", "2", "--json",
            "--journal", str(journal), "--resolution", "1e-5"]  # fmt: skip
    answer = _json(capsys, argv)
    assert answer["feasible"] and answer["robot"] == KRABY
    robot = import_robot(KRABY, foot=FootSearch())
    own = robot.legs[0].reading.geometry.lengths
    free = answer["search"]["free"]
    for name, length in zip(("l1", "l2", "l3"), own, strict=True):  # centred on the robot's
        np.testing.assert_allclose(free[name], [0.5 * length, 1.5 * length], rtol=1e-12)
    assert answer["yours"]["design"]["l1"] == pytest.approx(own[0], rel=1e-12)
    best = answer["best"]["design"]
    lengths = (best["l1"], best["l2"], best["l3"])
    flex = _json(capsys, ["flexibility", "--urdf", KRABY, *_lengths(lengths), "--json"])
    loads = _json(capsys, ["loads", "--urdf", KRABY, *_lengths(lengths), "--json"])
    assert flex["fb"] >= min_fb  # the single-design command confirms the requirement
    assert sum(lengths) <= sum(own) + 1e-9
    capacity = loads["payload_capacity"]["mass"]
    assert answer["best"]["objective"]["value"] == pytest.approx(capacity, rel=1e-9)
    grid_best, where = _grid_oracle(min_fb)
    assert where, "the grid has a feasible point for these requirement values"
    assert capacity >= grid_best * (1 - 1e-9), (capacity, grid_best, where)


def test_report_numbers_equal_the_single_design_commands(tmp_path, capsys):
    gait = _gait_file(tmp_path)
    out = tmp_path / "report"
    argv = ["report", "--urdf", KRABY, "--design", gait, "--l1-ratios", "0.25",
            "--l3-points", "10", "--workers", "2", "-o", str(out)]  # fmt: skip
    assert run_cli(argv) == 0, capsys.readouterr().err
    report = json.loads((out / "report.json").read_text())
    robot = import_robot(KRABY, foot=FootSearch())
    own = robot.legs[0].reading.geometry.lengths
    single = _single(capsys, own, gait)
    metrics = report["robot"]["metrics"]
    for name, value in single.items():
        assert metrics[name] == pytest.approx(value, rel=1e-9), name
    assert report["flexibility"]["axis"]["fb"] == pytest.approx(single["fb"], rel=1e-9)
    capacity = report["loads"]["axis"]["payload_capacity"]["mass"]
    assert capacity == pytest.approx(single["payload_capacity"], rel=1e-9)
    walking = report["walking_payload_capacity"]["mass"]
    assert walking == pytest.approx(single["walking_payload_capacity"], rel=1e-9)
    assert report["study_yours"]["fb"] == pytest.approx(single["fb"], rel=1e-9)
    for command in ("workspace", "manipulability"):  # each leg's swing phase
        legs = _json(capsys, [command, "--urdf", KRABY, "--json"])["legs"]
        assert {name: leg[command] for name, leg in report["legs"].items()} == legs
    text = (out / "report.md").read_text()
    assert f"FB = {single['fb']:.4f}" in text
    assert "left out for an imported robot" in text and "Tables 5 and 6" in text
    rows = pd.read_csv(out / "study" / "study.csv")
    assert len(rows) == 10 and (out / "viewer.html").exists()


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["study", "--urdf", KRABY, "--sensitivity"], "--sensitivity and --sweep with --urdf"),
        (["decide", "--urdf", KRABY, "--free-posture"], "--free-posture with --urdf"),
        (["decide", "--urdf", KRABY, "--choose-actuators"], "--choose-actuators with --urdf"),
        (["decide", "--urdf", KRABY, "--free", "body_width=0.1:0.2"], "with --urdf, one of"),
        (["decide", "--urdf", KRABY, "--leg-length", "0.04"], "above 0.044 m"),
        (["report", "--urdf", KRABY, "--collisions"], "--collisions with --urdf"),
        (["report", "--urdf", KRABY, "--simulate"], "--simulate with --urdf"),
        (["report", "--urdf", "missing.urdf"], "no such file"),
    ],
)
def test_refusals_are_one_line_and_write_nothing(tmp_path, capsys, argv, expected):
    out = tmp_path / "out"
    command = argv[0]
    written = ["--journal", str(out)] if command == "decide" else ["-o", str(out)]
    assert run_cli([*argv, *written]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and expected in err, err
    assert not out.exists()


def test_decide_measures_segments_the_template_design_would_refuse(capsys):
    # tibias at most the robot's body height: hexaleg's template design refuses them (its
    # body would not clear the feet), the robot's own model stands on them
    argv = ["decide", "--urdf", KRABY, "--free", "l3=0.03:0.044", "--evaluations", "60",
            "--workers", "2", "--json"]  # fmt: skip
    answer = _json(capsys, argv)
    best = answer["best"]["design"]
    lengths = (best["l1"], best["l2"], best["l3"])
    assert answer["feasible"] and 0.03 <= lengths[2] <= 0.044
    with pytest.raises(Exception, match="feet must stand below"):
        HexapodDesign(l1=lengths[0], l2=lengths[1], l3=0.9 * lengths[2], body_height=0.088)
    flex = _json(capsys, ["flexibility", "--urdf", KRABY, *_lengths(lengths), "--json"])
    assert answer["best"]["objective"]["value"] == pytest.approx(flex["fb"], rel=1e-9)


@pytest.mark.slow  # a decision and a report on a robot file: 18 s
def test_decide_and_report_read_the_robot_from_an_imported_design_file(tmp_path, capsys):
    target = tmp_path / "kraby.toml"
    assert run_cli(["design", "import", KRABY, "-o", str(target)]) == 0
    search = ["--min-fb", "0.3", "--evaluations", "60", "--workers", "2", "--json"]
    direct = _json(capsys, ["decide", "--urdf", KRABY, *search])
    via_file = _json(capsys, ["decide", "--design", str(target), *search])
    lengths = [[answer["best"]["design"][n] for n in ("l1", "l2", "l3")]
               for answer in (via_file, direct)]  # fmt: skip
    assert lengths[0] == lengths[1]
    # the objective as the single-design command measures it through the same file (the
    # body box's height comes from the design the robot goes over: the file's or the default)
    argv = ["flexibility", "--design", str(target), *_lengths(lengths[0]), "--json"]
    fb = _json(capsys, argv)["fb"]
    assert via_file["best"]["objective"]["value"] == pytest.approx(fb, rel=1e-9)
    assert via_file["search"] == direct["search"]
    out = tmp_path / "report"
    argv = ["report", "--design", str(target), "--l1-ratios", "0.25", "--l3-points", "10",
            "--workers", "2", "-o", str(out)]  # fmt: skip
    assert run_cli(argv) == 0, capsys.readouterr().err
    report = json.loads((out / "report.json").read_text())
    assert report["flexibility"]["axis"]["fb"] == pytest.approx(
        direct["yours"]["objective"]["value"], rel=1e-9
    )


def _walking_grid(min_walking: float, gait, points: int = 4) -> float:
    """The largest FB on a grid of the bounds among legs carrying ``min_walking`` walking."""
    from hexaleg.gait.capacity import walking_payload_capacity

    robot = import_robot(KRABY, foot=FootSearch())
    own = robot.legs[0].reading.geometry.lengths
    axes = [np.linspace(0.5 * length, 1.5 * length, points) for length in own]
    best = -math.inf
    for lengths in itertools.product(*axes):
        if sum(lengths) > sum(own) + 1e-12:
            continue
        changes = {leg: dict(zip(("coxa", "femur", "tibia"), lengths, strict=True))
                   for leg in robot.leg_names}  # fmt: skip
        model = ImportedHexapodModel(resize_robot(robot, changes), HexapodDesign())
        if walking_payload_capacity(model, gait).mass < min_walking:
            continue
        best = max(best, flexibility(model.design, "axis", "all", model).fb)
    return best


@pytest.mark.slow  # about 5 s
def test_decide_with_a_walking_payload_meets_it_and_beats_a_grid(tmp_path, capsys):
    from hexaleg.gait.spec import Gait

    gait_file = _gait_file(tmp_path)
    required = float(np.random.default_rng(3).uniform(2.0, 3.0))
    argv = ["decide", "--urdf", KRABY, "--design", gait_file, "--walking-payload",
            repr(required), "--evaluations", "150", "--workers", "2", "--json"]  # fmt: skip
    answer = _json(capsys, argv)
    best = answer["best"]["design"]
    lengths = (best["l1"], best["l2"], best["l3"])
    single = _single(capsys, lengths, gait_file)
    assert answer["feasible"] and single["walking_payload_capacity"] >= required
    assert answer["best"]["objective"]["value"] == pytest.approx(single["fb"], rel=1e-9)
    gait = Gait(stride=0.03, step_height=0.02, period=0.8, samples=60)  # the file's [gait]
    grid = _walking_grid(required, gait)
    assert grid > -math.inf and single["fb"] >= grid * (1 - 1e-9), (single["fb"], grid)


def test_a_study_carries_the_robot_file_s_reading_options_to_its_workers(tmp_path, capsys):
    # a Xacro file without feet: the foot offset must reach every worker that reads it again
    ochs = str(Path(KRABY).parents[1] / "phantomx_kevinochs" / "urdf" / "phantomX_model.xacro")
    foot = ["--foot-offset", "0", "0.133", "0"]
    out = tmp_path / "study"
    argv = ["study", "--urdf", ochs, *foot, "--l1-ratios", "0.15", "--l3-points", "3",
            "--workers", "2", "-o", str(out)]  # fmt: skip
    assert run_cli(argv) == 0, capsys.readouterr().err
    table = pd.read_csv(out / "study.csv", keep_default_na=False, na_values=[""])
    measured = table[table["error"].isna()]
    assert len(measured) >= 2
    for row in measured.to_dict(orient="records"):
        lengths = _lengths((row["l1"], row["l2"], row["l3"]))
        flex = _json(capsys, ["flexibility", "--urdf", ochs, *foot, *lengths, "--json"])
        assert row["fb"] == pytest.approx(flex["fb"], rel=1e-9)


@pytest.mark.slow
def test_a_free_coupled_study_row_equals_the_single_design_command(tmp_path, capsys):
    out = tmp_path / "free"
    argv = ["study", "--urdf", KRABY, "--mode", "free", "--l1-ratios", "0.25",
            "--l3-points", "2", "--workers", "2", "-o", str(out)]  # fmt: skip
    assert run_cli(argv) == 0, capsys.readouterr().err
    rows = pd.read_csv(out / "study.csv", keep_default_na=False, na_values=[""])
    locked = _study(tmp_path, "locked", ["--urdf", KRABY])
    measured = [row for row in rows.to_dict(orient="records") if pd.isna(row["error"])]
    assert measured, rows["error"].tolist()
    for row in measured:
        lengths = (row["l1"], row["l2"], row["l3"])
        argv = ["flexibility", "--urdf", KRABY, *_lengths(lengths), "--mode", "free", "--json"]
        single = _json(capsys, argv)
        assert row["fb"] == pytest.approx(single["fb"], rel=1e-9)
        same = locked[np.isclose(locked["l3_ratio"], row["l3_ratio"])]
        same = same[np.isclose(same["l1_ratio"], row["l1_ratio"])]
        assert same.empty or row["fb"] >= float(same["fb"].iloc[0]) - 1e-9  # free ≥ locked
