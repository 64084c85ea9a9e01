"""The report's "Simulated walk" part: only with --simulate, its table, still and JSON."""

from __future__ import annotations

import os
import sys

import numpy as np
import pytest

from hexaleg import HexapodModel
from hexaleg.exceptions import HexalegError
from hexaleg.output.report import PARTS, ReportData, ReportOptions, build_report
from hexaleg.output.report.document import Figure
from hexaleg.output.report.part import numbered
from hexaleg.output.report.registry import parts_for
from hexaleg.robot.robot import Robot

if not os.environ.get("CI"):  # CI installs hexaleg[test], which includes the sim extra
    pytest.importorskip("mujoco")

from test_sim_simulate import JSON_KEYS

from hexaleg.output.report import simulation, walking
from hexaleg.sim.video import RenderOutcome


@pytest.fixture(scope="module")
def data(default_design):
    options = ReportOptions(simulate=True, vector_figures=True, progress=False)
    parts = parts_for(Robot.build(over=default_design), options)
    base = ReportData(default_design, options, HexapodModel(default_design), parts=parts)
    return base.with_record(simulation.compute(base))


def test_the_part_comes_after_walking_only_when_asked(default_design):
    robot = Robot.build(over=default_design)
    plain = parts_for(robot, ReportOptions())
    assert simulation.PART in PARTS and simulation.PART not in plain
    asked = parts_for(robot, ReportOptions(simulate=True))
    after = plain.index(walking.PART) + 1
    assert asked == (*plain[:after], simulation.PART, *plain[after:])


def test_section_sets_the_walk_beside_the_plan_and_the_feet_beside_the_statics(data):
    record = data[simulation.SimulationRecord]
    result, torque = record.result, record.torque
    assert (result.controller, torque.controller) == ("servo", "torque")
    section = numbered(data, simulation.PART)
    assert section.title.startswith("3.5 Simulated walk")
    text = "\n".join(b for b in section.blocks if isinstance(b, str))
    assert "| quantity | servos | torque control | planned |" in text
    for walk in (result, torque):
        metrics = walk.metrics
        assert f"{metrics.distance:.3f} ({100 * metrics.distance_ratio:.1f} %)" in text
        assert f"| {metrics.internal_force:.1f} |" in text
    assert f"| {result.metrics.planned_distance:.3f} |" in text
    for leg in ("lf", "rm", "lr"):
        statics = result.standing.statics_foot_forces_z[leg]
        assert f"| {leg} | {result.standing.foot_forces_z[leg]:.1f} | {statics:.1f} |" in text
    for joint in ("root", "hip", "knee"):
        assert f"{result.planned_peak_torque[joint]:.1f}" in text
    figures = [b for b in section.blocks if isinstance(b, Figure)]
    assert [f.name for f in figures] == [simulation.STILL]


def test_json_is_the_simulate_commands_without_the_design(data):
    fields = simulation.to_json(data[simulation.SimulationRecord])
    assert set(fields) == {"simulation"} and set(fields["simulation"]) == {"servo", "torque"}
    for controller, walk in fields["simulation"].items():
        assert set(walk) == JSON_KEYS - {"design"} and walk["controller"] == controller


def test_the_motor_sizing_says_which_controller_it_holds_for_and_shows_both(data, tmp_path):
    from hexaleg.design_file import load_design
    from hexaleg.output.report import motors, yours

    path = tmp_path / "motors.toml"  # catalog motors on every joint (the walks: the default's)
    path.write_text("".join(f'[actuators.{j}]\ncatalog = "hd_cha_25a_100"\n'
                            for j in ("root", "hip", "knee")))  # fmt: skip
    design = load_design(path)
    mine = ReportData(design, data.options, HexapodModel(design), parts=data.parts)
    record = data[simulation.SimulationRecord]
    mine = mine.with_record(record).with_record(yours.compute(mine))  # its one evaluation
    mine = mine.with_record(motors.compute(mine))
    text = "\n".join(b for b in motors.section(mine).blocks if isinstance(b, str))
    assert "what a torque-controlled robot needs" in text and "stiff" in text
    assert "| joint | plan (the sizing) | servos | torque control |" in text
    for joint in ("root", "hip", "knee"):
        servo, torque = (w.metrics.peak_torque[joint] for w in record.walks.values())
        assert f"| {servo:.3g} | {torque:.3g} |" in text


def _picture(path) -> np.ndarray:
    from PIL import Image

    with Image.open(path) as image:
        return np.asarray(image.convert("RGB"), dtype=float)


@pytest.mark.slow
def test_the_still_is_mujocos_picture_as_png_and_svg(data, tmp_path):
    simulation.write_files(data, tmp_path)
    png, svg = tmp_path / f"{simulation.STILL}.png", tmp_path / f"{simulation.STILL}.svg"
    assert png.is_file() and svg.is_file()
    assert _picture(png).std() > 10.0  # a picture, not a blank page
    assert "<image" in svg.read_text()  # MuJoCo's render, embedded


def test_without_offscreen_opengl_the_still_is_drawn_as_lines(data, tmp_path, monkeypatch):
    monkeypatch.setattr(
        simulation, "write_still", lambda *args: RenderOutcome(None, None, ("egl",))
    )
    simulation.write_files(data, tmp_path)
    svg = (tmp_path / f"{simulation.STILL}.svg").read_text()
    assert "<image" not in svg and "<path" in svg  # lines, not a picture
    assert _picture(tmp_path / f"{simulation.STILL}.png").std() > 10.0


def test_missing_mujoco_fails_before_any_work(tmp_path, monkeypatch, capsys):
    from conftest import run_cli

    monkeypatch.setitem(sys.modules, "mujoco", None)  # import mujoco fails
    with pytest.raises(HexalegError, match=r"pip install 'hexaleg\[sim\]'"):
        build_report(tmp_path / "r", options=ReportOptions(simulate=True))
    assert run_cli(["report", "--simulate", "-o", str(tmp_path / "r")]) == 2
    assert capsys.readouterr().err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []
