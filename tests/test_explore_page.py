"""The explorer's page in headless Chromium: a slider moved, the numbers and the stance redrawn.

The page is driven through the DevTools protocol (:mod:`browser`); the server is a
subprocess on 127.0.0.1 stopped by its pid (:mod:`explorer`). What the page shows is
checked against the endpoint asked the same query; the page's ``redraw`` performance
measures (slider input to page drawn) are read and reported, not held to a time here
(the target is the benchmark's business).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from browser import evaluate, require_chromium
from explorer import running

pytestmark = pytest.mark.slow

PAGE_READY = """\
  const sleep = (ms) => new Promise(r => setTimeout(r, ms));
  while (!window.explorer) await sleep(20);  // the script not loaded yet
  await window.explorer.started;
  const e = window.explorer;
  const idle = async () => { while (e.inFlight || e.pending) await sleep(20); };
"""
"""Each page script's start: the page loaded and started, ``e`` the explorer, ``idle()``."""

MOVE_SLIDER = (
    """
(async (VALUES) => {
"""
    + PAGE_READY
    + """  await idle();
  while (!(e.cloud && e.cloud.ready)) await sleep(100);  // redraws timed without it measuring
  const shown = () => Object.fromEntries([...document.querySelectorAll('#numbers tr')]
    .map(tr => [tr.dataset.key, tr.dataset.value === '' ? null : Number(tr.dataset.value)]));
  const scene = () => document.getElementById('scene').toDataURL();
  const before = {numbers: shown(), scene: scene(), query: e.query()};
  const moves = [];
  for (const value of VALUES) {
    const l3 = document.getElementById('l3');
    l3.value = value;
    l3.dispatchEvent(new Event('input', {bubbles: true}));
    await idle();
    const query = e.query();
    const endpoint = await fetch('api/evaluate?' + query).then(r => r.json());
    moves.push({query: query, numbers: shown(), scene: scene(), endpoint: endpoint});
  }
  const redraws = performance.getEntriesByName('redraw').map(m => m.duration);
  document.getElementById('save').click();
  while (document.getElementById('saved').textContent === '') await sleep(20);
  document.getElementById('reset').click();
  await sleep(0);
  await idle();
  return {before: before, moves: moves, redraws: redraws,
          saved: document.getElementById('saved').textContent,
          reset: {numbers: shown(), query: e.query()},
          status: document.getElementById('status').textContent};
})(%s)
"""
)

ROBOTS = Path(__file__).parent / "data" / "robots"
KRABY = ROBOTS / "kraby" / "hexapod.urdf"


def _endpoint_value(answer: dict, key: str) -> float | None:
    value = answer
    for part in key.split("."):
        value = value[part]
    return value


@pytest.mark.parametrize(
    ("robot", "loaded", "values"),
    [
        ((), "0.4", ("0.46", "0.44", "0.48")),
        (("--urdf", str(KRABY)), "0.088", ("0.1", "0.08", "0.095")),
    ],
    ids=["template", "kraby"],
)
def test_a_slider_moved_redraws_numbers_and_stance_equal_to_the_endpoint_s(
    tmp_path, robot, loaded, values
):
    require_chromium()
    saved = tmp_path / "saved.toml"
    with running(*robot, "--save", str(saved)) as server:
        got = evaluate(server.url, MOVE_SLIDER % json.dumps([float(v) for v in values]))
    before, moves = got["before"], got["moves"]
    assert f"l3={loaded}&" in before["query"] + "&"
    for move, l3 in zip(moves, values, strict=True):
        assert f"l3={l3}&" in move["query"] + "&"
        numbers, endpoint = move["numbers"], move["endpoint"]
        assert numbers["fb"] != before["numbers"]["fb"]
        assert move["scene"] != before["scene"]
        assert set(numbers) >= {"fb", "payload_capacity", "peak_torque.hip", "max_speed"}
        for key, value in numbers.items():
            expected = _endpoint_value(endpoint, key)
            if expected is None:  # not measured (no motors): shown as a dash
                assert value is None, key
            else:
                assert value == pytest.approx(expected, rel=1e-12), key
    assert moves[0]["scene"] != moves[1]["scene"]
    assert len(got["redraws"]) == 3 and all(d > 0 for d in got["redraws"])
    assert got["saved"] == f"wrote {saved}"
    shown = _design_show("--design", str(saved))  # read back as the robot at the last slider
    assert shown["l3"] == pytest.approx(float(values[-1]), abs=1e-9)
    loaded_design = _design_show(*robot)  # the sliders not moved: their loaded values, exactly
    assert shown["nominal_angles"] == loaded_design["nominal_angles"]
    assert got["reset"] == {"numbers": before["numbers"], "query": before["query"]}
    print(f"redraw after a slider move [ms]: {', '.join(f'{d:.0f}' for d in got['redraws'])}")


