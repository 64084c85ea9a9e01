"""A design file's ``[gait]`` table: the default gait of every command that walks.

Oracle: the ``gait`` command's own options (``--speed --step-height --stride``) on the
same design without the table; the table must give exactly their numbers.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from conftest import run_cli
from explorer import running

from hexaleg.cli.gait_options import gait_from_args
from hexaleg.cli.inputs import design_from_args, inputs_from_args
from hexaleg.cli.main import build_parser
from hexaleg.design import HexapodDesign
from hexaleg.design_file import GAIT, load_design, load_table
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError
from hexaleg.gait.capacity import walking_payload_capacity
from hexaleg.gait.spec import Gait
from hexaleg.output.report import motors as report_motors
from hexaleg.output.report import study as report_study
from hexaleg.output.report import yours as report_yours
from hexaleg.output.report.options import ReportOptions
from hexaleg.output.report.part import ReportData
from hexaleg.robot.model import HexapodModel

OPTIONS = ["--speed", "0.2", "--step-height", "0.05", "--stride", "0.25"]
MOTORS = ("hd_cha_17a_e_100", "hd_cha_25a_100", "hd_cha_20a_100")
"""Catalog actuators for root, hip and knee, strong enough for the table's gait."""
TABLE = "[gait]\nspeed = 0.2\nstep_height = 0.05\nstride = 0.25\n"


@pytest.fixture
def files(tmp_path):
    with_table, without = tmp_path / "walks.toml", tmp_path / "plain.toml"
    with_table.write_text("l3 = 0.35\n" + TABLE)
    without.write_text("l3 = 0.35\n")
    return with_table, without


