"""``hexaleg gait`` and what it writes; ``loads``'s over-rating flags; the study's columns."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest
from conftest import run_cli
from robots import KINDS, robot_argv

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.cause import Cause
from hexaleg.evaluation.metrics import METRICS
from hexaleg.gait import Gait, analyze_gait
from hexaleg.gait.analysis import STUDY_GAIT
from hexaleg.statics import Payload, analyze_loads
from hexaleg.statics.ground import Ground
from hexaleg.study.rows import design_walking_row

GAIT_FIELDS = {
    "design",
    "gait",
    "payload",
    "mass",
    "peak_torque",
    "rms_torque",
    "peak_speed",
    "peak_power",
    "positive_work",
    "mechanical_cost_of_transport",
    "electrical",
    "battery",
    "min_zmp_margin",
    "feasible",
    "violations",
    "tipping",
    "max_stride",
    "max_speed",
}
"""The JSON fields the gait command documents."""


SMALL = ["--stride", "0.03", "--step-height", "0.02", "--period", "0.8", "--samples", "60"]
"""A gait a small robot file walks: short strides, a low step."""

WALKED = {"template": ["--samples", "24"], "kraby": [*robot_argv("kraby"), *SMALL]}
"""Each kind of robot (:data:`robots.KINDS`) and a gait it walks."""


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_gait_json_has_the_documented_fields(capsys, kind):
    assert run_cli(["gait", *WALKED[kind], "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert GAIT_FIELDS <= set(data)
    assert set(data["gait"]) == {
        "pattern", "duty_factor", "period", "stride", "step_height", "heading", "speed",
        "samples",
    }  # fmt: skip
    assert set(data["payload"]) == {"mass", "position"}
    for key in ("peak_torque", "rms_torque", "peak_speed", "peak_power"):
        assert set(data[key]) == {"root", "hip", "knee"}
    assert set(data["max_speed"]) == {"value", "limited_by"}
    assert data["max_speed"]["limited_by"]["kind"] in ("torque", "speed")
    assert data["feasible"] is True and data["violations"] == [] and data["over_rating"] == []
    assert data["tipping"] is None
    gait = data["gait"]
    assert gait["speed"] == pytest.approx(gait["stride"] / (gait["duty_factor"] * gait["period"]))


def test_speed_sets_the_period_and_over_ratings_are_flagged(capsys):
    argv = ["gait", "--samples", "24", "--stride", "0.4", "--speed", "0.8", "--payload", "40"]
    assert run_cli([*argv, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["gait"]["period"] == pytest.approx(0.4 / (0.5 * 0.8))
    over = {(o["leg"], o["joint"], o["quantity"]) for o in data["over_rating"]}
    assert ("lm", "hip", "torque") in over and any(q == "speed" for *_, q in over)
    for entry in data["over_rating"]:
        assert entry["peak"] > entry["rated"]
    assert run_cli(argv) == 0
    text = capsys.readouterr().out
    assert "OVER RATING" in text and "lm hip torque" in text


def test_gait_writes_its_time_series(tmp_path, capsys):
    csv = tmp_path / "walk.csv"
    argv = ["gait", "--samples", "30", "--pattern", "tetrapod", "--csv", str(csv)]
    assert run_cli(argv) == 0
    table = pd.read_csv(csv)
    assert len(table) == 30 and table["t"].iloc[1] == pytest.approx(2.0 / 30)
    assert {"lf_hip_q", "lf_hip_qd", "lf_hip_qdd", "lf_hip_tau", "rr_fz", "rm_stance"} <= set(table)
    legs = ("lf", "lm", "lr", "rf", "rm", "rr")
    assert (table[[f"{leg}_stance" for leg in legs]].sum(axis=1) == 4).all()
    assert "wrote" in capsys.readouterr().err


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_gait_table_names_the_robot_and_its_max_stride(capsys, kind):
    assert run_cli(["gait", *WALKED[kind]]) == 0
    out = capsys.readouterr().out
    title = out.splitlines()[0]
    assert title.startswith("Walking") and ("kraby" in title) == (kind == "kraby")
    assert "max stride" in out and "feasible" in out


STEP = {"template": "0.1", "kraby": "0.02"}
"""A step height each kind of robot walks at some stride [m]."""


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_a_stride_beyond_the_max_is_refused_at_the_max_the_robot_walks(capsys, tmp_path, kind):
    robot = [*robot_argv(kind), "--step-height", STEP[kind]]
    csv = tmp_path / "gait.csv"
    assert run_cli(["gait", *robot, "--stride", "5", "--csv", str(csv), "--json"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and not csv.exists()
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "--stride = 5 is not valid" in lines[0], err
    assert "max stride" in lines[0]
    # the oracle: that max stride is one the robot walks, a little more one it does not
    # (with motors that carry any load: the max stride is the legs' reach, not the motors')
    limit = float(lines[0].split("must be at most ")[1].split()[0])
    strong = ["--rated-torques", "1e4", "1e4", "1e4", "--rated-speeds", "1e3", "1e3", "1e3"]
    small = [*robot, *strong, "--samples", "60", "--json"]
    assert run_cli(["gait", *small, "--stride", str(0.99 * limit)]) == 0
    assert json.loads(capsys.readouterr().out)["feasible"]
    assert run_cli(["gait", *small, "--stride", str(1.01 * limit)]) == 2


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_gait_writes_its_figures(tmp_path, kind):
    plots = tmp_path / "plots"
    assert run_cli(["gait", *WALKED[kind], "--plot", str(plots)]) == 0
    for name in ("gait_joints.png", "gait_feet.png"):
        assert (plots / name).stat().st_size > 20_000


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--period", "0"], "period = 0 is not valid: must lie in [0.05, 1000] [s]"),
        (["--stride", "nan"], "stride = nan is not valid: must be finite"),
        (["--speed", "1", "--period", "2"], "--speed sets the period"),
        (["--pattern", "gallop"], "invalid choice: 'gallop'"),
        (["--samples", "3"], "3 is not valid: must be in 12..100000"),
        (["--payload", "-1"], "payload mass = -1 is not valid"),
        (["--stride", "0.9", "--json"], "stride = 0.9 is not valid: must be at most 0.61"),
        (["--step-height", "2"], "this design cannot walk the gait: t = "),
    ],
)
def test_bad_gait_options_are_one_line_and_write_nothing(tmp_path, capsys, argv, message):
    csv = tmp_path / "walk.csv"
    assert run_cli(["gait", *argv, "--csv", str(csv)]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1 and "Traceback" not in err
    assert not csv.exists()


def test_an_infeasible_gait_says_what_breaks_first(hexapod_model):
    analysis = analyze_gait(hexapod_model.design, Gait(stride=0.9, samples=24), model=hexapod_model)
    assert not analysis.feasible and str(analysis.violations[0]).startswith("t = ")
    assert analysis.max_stride is not None and analysis.max_stride.value < 0.9


def test_gait_help_lists_the_options(capsys):
    assert run_cli(["gait", "--help"]) == 0
    out = capsys.readouterr().out
    for flag in ("--pattern", "--period", "--stride", "--step-height", "--heading", "--speed",
                 "--samples", "--payload", "--payload-at", "--friction", "--distribution",
                 "--json", "--csv", "--plot", "--html"):  # fmt: skip
        assert flag in out


def test_loads_flags_every_joint_over_its_rating(capsys):
    design = HexapodDesign()
    analysis = analyze_loads(design, Payload(200.0))
    over = analysis.over_rating
    torques = [analysis.nominal, *(e.state for e in analysis.extremes)]
    expected = {
        (leg, joint)
        for state in torques
        for i, leg in enumerate(state.legs)
        for j, joint in enumerate(("root", "hip", "knee"))
        if abs(state.joint_torques[i, j]) > design.rated_torques[j]
    }
    assert {(o.leg, o.joint) for o in over} == expected and expected
    for o in over:  # the peak is the largest |τ| of that joint anywhere
        i = analysis.nominal.legs.index(o.leg)
        j = ("root", "hip", "knee").index(o.joint)
        assert o.peak == max(abs(s.joint_torques[i, j]) for s in torques)
    assert run_cli(["loads", "--payload", "200", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["over_rating"]) == len(over)
    assert data["payload_capacity"]["limited_by"]["kind"] == "torque"
    assert data["slopes"][0]["limited_by"]["description"] in ("tip", "slide")
    assert run_cli(["loads"]) == 0
    assert "OVER RATING" not in capsys.readouterr().out


def test_causes_of_every_kind_read_as_one_line():
    assert str(Cause("torque", "rm", "hip")) == "rm hip torque at its rating"
    assert str(Cause("speed", "lf", "knee")) == "lf knee speed at its rating"
    assert str(Cause("ground", "lr")) == "lr knee touches the ground"
    assert str(Cause("ground")) == "body touches the ground"
    for kind in ("tip", "slide", "stability", "search limit"):
        assert str(Cause(kind)) == kind  # type: ignore[arg-type]
    assert Cause("torque", "rm", "hip").to_dict()["description"] == "rm hip torque at its rating"


def test_the_study_columns_are_the_single_design_numbers(hexapod_model):
    design = HexapodDesign.from_ratios(0.15, 0.45)
    model = hexapod_model.with_design(design)
    row = design_walking_row(design, model)
    columns = row.to_dict()  # the study table's row
    single = analyze_gait(design, STUDY_GAIT, model=HexapodModel(design))
    assert columns["gait_feasible"] is True
    assert columns["gait_peak_hip_torque"] == pytest.approx(single.metrics.peak_torque["hip"])
    assert columns["gait_peak_torque"] == pytest.approx(max(single.metrics.peak_torque.values()))
    assert row.metrics.mechanical_cost_of_transport == pytest.approx(
        single.metrics.cost_of_transport
    )
    assert single.max_speed is not None
    assert row.metrics.max_speed == pytest.approx(single.max_speed.value)
    infeasible = HexapodDesign.from_ratios(0.2, 0.75)
    row = design_walking_row(infeasible, hexapod_model.with_design(infeasible))
    assert row.columns["gait_feasible"] is False
    assert math.isnan(row.metrics.value(METRICS.mechanical_cost_of_transport))
    assert row.metrics.max_speed == 0.0


def test_a_min_torque_gait_balances_and_respects_friction(hexapod_model):
    gait = Gait(samples=16)
    walked = analyze_gait(hexapod_model.design, gait, distribution="min-torque",
                          ground=Ground(friction=0.5), model=hexapod_model,
                          limits=False)  # fmt: skip
    norm = analyze_gait(hexapod_model.design, gait, model=hexapod_model, limits=False)
    standing = walked.foot_forces[walked.stance]
    assert (standing[:, 2] >= -1e-6).all()
    assert (np.abs(standing[:, :2]) <= 0.5 * standing[:, 2:3] + 1e-6).all()
    np.testing.assert_allclose(  # the same total push on the body: the same base rows
        walked.foot_forces.sum(axis=1), norm.foot_forces.sum(axis=1), atol=1e-6
    )
    ratio = np.abs(walked.joint_torques[walked.stance]) / np.array((60.0, 150.0, 120.0))
    ratio_norm = np.abs(norm.joint_torques[norm.stance]) / np.array((60.0, 150.0, 120.0))
    assert (ratio**2).sum() <= (ratio_norm**2).sum() + 1e-9


def test_a_study_row_whose_zmp_leaves_the_feet_is_not_gait_feasible(hexapod_model):
    from hexaleg.evaluation.evaluate import Conditions, evaluate
    from hexaleg.study.rows import WALKING_METRICS, study_row

    payload = Payload(30.0, (100.0, 100.0, 100.0))  # once "feasible yes" at a margin of −37 m
    conditions = Conditions(payload=payload, gait=STUDY_GAIT, keep=True)
    specs = (METRICS.fb, *WALKING_METRICS)
    found = evaluate(hexapod_model.design, specs, conditions, model=hexapod_model)
    assert found.gait is not None and found.gait.walkable and found.gait.min_zmp_margin < 0
    columns = study_row((0.2, 0.4), hexapod_model.design, found).to_dict()
    assert columns["gait_feasible"] is False  # ("walks": unloaded, it does)
    assert columns["max_speed"] == 0.0 and columns["max_speed_limited_by"] == (
        "ZMP leaves the support polygon"
    )
