"""Viewer: loopback-only server, named extremes and animation, drawn in a real browser."""

from __future__ import annotations

import contextlib
import os
import queue
import signal
import socket
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import psutil
import pytest
import umsgpack
from browser import LEGEND_LAYOUT, evaluate, require_chromium, screenshot
from robots import KINDS, robot_argv

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.output.viewer import HIGHLIGHT, LoopbackServer, build_scene, client, extreme_name
from hexaleg.stance import axis_locked_flexibility

SERVER_START_TIMEOUT = 120


def _listening(pid: int) -> list[str]:
    return [
        c.laddr.ip
        for c in psutil.Process(pid).net_connections("inet")
        if c.status == psutil.CONN_LISTEN
    ]


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def test_server_listens_on_loopback_only():
    before = set(_listening(os.getpid()))
    with LoopbackServer() as server:
        assert server.web_url.startswith("http://127.0.0.1:")
        assert server.zmq_url.startswith("tcp://127.0.0.1:")
        opened = [ip for ip in _listening(os.getpid()) if ip not in before] or _listening(
            os.getpid()
        )
        assert opened and all(ip == "127.0.0.1" for ip in _listening(os.getpid()))


def _node(tree, path: str):
    """The scene-tree node at ``path``; fails if any part is missing (no defaultdict creation)."""
    node = tree
    for part in path.split("/"):
        assert part in node, f"{path}: no {part!r} among {sorted(node)}"
        node = node[part]
    return node


def test_scene_has_every_extreme_by_name_and_an_animation(hexapod_model, default_design):
    result = axis_locked_flexibility(default_design, "all", hexapod_model)
    with LoopbackServer() as server:
        build_scene(client(server), hexapod_model, result, workspace_leg="lf")
        time.sleep(0.2)
        tree = server._bridge.tree
        names = {extreme_name(e) for e in result.extremes}
        assert names == {f"{a}{s}" for a in ("x", "y", "z", "roll", "pitch", "yaw") for s in "+-"}
        for name in names:
            visuals = _node(tree, f"meshcat/hexaleg/extremes/{name}/visuals")
            assert len(visuals) == 25  # body + 6 legs × (coxa, femur, tibia, foot)
            assert all(child.object is not None for child in visuals.values())
        assert len(_node(tree, "meshcat/hexaleg/nominal/visuals")) == 25
        assert _node(tree, "meshcat/hexaleg/workspace/lf").object is not None
        assert _node(tree, "meshcat/hexaleg/footholds/rm").object is not None
        # the link whose joint stops each extreme is drawn in the highlight colour, others not
        red = (
            int(HIGHLIGHT[0] * 255) * 65536
            + int(HIGHLIGHT[1] * 255) * 256
            + int(HIGHLIGHT[2] * 255)
        )
        for extreme in result.extremes:
            visuals = _node(tree, f"meshcat/hexaleg/extremes/{extreme_name(extreme)}/visuals")
            colours = {
                name: umsgpack.unpackb(node.object)["object"]["materials"][0]["color"]
                for name, node in visuals.items()
            }
            # the links each joint moves: the knee carries the tibia and the foot fixed to it
            moved = {"root": ("coxa",), "hip": ("femur",), "knee": ("tibia", "foot")}
            binding = {f"{c.leg}_{link}_0" for c in extreme.binding for link in moved[c.joint]}
            assert extreme.limited_by in extreme.binding
            assert {name for name, c in colours.items() if c == red} == binding
        # nothing else is reddish: red means a limit (the footholds are black, the cloud grey)
        foothold = umsgpack.unpackb(_node(tree, "meshcat/hexaleg/footholds/rm").object)
        r, g, b = (foothold["object"]["materials"][0]["color"] >> k & 255 for k in (16, 8, 0))
        assert r < 100 or r < 1.5 * max(g, b)
        cloud = umsgpack.unpackb(_node(tree, "meshcat/hexaleg/workspace/lf").object)
        rgb = np.frombuffer(
            cloud["object"]["geometries"][0]["data"]["attributes"]["color"]["array"].data,
            dtype=np.float32,
        )
        rgb = rgb.reshape(-1, 3)
        assert np.allclose(rgb[:, 0], rgb[:, 1]) and np.allclose(rgb[:, 1], rgb[:, 2])
        animated = [node for node in (tree, tree["meshcat"]) if node.animation is not None]
        assert animated  # one animation: out to every extreme and back


@pytest.fixture(scope="module")
def empty_scene(tmp_path_factory):
    require_chromium()
    import meshcat

    page = Path(meshcat.__file__).parent / "viewer" / "dist" / "index.html"
    return screenshot(page.as_uri(), tmp_path_factory.mktemp("empty") / "empty.png")