def _design_show(*options: str) -> dict:
    """``design show OPTIONS --json``'s design, run as a user would."""
    found = subprocess.run(
        [sys.executable, "-m", "hexaleg", "design", "show", *options, "--json"],
        capture_output=True, text=True, timeout=300, check=True,
    )  # fmt: skip
    return json.loads(found.stdout)["design"]


CHOOSE_MOTORS_AND_RUN_A_JOB = (
    """
(async () => {
"""
    + PAGE_READY
    + """  await idle();
  const motors = {root: 'hd_cha_20a_100', hip: 'hd_cha_32a_50', knee: 'hd_cha_25a_100'};
  for (const [joint, name] of Object.entries(motors)) {
    const select = document.getElementById('motor_' + joint);
    select.value = name;
    select.dispatchEvent(new Event('change', {bubbles: true}));
    await idle();
  }
  const row = document.querySelector('#numbers tr[data-key="energy_per_km"]');
  const endpoint = await fetch('api/evaluate?' + e.query()).then(r => r.json());
  const box = document.querySelector('#jobs .job[data-kind="decide"]');  // minutes long
  box.querySelector('button').click();
  const bar = box.querySelector('progress');
  const start = Date.now();
  while (!(box.dataset.state === 'running' && bar.value > 0) && Date.now() - start < 90000) {
    await sleep(100);
  }
  const moved = {state: box.dataset.state, value: bar.value, max: bar.max,
                 text: box.querySelector('.job-state').textContent};
  box.querySelector('button').click();  // it reads "stop" while the search runs
  while (box.dataset.state === 'running' && Date.now() - start < 100000) await sleep(100);
  return {query: e.query(), shown: row.dataset.value, endpoint: endpoint.energy_per_km,
          moved: moved, state: box.dataset.state,
          text: box.querySelector('.job-state').textContent};
})()
"""
)


def test_motors_chosen_on_the_page_and_a_decision_shown_and_stopped():
    require_chromium()
    with running() as server:
        got = evaluate(server.url, CHOOSE_MOTORS_AND_RUN_A_JOB)
    assert "actuators.hip=hd_cha_32a_50" in got["query"]
    assert got["shown"] != "" and float(got["shown"]) == pytest.approx(got["endpoint"], rel=1e-12)
    moved = got["moved"]
    assert moved["state"] == "running" and 0 < moved["value"] <= moved["max"], got
    assert moved["text"].startswith(f"{moved['value']:.0f}/{moved['max']:.0f}, ")
    assert got["state"] == "stopped", got  # the button stopped it


