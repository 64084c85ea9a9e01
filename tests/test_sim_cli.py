"""``hexaleg simulate``: refusals before simulating, the JSON, the table, the animation."""

from __future__ import annotations

import json
import os
import time

import numpy as np
import pytest
from conftest import run_cli
from robots import KINDS, KRABY, robot_argv

from hexaleg import HexapodDesign

if not os.environ.get("CI"):  # CI installs hexaleg[test], which includes the sim extra
    pytest.importorskip("mujoco")

from test_sim_simulate import JSON_KEYS

from hexaleg.cli import simulate as command
from hexaleg.sim import simulate, simulate_gait


@pytest.fixture(scope="module")
def walked():
    return simulate_gait(HexapodDesign(), cycles=2)


def _never(*args, **kwargs):
    raise AssertionError("simulated although the input was refused")


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_an_over_long_stride_exits_2_in_one_line_before_simulating(monkeypatch, capsys, kind):
    monkeypatch.setattr(simulate, "run_plan", _never)
    assert run_cli(["simulate", *robot_argv(kind), "--step-height", "0.02", "--stride", "5"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert "stride = 5 is not valid" in err and "max stride" in err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--video", "walk.mp4"], "video = "),
        (["--html", "."], "is a folder"),
        (["--video", "nothere/"], "names a folder"),
        (["--cycles", "1"], "--cycles"),
        (["--friction", "-1"], "friction"),
        (["--payload", "-5"], "payload mass"),
    ],
)
def test_bad_options_are_refused_before_simulating(monkeypatch, tmp_path, capsys, argv, message):
    monkeypatch.setattr(simulate, "SimModel", _never)
    monkeypatch.setattr(simulate, "run_plan", _never)
    monkeypatch.chdir(tmp_path)
    assert run_cli(["simulate", *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_json_has_the_documented_fields(monkeypatch, capsys, walked, kind):
    monkeypatch.setattr(command, "simulate_gait", lambda *args, **kwargs: walked)
    assert run_cli(["simulate", *robot_argv(kind), "--json", "--cycles", "2"]) == 0
    fields = json.loads(capsys.readouterr().out)
    # a robot file's JSON also names it and gives its posture in both conventions
    posture = {"robot", "joint_angles", "urdf_joint_angles"} if kind == "kraby" else set()
    assert set(fields) == JSON_KEYS | posture
    if kind == "kraby":
        assert fields["robot"] == KRABY
    assert fields["cycles"] == 2
    assert fields["distance"] == pytest.approx(walked.metrics.distance)


def test_options_reach_the_simulation(monkeypatch, capsys, walked):
    seen = {}

    def record(design, gait, payload, **kwargs):
        seen.update(design=design, gait=gait, payload=payload, **kwargs)
        return walked

    monkeypatch.setattr(command, "simulate_gait", record)
    argv = ["simulate", "--l3", "0.45", "--stride", "0.2", "--pattern", "tetrapod"]
    argv += ["--payload", "12", "--friction", "0.8", "--cycles", "3"]
    assert run_cli(argv) == 0
    assert seen["design"].l3 == 0.45
    assert (seen["gait"].stride, seen["gait"].pattern) == (0.2, "tetrapod")
    assert seen["payload"].mass == 12.0
    assert (seen["friction"], seen["cycles"]) == (0.8, 3)
    out = capsys.readouterr().out
    assert "Simulated walk (MuJoCo)" in out and "fell" in out and "standing on lf, rm, lr" in out


def test_video_without_offscreen_opengl_is_skipped_with_a_note(
    monkeypatch, tmp_path, capsys, walked
):
    from hexaleg.sim import video

    monkeypatch.setattr(command, "simulate_gait", lambda *args, **kwargs: walked)
    monkeypatch.setattr(video, "_backends", lambda: ("glx-nowhere",))  # MuJoCo refuses it
    target = tmp_path / "walk.gif"
    assert run_cli(["simulate", "--video", str(target)]) == 0
    err = capsys.readouterr().err
    assert "--video skipped: no offscreen OpenGL" in err and "glx-nowhere" in err
    assert not target.exists()


@pytest.mark.slow
def test_the_animation_is_the_simulated_motion_drawn_in_a_browser(tmp_path, walked):
    from browser import require_chromium, screenshot
    from test_viewer import _drawn_share, _node

    from hexaleg.cli.simulate import _animation
    from hexaleg.output.viewer import LoopbackServer, client
    from hexaleg.output.viewer.gait import ANIMATION_PATH, NODE, build_motion_scene

    ratios = np.abs(walked.frame_torques) / np.array(walked.design.rated_torques)
    with LoopbackServer() as server:
        model = walked.sim_model().hexapod
        build_motion_scene(client(server), model, walked.frames, walked.frame_rate, ratios)
        time.sleep(0.2)
        tree = server._bridge.tree
        assert len(_node(tree, f"meshcat/{NODE}/visuals")) == 25  # body, 6 × 4 leg links
        assert _node(tree, ANIMATION_PATH.strip("/")).animation is not None
    page = _animation(walked, model, str(tmp_path / "walk.html"))
    require_chromium()
    import meshcat

    empty = screenshot(
        (meshcat.__file__.rsplit("/", 1)[0] + "/viewer/dist/index.html").join(["file://", ""]),
        tmp_path / "empty.png",
    )
    image = screenshot(page.as_uri(), tmp_path / "walk.png")
    assert _drawn_share(image, empty) > 0.05


@pytest.fixture(scope="module")
def overloaded():
    from hexaleg.statics import Payload

    return simulate_gait(HexapodDesign(), payload=Payload(30.0), cycles=2)  # hips past 150 N·m


def test_measured_peaks_over_their_ratings_are_flagged_in_text_and_json(
    monkeypatch, capsys, overloaded
):
    metrics, design = overloaded.metrics, overloaded.design
    rated = dict(zip(("root", "hip", "knee"), design.rated_torques, strict=True))
    over = {joint for joint, peak in metrics.peak_torque.items() if peak > rated[joint]}
    assert over  # the case this test is about: a measured peak beyond its rating
    assert {flag.joint for flag in metrics.over_rating} == over
    for joint in over:
        flags = [flag for flag in metrics.over_rating if flag.joint == joint]
        assert max(flag.peak for flag in flags) == metrics.peak_torque[joint]
        assert all(flag.peak > flag.rated == rated[joint] for flag in flags)
    period = overloaded.gait.period
    for flag in metrics.over_rating:  # peaks in the measured periods, after the first
        assert period <= float(flag.at.removeprefix("t = ").removesuffix(" s")) <= 2 * period
    monkeypatch.setattr(command, "simulate_gait", lambda *args, **kwargs: overloaded)
    assert run_cli(["simulate", "--payload", "30", "--cycles", "2"]) == 0
    out = capsys.readouterr().out
    for joint in over:
        assert f"{joint}: peak |τ| simulated / planned" in out
        line = next(row for row in out.splitlines() if f"{joint}: peak |τ|" in row)
        assert line.endswith("OVER RATING")
    assert [row.split(None, 2)[2] for row in out.splitlines() if "OVER RATING  " in row] == [
        str(flag) for flag in metrics.over_rating
    ]
    assert run_cli(["simulate", "--payload", "30", "--cycles", "2", "--json"]) == 0
    fields = json.loads(capsys.readouterr().out)
    assert fields["over_rating"] == [flag.to_dict() for flag in metrics.over_rating]
