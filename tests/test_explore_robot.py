"""``hexaleg explore --urdf FILE``: an imported robot's numbers are the command line's.

Each server is a subprocess on 127.0.0.1, port 0, stopped by its pid (:mod:`explorer`).
The oracle is the command line run in-process on the same robot file at the same segment
lengths (``--urdf FILE --l1 --l2 --l3``): ``flexibility``, ``loads``, ``gait``,
``workspace`` and ``manipulability`` with ``--json``; and, for the feet's reach, each
leg's own segments and offsets as ``design show`` lists them.
"""

from __future__ import annotations

import time
import urllib.parse
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from explorer import Explorer, running
from robots import KRABY, robot_json

GAIT = "[gait]\nstride = 0.03\nstep_height = 0.02\nperiod = 0.8\nsamples = 60\n"
"""A gait this small robot walks (the default one is sized for hexaleg's)."""
RTOL = 1e-9


@pytest.fixture(scope="module")
def gait_file(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("kraby") / "small_gait.toml"
    path.write_text(GAIT)
    return path


@pytest.fixture(scope="module")
def explorer(gait_file) -> Explorer:
    with running("--urdf", KRABY, "--design", str(gait_file), "--save", "unused.toml") as server:
        yield server


def _lengths(count: int) -> list[dict[str, float]]:
    """Seeded segment lengths around Kraby's own (coxa 49 mm, femur 60 mm, tibia 88 mm)."""
    rng = np.random.default_rng(20261204)
    return [
        {
            "l1": round(float(rng.uniform(0.04, 0.06)), 4),
            "l2": round(float(rng.uniform(0.05, 0.08)), 4),
            "l3": round(float(rng.uniform(0.08, 0.1)), 4),
        }
        for _ in range(count)
    ]


@pytest.mark.parametrize("lengths", _lengths(2))
def test_the_endpoint_s_numbers_are_the_command_line_s(explorer, capsys, gait_file, lengths):
    status, got = explorer.get("api/evaluate?" + urllib.parse.urlencode(lengths))
    assert status == 200 and got["error"] == "", got
    robot = ["--urdf", KRABY, *(p for k, v in lengths.items() for p in (f"--{k}", str(v)))]
    walked = [*robot, "--design", str(gait_file)]
    flexibility = robot_json(capsys, ["flexibility", *robot, "--json"])
    loads = robot_json(capsys, ["loads", *walked, "--json"])
    gait = robot_json(capsys, ["gait", *walked, "--json"])
    workspace = robot_json(capsys, ["workspace", *robot, "--samples", "1", "--json"])
    manipulability = robot_json(capsys, ["manipulability", *robot, "--json"])
    first = next(iter(workspace["legs"].values()))
    expected = {
        "fb": flexibility["fb"],
        "payload_capacity": loads["payload_capacity"]["mass"],
        "walking_payload_capacity": loads["walking_payload_capacity"]["mass"],
        "max_speed": gait["max_speed"]["value"],
        "improved_area": first["area"]["improved_closed_form"],
        "average_manipulability": next(iter(manipulability["legs"].values()))["average"][
            "improved"
        ],
    }
    for key, value in expected.items():
        assert got[key] == pytest.approx(value, rel=RTOL), key
    assert got["walking_payload_capacity"] > 0  # the file's [gait] is walked
    for joint in ("root", "hip", "knee"):
        assert got["peak_torque"][joint] == pytest.approx(gait["peak_torque"][joint], rel=RTOL)
    assert got["robot_mass"] == pytest.approx(loads["mass"], rel=RTOL)  # no payload aboard


def test_the_robot_weighs_what_its_file_says(explorer):
    status, got = explorer.get("api/evaluate")
    raw = pin.buildModelFromUrdf(KRABY, pin.JointModelFreeFlyer())  # the root link counted
    assert status == 200 and got["robot_mass"] == pytest.approx(pin.computeTotalMass(raw), 1e-12)


def test_the_feet_s_reach_lies_within_each_leg_s_span(explorer, capsys):
    status, got = explorer.get("api/reach?l2=0.07")
    assert status == 200
    shown = robot_json(capsys, ["design", "show", "--urdf", KRABY, "--l2", "0.07", "--json"])[
        "design"
    ]["legs"]
    status, stance = explorer.get("api/evaluate?l2=0.07")
    for leg, reach, chain in zip(shown, got["reach"], stance["stance"]["chains"], strict=True):
        points = np.asarray(reach)
        assert len(points) > 20
        span = leg["coxa"] + leg["femur"] + leg["tibia"] + abs(leg.get("foot_lateral", 0.0))
        root = np.asarray(chain[0][:2])  # the leg's yaw axis, where the chain starts
        assert (np.linalg.norm(points - root, axis=1) <= span + 1e-9).all(), leg["name"]


@pytest.mark.parametrize(
    "key", ["body_length", "body_width", "actuators.hip", "rated_torques", "body_mass", "layout"]
)
def test_what_the_file_fixes_answers_400_and_the_server_keeps_serving(explorer, key):
    status, got = explorer.get(f"api/evaluate?{key}=0.5")
    assert status == 400 and key in got["error"] and "imported robot" in got["error"]
    assert explorer.get("api/evaluate?l2=0.07")[0] == 200


def test_the_page_offers_the_segments_posture_payload_and_gait_only(explorer):
    status, loaded = explorer.get("api/loaded")
    assert status == 200 and loaded["robot"].endswith("hexapod.urdf")
    assert sorted(loaded["sliders"]) == ["l1", "l2", "l3"]
    assert loaded["values"]["l3"] == pytest.approx(0.088, abs=1e-9)  # Kraby's tibia
    assert loaded["values"]["stride"] == pytest.approx(0.03)  # the file's [gait]


def _job(explorer: Explorer, kind: str, query: str) -> dict:
    """Start the job ``kind`` on the design ``query`` asks for; its state once it ends."""
    status, job = explorer.post(f"api/job?kind={kind}&{query}")
    assert status == 200 and job["state"] == "running", job
    deadline = time.monotonic() + 240
    while job["state"] == "running" and time.monotonic() < deadline:
        time.sleep(0.5)
        job = explorer.get(f"api/job?kind={kind}")[1]
    assert job["state"] == "done", job
    return job


def test_the_free_coupled_job_answers_as_the_command_line_on_the_robot(explorer, capsys):
    job = _job(explorer, "free", "l2=0.07")
    free = robot_json(
        capsys, ["flexibility", "--urdf", KRABY, "--l2", "0.07", "--mode", "free", "--json"]
    )
    assert job["answer"]["fb"] == pytest.approx(free["fb"], rel=1e-9)


@pytest.mark.slow  # two decisions over Kraby's segments, a minute each on 2 cores
def test_the_decide_job_answers_as_the_command_line_on_the_saved_design(
    tmp_path, capsys, gait_file
):
    saved = tmp_path / "kraby.toml"
    with running("--urdf", KRABY, "--design", str(gait_file), "--save", str(saved)) as server:
        assert server.post("api/save?l2=0.07")[0] == 200
        job = _job(server, "decide", "l2=0.07")
    decided = robot_json(
        capsys, ["decide", "--design", str(saved), "--json"]
    )  # the job's design, as saved
    lengths = [
        [answer["best"]["design"][k] for k in ("l1", "l2", "l3")]
        for answer in (job["answer"], decided)
    ]
    assert lengths[0] == pytest.approx(lengths[1], rel=1e-9)
    assert job["answer"]["best"]["objective"] == pytest.approx(decided["best"]["objective"])


def test_save_writes_the_segments_and_posture_slid_into_the_robot_s_design_file(
    tmp_path, monkeypatch
):
    from hexaleg.cli import build_parser
    from hexaleg.cli.inputs import inputs_from_args
    from hexaleg.explore.cloud import Cloud
    from hexaleg.explore.session import Session

    monkeypatch.setattr(Cloud, "start", lambda cloud: cloud)  # not measured here

    def robot(*argv: str):
        return inputs_from_args(build_parser("explore").parse_args(["explore", *argv]))

    loaded = robot("--urdf", KRABY)
    session = Session.start(loaded.robot, loaded.requirements, tmp_path / "kraby.toml")
    path = session.save({"l2": "0.07", "theta2": "0.1", "theta3": "-1.4", "slope_deg": "0"})
    saved = robot("--design", str(path)).robot.design
    assert saved.l2 == pytest.approx(0.07, abs=1e-12) and saved.l3 == pytest.approx(0.088)
    assert saved.nominal_angles == (0.0, 0.1, -1.4)  # the posture slid, read back exactly
    assert loaded.robot.design.nominal_angles != saved.nominal_angles
