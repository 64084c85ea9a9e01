"""The report: every section on a reduced sweep, the same numbers as the CLI, atomic output."""

from __future__ import annotations

import json
import re
import warnings
from dataclasses import replace

import pytest
from conftest import run_cli

from hexaleg import HexapodDesign
from hexaleg.cli import main
from hexaleg.design_file import load_design
from hexaleg.exceptions import HexalegError
from hexaleg.output.report import ReportOptions, build_report

REDUCED = ReportOptions(
    l3_points=10, sensitivity_points=4, workers=1, progress=False, vector_figures=False
)
SECTIONS = [
    "## Decision",
    "## Design",
    "## 1. Swing phase: workspace",
    "## 2. Manipulability",
    "**Table 6 reproduced**",
    "## 3. Body flexibility",
    "## 3.1 Design study",
    "## 3.2 Sensitivity",
    "## 3.3 Statics",
    "## 4. 3-D view",
    "## 5. Recommendation",
    "## 5.1 Pareto front",
]
FILES = [
    "report.md",
    "report.html",
    "report.json",
    "hexapod.urdf",
    "viewer.html",
    "table5.csv",
    "table6.csv",
    "average_manipulability.csv",
    "extremes.csv",
    "sensitivity.csv",
    "recommendation_scores.csv",
    "study/study.csv",
    "workspace_monte_carlo.png",
    "workspace_planar.png",
    "workspace_l1_series.png",
    "manipulability_surface.png",
    "manipulability_surfaces_table5.png",
    "manipulability_average_map.png",
    "flexibility_extremes.png",
    "flexibility_fb.png",
    "flexibility_ranges.png",
    "study_statics.png",
    "loads.png",
    "pareto_front.png",
    "pareto_front.csv",
    "viewer_still.png",
]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("report") / "out"
    data = build_report(out, options=REDUCED).to_dict()
    return out, data


@pytest.mark.slow  # the reduced report, computed once for these three
def test_report_has_every_section_and_file(report):
    out, _ = report
    text = (out / "report.md").read_text()
    for heading in SECTIONS:
        assert heading in text
    for name in FILES:
        assert (out / name).is_file(), name
    html = (out / "report.html").read_text()
    assert "<table>" in html and "workspace_planar.png" in html
    for image in [n for n in FILES if n.endswith(".png")]:
        assert f"]({image})" in text  # every figure is shown in the report
    assert "**misprinted**" in text  # Table 6 row 1, flagged rather than matched