def _json(capsys, argv):
    assert run_cli([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def load_gait(path):
    """The gait a design file's ``[gait]`` table describes."""
    return load_table(path, GAIT, Gait.from_table)


def _options_gait(argv):
    """The gait the ``gait`` command's options describe (the oracle)."""
    args = build_parser().parse_args(["gait", *argv])
    return gait_from_args(args, inputs_from_args(args).gait)


def test_the_table_reads_as_the_options_do(files):
    with_table, without = files
    assert load_gait(with_table) == _options_gait(["--design", str(without), *OPTIONS])
    assert load_gait(without) == Gait()


def test_gait_walks_the_table_as_the_options(files, capsys):
    with_table, without = files
    assert _json(capsys, ["gait", "--design", str(with_table)]) == _json(
        capsys, ["gait", "--design", str(without), *OPTIONS]
    )


def test_options_override_the_table(files):
    with_table, _ = files
    gait = _options_gait(["--design", str(with_table), "--step-height", "0.08"])
    assert gait == load_gait(with_table).replace(step_height=0.08)
    assert gait.stride == 0.25 and gait.period == pytest.approx(0.25 / (0.5 * 0.2))


def test_loads_walking_capacity_walks_the_table(files, capsys):
    with_table, without = files
    found = _json(capsys, ["loads", "--design", str(with_table)])["walking_payload_capacity"]
    args = build_parser().parse_args(["gait", "--design", str(without), *OPTIONS])
    model = HexapodModel(design_from_args(args))
    oracle = walking_payload_capacity(model, gait_from_args(args, Gait()))
    assert found == oracle.to_dict()
    default = _json(capsys, ["loads", "--design", str(without)])["walking_payload_capacity"]
    assert default != found  # the table changed what is computed


def test_requirements_walk_the_table_and_override_it(files):
    with_table, _ = files
    args = build_parser().parse_args(["decide", "--design", str(with_table)])
    requirements = inputs_from_args(args).requirements
    assert requirements.gait == load_gait(with_table)
    faster = Requirements(speed=0.3, step_height=0.07, walked=requirements.walked)
    assert faster.gait == Gait(stride=0.25, step_height=0.07).with_speed(0.3)


@pytest.mark.parametrize(
    ("table", "expected"),
    [
        ("step_hieght = 0.05", "unknown key 'gait.step_hieght': did you mean 'step_height'"),
        ("stride = -1", "gait.stride = -1 is not valid: must lie in [0.0001, 100]"),
        ("pattern = 'gallop'", "gait.pattern"),
        ("speed = 0.2\nperiod = 2", "gait.speed"),
        ("samples = 3", "gait.samples"),
    ],
)
@pytest.mark.parametrize("command", ["gait", "loads", "workspace"])
def test_a_bad_gait_table_is_refused_in_one_line(tmp_path, capsys, table, expected, command):
    path = tmp_path / "bad.toml"
    path.write_text(f"[gait]\n{table}\n")
    out = tmp_path / "out.csv"
    argv = [command, "--design", str(path)] + (["--csv", str(out)] if command == "gait" else [])
    assert run_cli(argv) == 2
    err = capsys.readouterr().err.strip()
    assert expected in err and "\n" not in err
    assert not out.exists()


def test_design_init_and_show_round_trip_the_table(files, tmp_path, capsys):
    with_table, without = files
    written = tmp_path / "again.toml"
    assert run_cli(["design", "init", str(written), "--design", str(with_table)]) == 0
    assert load_gait(written) == load_gait(with_table)
    shown = _json(capsys, ["design", "show", "--design", str(written)])
    assert shown["gait"] == _options_gait(["--design", str(without), *OPTIONS]).to_dict()
    plain = tmp_path / "plain_again.toml"
    assert run_cli(["design", "init", str(plain), "--design", str(without)]) == 0
    assert "[gait]" not in plain.read_text()
    assert "gait" not in _json(capsys, ["design", "show", "--design", str(plain)])


def _gait_json(capsys, design_file, design):
    """The ``gait`` command's numbers for ``design`` walking the options' gait (the oracle).

    None: the command refuses the gait (exit 2), the design cannot walk it.
    """
    lengths = ["--l1", repr(design.l1), "--l2", repr(design.l2), "--l3", repr(design.l3)]
    capsys.readouterr()
    code = run_cli(["gait", "--design", str(design_file), *lengths, *OPTIONS, "--json"])
    out = capsys.readouterr().out
    assert code in (0, 2)
    return json.loads(out) if code == 0 else None


def test_a_study_walks_the_table(files, tmp_path, capsys):
    with_table, without = files
    out = tmp_path / "study"
    argv = ["study", "--design", str(with_table), "--l1-ratios", "0.1", "--l3-points", "3"]
    assert run_cli([*argv, "--workers", "1", "-o", str(out)]) == 0
    table = pd.read_csv(out / "study.csv")
    base = HexapodDesign(l3=0.35)
    checked = 0
    for row in table.to_dict(orient="records"):
        design = base.with_ratios(row["l1_ratio"], row["l3_ratio"], base.leg_length)
        oracle = _gait_json(capsys, without, design)
        if oracle is None:
            assert not row["walks"]
            continue
        checked += 1
        for joint in ("root", "hip", "knee"):
            assert row[f"gait_peak_{joint}_torque"] == pytest.approx(
                oracle["peak_torque"][joint], rel=1e-9
            )
        assert row["max_speed"] == pytest.approx(oracle["max_speed"]["value"], rel=1e-9)
    assert checked >= 2
    plain = tmp_path / "plain"
    argv[2] = str(without)
    assert run_cli([*argv, "--workers", "1", "-o", str(plain)]) == 0
    default = pd.read_csv(plain / "study.csv")
    assert not np.allclose(default["gait_peak_hip_torque"], table["gait_peak_hip_torque"])


def test_the_report_walks_the_table(files, monkeypatch):
    with_table, _ = files
    asked = {}

    def stop(out, design, options):
        asked["options"] = options
        raise HexalegError("stopped before any work")

    monkeypatch.setattr("hexaleg.cli.report.build_report", stop)
    assert run_cli(["report", "--design", str(with_table), "-o", "unused"]) == 2
    options = asked["options"]
    assert options.gait == load_gait(with_table) != Gait()
    assert options.decision.gait == options.gait  # what the decision ranks by


def test_the_report_s_study_and_motors_walk_its_gait(files, capsys, tmp_path):
    """The report's parts, computed on their own: the study's rows and the motors' period."""
    with_table, without = files
    gait = load_gait(with_table)
    design = HexapodDesign(l3=0.35)
    options = ReportOptions(l3_points=10, workers=1, progress=False, l1_ratios=(0.1,), gait=gait)
    data = ReportData(design, options, HexapodModel(design))
    study = report_study.compute(data.with_record(report_yours.compute(data)))
    assert study.spec.walked == gait
    oracle = _gait_json(capsys, without, design)
    assert study.yours.metrics.gait_peak_hip_torque == pytest.approx(
        oracle["peak_torque"]["hip"], rel=1e-9
    )
    motors_file = tmp_path / "motors.toml"
    motors_file.write_text(
        "l3 = 0.35\n"
        + "".join(
            f'[actuators.{joint}]\ncatalog = "{name}"\n'
            for joint, name in zip(("root", "hip", "knee"), MOTORS, strict=True)
        )
        + "[battery]\ncapacity = 500\nspecific_energy = 200\nvoltage = 680\n"  # one bus
    )
    with_motors = load_design(motors_file)
    data = ReportData(with_motors, options, HexapodModel(with_motors))
    walked = report_motors.compute(data.with_record(report_yours.compute(data))).walked
    args = ["gait", "--design", str(motors_file), *OPTIONS]
    energy = _json(capsys, args)["electrical"]["energy_per_km"]
    assert walked.gait == gait and walked.electrical.energy_per_km == pytest.approx(energy, 1e-12)


def test_the_explorer_without_requirements_walks_the_table(files, capsys):
    with_table, _ = files
    loads = _json(capsys, ["loads", "--design", str(with_table)])
    with running("--design", str(with_table)) as server:
        status, got = server.get("api/evaluate")
    assert status == 200 and got["error"] == ""
    walking = loads["walking_payload_capacity"]["mass"]
    assert got["walking_payload_capacity"] == pytest.approx(walking, rel=1e-9)