ONE_MOTOR_AND_A_REFUSED_POSTURE = (
    """
(async () => {
"""
    + PAGE_READY
    + """  const set = async (id, value, kind) => {
    const input = document.getElementById(id);
    input.value = value;
    input.dispatchEvent(new Event(kind, {bubbles: true}));
    await idle();
  };
  await idle();
  await set('motor_hip', 'hd_cha_25a_100', 'change');  // one motor chosen: the others follow
  const motors = ['root', 'hip', 'knee'].map(j => document.getElementById('motor_' + j).value);
  const afterMotor = {status: document.getElementById('status').className, motors: motors,
                      stale: document.getElementById('results').classList.contains('stale')};
  await set('theta3', -0.27, 'input');
  const shown = () => [...document.querySelectorAll('#numbers tr')].map(tr => tr.dataset.value);
  const fb = shown();
  await set('theta2', 0.52, 'input');  // the knee above the coupled bound: refused
  const refused = {status: document.getElementById('status').textContent,
                   stale: document.getElementById('results').classList.contains('stale'),
                   fb: shown()};
  await set('theta2', 0.0, 'input');
  await set('theta3', -1.5, 'input');
  return {afterMotor: afterMotor, fb: fb, refused: refused,
          again: document.getElementById('results').classList.contains('stale')};
})()
"""
)


def test_one_motor_fills_the_others_and_a_refused_design_greys_the_numbers():
    require_chromium()
    with running() as server:
        got = evaluate(server.url, ONE_MOTOR_AND_A_REFUSED_POSTURE)
    after = got["afterMotor"]
    assert after["motors"] == ["hd_cha_25a_100"] * 3 and after["status"] != "error", got
    assert not after["stale"]
    refused = got["refused"]
    assert refused["stale"] and "last design measured" in refused["status"], got
    assert refused["fb"] == got["fb"]  # the numbers kept are the last measured design's
    assert not got["again"]  # a design measured again: no longer grey


POSTURE = (
    """
(async (ANGLES) => {
"""
    + PAGE_READY
    + """  const set = async (id, value) => {
    const input = document.getElementById(id);
    input.value = value;
    input.dispatchEvent(new Event('input', {bubbles: true}));
    await idle();
  };
  const shown = () => Object.fromEntries([...document.querySelectorAll('#numbers tr')]
    .map(tr => [tr.dataset.key, tr.dataset.value === '' ? null : Number(tr.dataset.value)]));
  const endpoint = () => fetch('api/evaluate?' + e.query()).then(r => r.json());
  await idle();
  const slope = document.getElementById('slope_deg');
  const stale = () => document.getElementById('results').classList.contains('stale');
  await set('slope_deg', 5);  // walked uphill
  const sloped = {range: [slope.min, slope.max], stale: stale(), query: e.query(),
                  status: document.getElementById('status').textContent,
                  numbers: shown(), endpoint: await endpoint()};
  await set('slope_deg', 0);
  Object.assign(sloped, {level: document.getElementById('status').textContent, back: stale()});
  await set('theta2', ANGLES[0]);
  await set('theta3', ANGLES[1]);
  const moved = {query: e.query(), numbers: shown(), endpoint: await endpoint(), sloped: sloped};
  const box = document.querySelector('.job[data-kind="posture"]');
  const button = box.querySelector('button');
  const pressed = {disabled: button.disabled, title: button.title,
                   objective: document.getElementById('posture_objective').value};
  if (button.disabled) return {moved: moved, pressed: pressed};
  button.click();
  const start = Date.now();
  while (box.dataset.state !== 'done' && box.dataset.state !== 'failed'
         && Date.now() - start < 240000) await sleep(200);
  await sleep(0);
  await idle();
  const job = await fetch('api/job?kind=posture').then(r => r.json());
  return {moved: moved, pressed: pressed, job: job, query: e.query(), numbers: shown(),
          endpoint: await endpoint(), text: box.querySelector('.job-state').textContent,
          sliders: [e.exact.theta2, e.exact.theta3]};
})(%s)
"""
)


def _numbers_are_the_endpoint_s(numbers: dict, endpoint: dict) -> None:
    for key, value in numbers.items():
        expected = _endpoint_value(endpoint, key)
        if expected is None:
            assert value is None, key
        else:
            assert value == pytest.approx(expected, rel=1e-12), key