@pytest.mark.slow  # the reduced report, computed once for these three
def test_report_numbers_equal_the_cli_json(report, capsys):
    _, data = report
    assert main(["workspace", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == data["workspace"]
    assert main(["manipulability", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == data["manipulability"]
    assert main(["flexibility", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == data["flexibility"]["axis"]
    assert main(["flexibility", "--mode", "free", "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == data["flexibility"]["free"]


@pytest.mark.slow  # the reduced report, computed once for these three
def test_report_json_equals_what_was_returned(report):
    out, data = report
    assert json.loads((out / "report.json").read_text())["recommendation"] == json.loads(
        json.dumps(data["recommendation"])
    )
    rec = data["recommendation"]
    assert rec["l1_ratio"] == pytest.approx(0.10)
    assert rec["l3_band"][0] <= rec["l3_ratio"] <= rec["l3_band"][1]
    assert sum(rec["lengths_m"]) == pytest.approx(1.0)


@pytest.mark.slow
def test_second_run_replaces_and_reproduces_the_numbers(tmp_path):
    out = tmp_path / "again"
    first = build_report(out, options=REDUCED).to_dict()
    # a file an earlier hexaleg wrote (its marker lists it) that this one no longer writes;
    # a file of the user's own is refused instead, never deleted (tests/test_folders.py)
    marker = json.loads((out / ".hexaleg.json").read_text())
    (out / ".hexaleg.json").write_text(
        json.dumps({**marker, "files": [*marker["files"], "stale.txt"]})
    )
    (out / "stale.txt").write_text("left over")
    second = build_report(out, options=REDUCED).to_dict()
    assert json.dumps(first, sort_keys=True) == json.dumps(second, sort_keys=True)
    assert not (out / "stale.txt").exists()  # nothing stale survives
    assert [p.name for p in tmp_path.iterdir()] == ["again"]  # no staging folders left


@pytest.mark.slow
@pytest.mark.parametrize(
    ("module", "name"),
    [
        ("hexaleg.output.report.sensitivity", "sensitivity_table"),  # while computing
        ("hexaleg.output.report.viewer", "write_static_html"),  # half-way through writing
    ],
)
def test_failed_run_leaves_the_previous_report(tmp_path, monkeypatch, module, name):
    import importlib

    out = tmp_path / "kept"
    build_report(out, options=REDUCED)
    before = (out / "report.json").read_text()

    def broken(*args, **kwargs):
        raise RuntimeError("simulated failure in the middle")

    monkeypatch.setattr(importlib.import_module(module), name, broken)
    with pytest.raises(RuntimeError, match="simulated"):
        build_report(out, options=REDUCED)
    assert (out / "report.json").read_text() == before
    assert [p.name for p in tmp_path.iterdir()] == ["kept"]


def test_refuses_a_folder_that_is_not_a_report(tmp_path, capsys):
    (tmp_path / "mine.txt").write_text("user data")
    with pytest.raises(HexalegError, match="not a hexaleg report"):
        build_report(tmp_path, options=REDUCED)
    assert main(["report", "-o", str(tmp_path), "--l3-points", "10"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "not a hexaleg report" in err
    assert [p.name for p in tmp_path.iterdir()] == ["mine.txt"]


def test_the_help_gives_the_tibia_ratios_the_report_accepts(capsys):
    assert run_cli(["report", "--help"]) == 0
    assert "10..1000" in " ".join(capsys.readouterr().out.split())


@pytest.mark.slow
def test_report_for_another_design(tmp_path):
    design = HexapodDesign.from_ratios(0.1, 0.45)
    data = build_report(tmp_path / "r", design, REDUCED).to_dict()
    assert data["design"]["l3"] == pytest.approx(0.45)
    assert "0.1, 0.45, 0.45" in (tmp_path / "r" / "report.md").read_text()


@pytest.mark.slow
def test_report_on_a_hexagonal_design_file_with_a_body_sweep(tmp_path):
    from hexaleg.cli import main
    from hexaleg.design_text import design_toml
    from hexaleg.stance import flexibility

    design = HexapodDesign(layout="hexagon", body_radius=0.35, l1=0.12, l2=0.45, l3=0.43)
    (tmp_path / "robot.toml").write_text(design_toml(design))
    argv = ["report", "-o", str(tmp_path / "r"), "--design", str(tmp_path / "robot.toml")]
    argv += ["--l3-points", "10", "--sensitivity-points", "4", "--workers", "1"]
    assert main([*argv, "--sweep", "body_radius=0.3:0.4:3"]) == 0
    data = json.loads((tmp_path / "r" / "report.json").read_text())
    assert data["design"]["layout"] == "hexagon"
    assert data["flexibility"]["axis"]["fb"] == pytest.approx(flexibility(design).fb, rel=1e-12)
    variants = {row["variant"] for row in data["sensitivity"]}
    assert variants == {f"body_radius = {r:g} m" for r in (0.3, 0.35, 0.4)}
    text = (tmp_path / "r" / "report.md").read_text()
    assert "cylinder of radius 0.35 m" in text and "body_radius from 0.3 to 0.4" in text


@pytest.mark.slow
def test_a_killed_report_leaves_no_staging_folder_behind(tmp_path):
    """kill -9 mid-report leaves its staging folder; the next run removes it."""
    import os

    from conftest import kill_hexaleg_when

    out = tmp_path / "r"

    def staging() -> list:
        return [p for p in tmp_path.iterdir() if p.name.startswith(".r.staging-")]

    def writing() -> bool:  # it has started writing its staging folder
        staged = staging()
        return bool(staged) and any(staged[0].iterdir())

    argv = ["report", "-o", str(out), "--l3-points", "40", "--workers", "1"]
    kill_hexaleg_when(argv, writing, "the report")
    assert not out.exists() and len(staging()) == 1
    build_report(out, options=REDUCED)
    assert [p.name for p in tmp_path.iterdir()] == ["r"]
    mask = os.umask(0)
    os.umask(mask)
    assert out.stat().st_mode & 0o777 == 0o777 & ~mask  # a normal folder, not mkdtemp's 0700


def _walking(design) -> float:
    from hexaleg import HexapodModel
    from hexaleg.gait.capacity import walking_payload_capacity

    return walking_payload_capacity(HexapodModel(design)).mass


@pytest.mark.slow  # the reduced report, computed once for these tests
def test_the_decision_comes_first_with_one_recommendation_scored_by_one_rule(report, capsys):
    import math

    from hexaleg.stance import flexibility
    from hexaleg.study.ranking import RANKING_RULE
    from hexaleg.swing.manipulability import average_manipulability, rectangular_and_improved

    out, data = report
    text = (out / "report.md").read_text()
    assert text.index("## Decision") < text.index("## Design") < text.index("## 5. Recommendation")
    decision_text = text.split("## Design")[0]
    assert decision_text.count("**Recommended:") == 1 and "Pareto recommendation" not in text
    assert RANKING_RULE in decision_text
    design = HexapodDesign()
    decision, rec = data["decision"], data["recommendation"]
    yours = decision["yours"]["metrics"]
    # independent oracles: eq 16, the w_A kernel on the improved domain, axis-locked FB,
    # the walking payload capacity (held against a bisection on analyze_gait in
    # test_gait_capacity)
    assert yours["improved_area"] == pytest.approx(2 * math.pi * 0.4 * 0.4 / 3, rel=1e-12)
    improved = rectangular_and_improved(design.manipulability_limits)[1]
    assert yours["average_manipulability"] == pytest.approx(
        float(average_manipulability(design.lengths, improved)), rel=1e-12
    )
    assert yours["fb"] == pytest.approx(flexibility(design, "axis").fb, rel=1e-12)
    assert yours["walking_payload_capacity"] == pytest.approx(_walking(design), rel=1e-9)
    assert decision["yours"]["score"] == 1.0
    # three columns: yours as posed, your lengths re-posed, the recommended leg at its posture
    reposed, recommended = decision["reposed"], decision["recommended"]
    assert reposed["lengths_m"] == pytest.approx(list(design.lengths), abs=1e-12)
    assert rec["reference_best"]["score"] >= 1.0  # your posture is a candidate
    assert rec["reference_best"]["score"] == pytest.approx(reposed["score"], rel=1e-12)
    assert rec["reference_best"]["nominal_angles"] == reposed["nominal_angles"]
    assert rec["nominal_angles"] == recommended["nominal_angles"]
    for leg in (decision["yours"], reposed, recommended):
        lengths, angles = leg["lengths_m"], leg["nominal_angles"]
        theirs = HexapodDesign(*lengths, nominal_angles=tuple(angles))
        metrics = {
            "improved_area": 2 * math.pi * lengths[1] * lengths[2] / 3,
            "average_manipulability": float(average_manipulability(theirs.lengths, improved)),
        }
        for name, value in metrics.items():
            assert leg["metrics"][name] == pytest.approx(value, rel=1e-9), name
        # oracle: the CLI at those lengths and that posture
        argv = ["--l1", str(lengths[0]), "--l2", str(lengths[1]), "--l3", str(lengths[2]),
                "--nominal-angles", *map(str, angles), "--json"]  # fmt: skip
        assert main(["flexibility", *argv]) == 0
        assert leg["metrics"]["fb"] == pytest.approx(json.loads(capsys.readouterr().out)["fb"])
        assert main(["gait", *argv]) == 0
        walked = json.loads(capsys.readouterr().out)
        assert walked["feasible"] and not walked["over_rating"]  # each walks: the constraint
        assert leg["metrics"]["min_zmp_margin"] == pytest.approx(walked["min_zmp_margin"])
        for joint, value in walked["peak_torque"].items():
            assert leg["metrics"][f"gait_peak_{joint}_torque"] == pytest.approx(value)
        by_hand = math.prod(leg["metrics"][k] / yours[k] for k in decision["metrics"]) ** (1 / 3)
        assert leg["score"] == pytest.approx(by_hand, rel=1e-9)  # the stated rule
    assert recommended["score"] == pytest.approx(rec["score"], rel=1e-12)
    assert recommended["score"] >= reposed["score"] >= 1.0
    band = rec["l3_band"]
    assert band[0] <= rec["l3_ratio"] <= band[1]
    for cliff in rec["cliffs"]:  # the band keeps its distance from every cliff
        assert min(abs(cliff["l3_ratio"] - b) for b in band) >= rec["cliff_margin"] - 1e-12
    # the Pareto front is ranked by the same rule (at your posture)
    first = data["pareto_front"][0]
    assert first["score"] == pytest.approx(
        math.prod(first[k] / yours[k] for k in decision["metrics"]) ** (1 / 3), rel=1e-12
    )


@pytest.mark.slow
def test_a_fixed_coxa_moves_the_recommendation(tmp_path):
    design = HexapodDesign(l1=0.15, l2=0.6, l3=0.45, body_length=1.4, body_width=0.8)
    free = build_report(tmp_path / "free", design, REDUCED).to_dict()["recommendation"]
    options = replace(REDUCED, l1_ratios=(0.125,))  # the user's own coxa: 0.15 m of 1.2 m
    fixed = build_report(tmp_path / "fixed", design, options).to_dict()["recommendation"]
    assert free["l1_ratio"] != pytest.approx(0.125)  # so the fixed coxa is a constraint
    assert fixed["l1_ratio"] == pytest.approx(0.125)
    assert sum(fixed["lengths_m"]) == pytest.approx(1.2)
    assert fixed["l3_ratio"] != pytest.approx(free["l3_ratio"], abs=1e-4)
    # the sensitivity variants are relative to the user's body, not absolute sizes
    import pandas as pd

    variants = pd.read_csv(tmp_path / "fixed" / "sensitivity.csv")
    names = list(dict.fromkeys(variants["variant"]))
    assert names[0] == "your design" and "body 20 % wider (0.96 m)" in names
    peak = variants.groupby("variant", sort=False)["peak_fb"].first()
    assert peak["body 20 % wider (0.96 m)"] != pytest.approx(peak["your design"])


@pytest.mark.parametrize("points", [2, 9])
def test_grids_too_coarse_to_locate_the_peaks_are_refused(tmp_path, capsys, points):
    with pytest.raises(HexalegError, match="too coarse"):
        ReportOptions(l3_points=points)
    assert run_cli(["report", "--l3-points", str(points), "-o", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err  # the option's range, as --help gives it
    assert err.count("\n") == 1 and f"{points} is not valid: must be in 10..1000" in err
    assert list(tmp_path.iterdir()) == []


def _figure_texts(path) -> list[str]:
    from PIL import Image

    from hexaleg.output.figures.canvas import TEXTS_KEY

    with Image.open(path) as image:
        return json.loads(image.text[TEXTS_KEY])


def _numbers(text: str) -> list[float]:
    return [float(n) for n in re.findall(r"-?\d+\.\d+|-?\d+", text)]


def _table(text: str, header: str) -> dict[str, list[str]]:
    """The markdown table whose header line starts with ``header``: its rows by first cell."""
    lines = text[text.index(header) :].splitlines()[2:]
    rows = [line.strip("|").split(" | ") for line in lines[: lines.index("")]]
    return {row[0].strip(): [cell.strip() for cell in row[1:]] for row in rows}


def _reads_as(printed: str, value: float) -> bool:
    """``printed`` is ``value`` to the digits printed (rounded half either way)."""
    decimals = len(printed.split(".")[1]) if "." in printed else 0
    return abs(float(printed) - value) <= 0.5 * 10.0**-decimals * (1 + 1e-9)


@pytest.mark.slow  # the reduced report, computed once for these tests
def test_every_number_reads_the_same_in_the_report_its_json_and_its_figures(report):
    """The peaks, the recommendation and the scored metrics: report.md, report.json and the
    figures' own texts (the PNG records them) agree to the digits each prints."""
    out, _ = report
    text = (out / "report.md").read_text()
    saved = json.loads((out / "report.json").read_text())
    rec = saved["recommendation"]
    # the recommendation: every sentence that states it, in the Decision and in section 5
    stated = re.findall(r"Recommended: l1 : l2 : l3 = (\S+) : (\S+) : (\S+)\*\*", text)
    assert len(stated) == 2
    for ratios in stated:
        for printed, value in zip(ratios, (rec[f"l{k}_ratio"] for k in (1, 2, 3)), strict=True):
            assert _reads_as(printed, value), (printed, value)
    bands = re.findall(r"any tibia ratio in (\d\.\d+)–(\d\.\d+)", text, re.I)
    assert len(bands) == 2
    for band in bands:
        assert all(_reads_as(p, v) for p, v in zip(band, rec["l3_band"], strict=True))
    # the scored metrics: the Decision table's yours and recommended columns
    decision = saved["decision"]
    rows = dict(
        re.findall(r"^\| ([^|]+?) \| (\S+ \| \S+ \| \S+) \|", text.split("## Design")[0], re.M)
    )
    from hexaleg.evaluation.metrics import METRICS

    for name in decision["metrics"]:
        spec = METRICS.named(name)
        yours, reposed, theirs = rows[spec.described].split(" | ")
        assert _reads_as(yours, decision["yours"]["metrics"][name]), (name, yours)
        assert _reads_as(reposed, decision["reposed"]["metrics"][name]), (name, reposed)
        assert _reads_as(theirs, decision["recommended"]["metrics"][name]), (name, theirs)
        assert decision["recommended"]["metrics"][name] == pytest.approx(rec["metrics"][name])
    # the w_A peaks: the table of section 2 and the figure's legend
    legend = " ".join(_figure_texts(out / "manipulability_average_map.png"))
    for peak in saved["average_manipulability_peaks"]:
        r1 = f"{peak['l1_ratio']:.2f}"
        row = _table(text, "| l1 ratio | w_A refined peak")[r1]
        assert _reads_as(row[0], peak["rectangular_peak_l3_ratio"])
        assert _reads_as(row[1], peak["improved_peak_l3_ratio"])
        shown = re.findall(rf"coxa ratio {r1}: refined peak at (\d\.\d+)", legend)
        assert sorted(shown) == sorted(row)  # one curve per domain, the table's two peaks
    # the FB grid peaks: the table of section 3.1 and the figure's annotations
    marked = _figure_texts(out / "flexibility_fb.png")
    for peak in saved["study_peaks"]:
        r1 = f"{peak['l1_ratio']:.2f}"
        row = _table(text, "| l1 ratio | FB peak l3 ratio")[r1]
        assert _reads_as(row[0], peak["peak_l3_ratio"]) and _reads_as(row[1], peak["peak_fb"])
        assert row[0] in marked
    # the Pareto front's first: its sentence, its table's first row and the star's label
    first = saved["pareto_front"][0]
    (sentence,) = re.findall(r"so its first, l1 : l2 : l3 = (\S+) : (\S+) : (\S+), is", text)
    assert _reads_as(sentence[2], first["l3_ratio"])
    star = [t for t in _figure_texts(out / "pareto_front.png") if "front's best grid point" in t]
    assert len(star) == 1 and f"tibia {sentence[2]}" in star[0]


@pytest.mark.slow
def test_a_design_s_gait_is_what_the_whole_report_walks(tmp_path):
    from hexaleg import analyze_gait
    from hexaleg.gait.capacity import walking_payload_capacity
    from hexaleg.gait.spec import Gait
    from hexaleg.robot.model import HexapodModel

    gait = Gait(step_height=0.08).with_speed(0.2)
    motors = tmp_path / "motors.toml"
    motors.write_text(
        '[actuators.root]\ncatalog = "hd_cha_17a_e_100"\n[actuators.hip]\ncatalog = '
        '"hd_cha_25a_100"\n[actuators.knee]\ncatalog = "hd_cha_20a_100"\n'
        "[battery]\ncapacity = 20\nspecific_energy = 200\nvoltage = 680\n"  # one bus
    )
    design = load_design(motors)
    options = replace(REDUCED, l1_ratios=(0.1,), gait=gait)
    with warnings.catch_warnings():  # legs that cannot walk it: no numeric warning for a user
        warnings.simplefilter("error", RuntimeWarning)
        data = build_report(tmp_path / "r", design, options).to_dict()
    text = (tmp_path / "r" / "report.md").read_text()
    assert "the default gait" not in text and text.count("the design's gait") >= 4
    recommended = data["decision"]["recommended"]
    angles = tuple(recommended["nominal_angles"])  # the recommended leg at its posture
    theirs = replace(
        design.with_ratios(data["recommendation"]["l1_ratio"], data["recommendation"]["l3_ratio"]),
        nominal_angles=angles,
    )
    capacity = walking_payload_capacity(HexapodModel(theirs), gait).mass
    assert recommended["metrics"]["walking_payload_capacity"] == pytest.approx(capacity, 1e-9)
    mine = walking_payload_capacity(HexapodModel(design), gait).mass
    assert data["decision"]["yours"]["metrics"]["walking_payload_capacity"] == pytest.approx(
        mine, 1e-9
    )
    default = walking_payload_capacity(HexapodModel(theirs)).mass  # walking the default gait
    assert capacity != pytest.approx(default, rel=1e-3)  # the gait matters
    for leg, column in ((design, "yours"), (theirs, "recommended")):  # what the choice costs
        walked = analyze_gait(leg, gait, limits=False, speed=True)
        found = data["decision"][column]["metrics"]
        assert found["max_speed"] == pytest.approx(walked.max_speed.value, rel=1e-9)
        assert found["gait_peak_hip_torque"] == pytest.approx(walked.metrics.peak_torque["hip"])
        assert found["energy_per_km"] == pytest.approx(walked.electrical.energy_per_km, 1e-9)
    band = data["recommendation"]["l3_band"]
    for end in band:
        leg = replace(design.with_ratios(0.1, end), nominal_angles=angles)
        walked = analyze_gait(leg, gait, limits=False)
        assert walked.feasible and not walked.over_rating and walked.min_zmp_margin > 0