def _drawn_share(image: np.ndarray, empty: np.ndarray) -> float:
    return float((np.abs(image - empty).sum(axis=-1) > 30).mean())


@contextlib.contextmanager
def _served(*options: str) -> Iterator[tuple[subprocess.Popen[str], str]]:
    """``hexaleg view`` serving on a free loopback port: its process and its page's URL.

    Killed by its pid on the way out if the test has not stopped it.
    """
    port = _free_port()
    process = subprocess.Popen(
        [sys.executable, "-m", "hexaleg", "view", "--port", str(port), *options],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    lines: queue.Queue[str] = queue.Queue()
    threading.Thread(target=lambda: [lines.put(x) for x in process.stdout], daemon=True).start()
    try:
        try:
            line = lines.get(timeout=SERVER_START_TIMEOUT)  # the first line is the URL
        except queue.Empty:
            pytest.fail(f"hexaleg view printed no URL within {SERVER_START_TIMEOUT} s")
        url = f"http://127.0.0.1:{port}/static/"
        assert f"open {url}" in line
        yield process, url
    finally:
        if process.poll() is None:
            os.kill(process.pid, signal.SIGKILL)
            process.wait(timeout=30)


@pytest.mark.slow  # starts the server, computes the extremes, drives a browser
def test_view_serves_the_robot_in_a_browser_and_stops_on_ctrl_c(tmp_path, empty_scene):
    with _served() as (process, url):
        ips = _listening(process.pid)
        assert ips and all(ip == "127.0.0.1" for ip in ips), ips
        image = screenshot(url, tmp_path / "live.png")
        assert _drawn_share(image, empty_scene) > 0.05
        process.send_signal(signal.SIGINT)
        assert process.wait(timeout=30) == 0
        assert "stopped" in process.stderr.read()
    assert (
        not psutil.pid_exists(process.pid)
        or psutil.Process(process.pid).status() == psutil.STATUS_ZOMBIE
    )


def _assert_legend_beside_the_scene(layout: dict) -> None:
    """The legend is on screen, seen (nothing covers it) and wholly left of the canvas."""
    legend, canvas, window = layout["legend"], layout["canvas"], layout["window"]
    assert legend is not None, "no legend on the page"
    assert layout["shown"], layout
    assert 0 <= legend["left"] and legend["right"] - legend["left"] > 100
    assert legend["top"] >= 0 and legend["bottom"] <= window["height"]
    assert canvas["left"] >= legend["right"] - 1, (legend, canvas)  # beside, not over it
    assert canvas["right"] <= window["width"] + 1 and canvas["right"] - canvas["left"] > 400


@pytest.mark.slow  # the viewer computes the extremes (or walks a period) before it serves
def test_the_served_page_shows_the_legend_beside_the_scene(tmp_path, empty_scene):
    with _served() as (_, url):
        layout = evaluate(url, LEGEND_LAYOUT)
        image = screenshot(url, tmp_path / "live.png")
    _assert_legend_beside_the_scene(layout)
    assert "|τ| / rated torque" in layout["text"]
    assert "red: the link whose joint stops an extreme" in layout["text"]
    width = round(layout["legend"]["right"])
    assert _drawn_share(image[:, width:], empty_scene[:, :-width]) > 0.05  # the robot, beside
    with _served("--gait") as (_, url):
        layout = evaluate(url, LEGEND_LAYOUT)
    _assert_legend_beside_the_scene(layout)
    assert "gait period" in layout["text"]
    assert "red" not in layout["text"] and "extreme" not in layout["text"]


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize(
    "kind",
    [KINDS[0], pytest.param(KINDS[1], marks=pytest.mark.slow)],  # one drawing by default
)
def test_static_html_draws_the_robot(tmp_path, empty_scene, kind):
    from hexaleg.cli import main

    page = tmp_path / "scene.html"
    assert main(["view", *robot_argv(kind), "--html", str(page), "--stance", "tripod"]) == 0
    assert "<html" in page.read_text()[:2000].lower()
    image = screenshot(page.as_uri(), tmp_path / "static.png")
    assert _drawn_share(image, empty_scene) > 0.05


def test_view_rejects_bad_input_in_one_line(capsys, tmp_path):
    from conftest import run_cli

    assert run_cli(["view", "--workspace", "zz", "--html", str(tmp_path / "x.html")]) == 2
    assert run_cli(["view", "--port", "70000"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and "--workspace" in err[0] and "--port" in err[1]
    assert list(tmp_path.iterdir()) == []


def test_meshcat_chatter_is_not_shown_to_the_user(capfd):
    """A second server finds port 7000 taken: meshcat would print "Port: ... in use"."""
    with LoopbackServer() as first, LoopbackServer() as second:
        assert first.web_url != second.web_url
    captured = capfd.readouterr()
    assert "in use" not in captured.err + captured.out
    assert "opened:" not in captured.err


def test_leg_links_are_coloured_by_torque_over_rating(hexapod_model, default_design):
    from hexaleg.output.viewer.scene import torque_colour
    from hexaleg.statics.loads import loads_at_extremes

    result = axis_locked_flexibility(default_design, "all", hexapod_model)
    loads = loads_at_extremes(hexapod_model, result)
    with LoopbackServer() as server:
        build_scene(client(server), hexapod_model, result, loads=loads)
        time.sleep(0.2)
        tree = server._bridge.tree
        assert "legend" not in _node(tree, "meshcat/hexaleg")  # beside the scene, not in it
        visuals = _node(tree, "meshcat/hexaleg/nominal/visuals")
        rated = np.array(default_design.rated_torques)
        for leg, torques in zip(loads.nominal.legs, loads.nominal.joint_torques, strict=True):
            for link, torque, limit in zip(("coxa", "femur", "tibia"), torques, rated, strict=True):
                colour = umsgpack.unpackb(visuals[f"{leg}_{link}_0"].object)["object"]["materials"][
                    0
                ]["color"]
                red, green, blue, _ = torque_colour(abs(torque) / limit)
                expected = int(red * 255) * 65536 + int(green * 255) * 256 + int(blue * 255)
                assert colour == expected
        hip = umsgpack.unpackb(visuals["lf_femur_0"].object)["object"]["materials"][0]["color"]
        knee = umsgpack.unpackb(visuals["lf_tibia_0"].object)["object"]["materials"][0]["color"]
        assert hip != knee  # the nominal hip works, the vertical tibia's knee hardly


@pytest.mark.slow  # a browser screenshot of the legend
def test_the_torque_legend_is_html_beside_the_scene(tmp_path, empty_scene, hexapod_model):
    from hexaleg.output.viewer.legend import STATICS_LEGEND, torque_legend_html
    from hexaleg.output.viewer.scene import write_static_html
    from hexaleg.statics.loads import loads_at_extremes

    legend = torque_legend_html(STATICS_LEGEND)
    # viridis runs from yellow #fde725 (at the rating) down to purple #440154 (idle)
    assert "linear-gradient(to bottom, rgb(253,231,37) 0%" in legend
    assert "rgb(68,1,84) 100%" in legend
    result = axis_locked_flexibility(hexapod_model.design, "all", hexapod_model)
    page = write_static_html(
        hexapod_model, result, tmp_path / "v.html", loads=loads_at_extremes(hexapod_model, result)
    )
    assert page.read_text().count("id='hexaleg-legend'") == 1
    image = screenshot(page.as_uri(), tmp_path / "v.png")
    column = image[:, :200]  # the legend's 13rem column at the left
    assert (np.abs(column - 244).sum(axis=-1) < 6).mean() > 0.7  # mostly its plain background
    assert (np.abs(column[100:300, 16:40] - [253, 231, 37]).sum(axis=-1) < 60).any()  # its bar
    scene = image[:, 220:]
    assert (np.abs(scene - 244).sum(axis=-1) < 6).mean() < 0.2  # the 3-D scene, not the legend
    assert _drawn_share(image[:, 220:], empty_scene[:, :-220]) > 0.05


@pytest.mark.slow  # a browser draws a second robot (the default suite keeps one drawing)
def test_hexagonal_robot_is_drawn_with_a_round_body(tmp_path, empty_scene):
    from hexaleg.cli import main

    design = HexapodDesign(layout="hexagon", body_radius=0.35)
    model = HexapodModel(design)
    result = axis_locked_flexibility(design, "all", model)
    with LoopbackServer() as server:
        build_scene(client(server), model, result)
        time.sleep(0.2)
        body = _node(server._bridge.tree, "meshcat/hexaleg/nominal/visuals/base_link_0")
        geometry = umsgpack.unpackb(body.object)["object"]["geometries"][0]
        assert geometry["type"] == "CylinderGeometry"
        assert geometry["radiusTop"] == pytest.approx(design.body_radius)
    page = tmp_path / "hexagon.html"
    assert main(["view", "--layout", "hexagon", "--body-radius", "0.35", "--html", str(page)]) == 0
    image = screenshot(page.as_uri(), tmp_path / "hexagon.png")
    assert _drawn_share(image, empty_scene) > 0.05