def _cli_json(*argv: str) -> dict:
    """A command's ``--json``, run in this process."""
    import contextlib
    import io

    from hexaleg.cli import main

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main([*argv, "--json"]) == 0
    return json.loads(out.getvalue())


@pytest.mark.parametrize(
    ("robot", "angles"),
    [((), (-0.3, -1.75)), (("--urdf", str(KRABY)), (0.1, -1.4))],
    ids=["template", "kraby"],
)
def test_the_posture_sliders_and_the_best_posture_button(tmp_path, robot, angles):
    require_chromium()
    if robot:  # its own gait, fixed (its default one is sized to it at each posture)
        gait = tmp_path / "gait.toml"
        gait.write_text("[gait]\nstride = 0.03\nstep_height = 0.02\nperiod = 0.8\n")
        robot = (*robot, "--design", str(gait))
    options = [*robot, "--save", str(tmp_path / "saved.toml")]
    with running(*options) as server:
        got = evaluate(server.url, POSTURE % json.dumps(list(angles)))
    moved = got["moved"]
    assert f"theta2={angles[0]}&theta3={angles[1]}" in moved["query"]
    sloped = moved["sloped"]  # the walking slope slider: the ground's bound, walked uphill
    assert (
        sloped["range"] == ["-60", "60"]
        and not sloped["stale"]
        and "slope_deg=5" in sloped["query"]
    )
    assert "5° slope" in sloped["status"] and "uphill" in sloped["status"]
    _numbers_are_the_endpoint_s(sloped["numbers"], sloped["endpoint"])
    uphill = _cli_json("gait", *robot, "--slope-deg", "5")
    for joint, value in uphill["peak_torque"].items():
        assert sloped["endpoint"]["peak_torque"][joint] == pytest.approx(value, rel=1e-9), joint
    assert not sloped["back"] and "walking on level ground" in sloped["level"]
    assert "slope_deg" not in moved["query"]  # back at its start: the loaded ground
    _numbers_are_the_endpoint_s(moved["numbers"], moved["endpoint"])
    posed = [*robot, "--nominal-angles", "0", str(angles[0]), str(angles[1])]
    loads = _cli_json("loads", *posed)
    gait = _cli_json("gait", *posed)
    endpoint = moved["endpoint"]
    assert endpoint["payload_capacity"] == pytest.approx(loads["payload_capacity"]["mass"], 1e-9)
    walking = loads["walking_payload_capacity"]["mass"]
    assert endpoint["walking_payload_capacity"] == pytest.approx(walking, rel=1e-9)
    for joint, value in gait["peak_torque"].items():
        assert endpoint["peak_torque"][joint] == pytest.approx(value, rel=1e-9), joint
    pressed = got["pressed"]
    assert pressed["objective"] == "maximize=walking_payload_capacity"
    if robot:  # a robot file's posture is slid, not searched: the button says so
        assert pressed["disabled"] and "robot file" in pressed["title"]
        return
    job = got["job"]
    assert job["state"] == "done", job
    best = job["answer"]["best"]
    assert got["sliders"] == best["nominal_angles"][1:]  # the page asks at the exact angles
    assert f"theta2={got['sliders'][0]!r}&theta3={got['sliders'][1]!r}" in got["query"]
    expected = _cli_json("posture", *posed)  # the command on the design the button was pressed on
    assert best["nominal_angles"] == pytest.approx(expected["best"]["nominal_angles"], abs=1e-12)
    value = expected["best"]["objective"]["value"]
    assert best["objective"]["value"] == pytest.approx(value, rel=1e-9)
    assert got["endpoint"]["walking_payload_capacity"] == pytest.approx(value, rel=1e-9)
    _numbers_are_the_endpoint_s(got["numbers"], got["endpoint"])
    assert got["text"].startswith(f"θ2 {best['nominal_angles'][1]:.3f}, θ3 ")
