"""``hexaleg explore``: the endpoint's numbers are the command line's, bad values answer 400.

Each server is a subprocess on 127.0.0.1, port 0, stopped by its pid (:mod:`explorer`).
The command line is the oracle: its ``--json`` of flexibility, workspace,
manipulability, loads and gait, run in-process for the same design and conditions.
"""

from __future__ import annotations

import json
import signal
import urllib.parse

import numpy as np
import psutil
import pytest
from explorer import Explorer, running

from hexaleg.cli import main
from hexaleg.design import HexapodDesign
from hexaleg.design_file import load_design_file
from hexaleg.evaluation.evaluate import Conditions, _Measuring
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import ParameterError
from hexaleg.explore.query import parse_query
from hexaleg.explore.session import Session

RTOL = 1e-9
"""Endpoint against command line: the same computation, summed in another order at most."""


@pytest.fixture(scope="module")
def explorer() -> Explorer:
    with running() as server:
        yield server


def _cli(capsys: pytest.CaptureFixture[str], *argv: str) -> dict:
    capsys.readouterr()
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def _random_designs(count: int) -> list[dict[str, float]]:
    """Seeded designs around the default robot that stand and walk the default gait."""
    rng = np.random.default_rng(20261203)
    return [
        {
            "l1": round(float(rng.uniform(0.1, 0.3)), 4),
            "l2": round(float(rng.uniform(0.35, 0.5)), 4),
            "l3": round(float(rng.uniform(0.35, 0.5)), 4),
            "body_width": round(float(rng.uniform(0.5, 0.7)), 4),
            "payload": round(float(rng.uniform(0.0, 20.0)), 3),
        }
        for _ in range(count)
    ]


def _options(query: dict[str, float]) -> list[str]:
    design = [f"--{k.replace('_', '-')}" for k in query if k != "payload"]
    return [part for flag in design for part in (flag, str(query[flag[2:].replace("-", "_")]))]


@pytest.mark.parametrize("query", _random_designs(3))
def test_the_endpoint_s_numbers_are_the_command_line_s(explorer, capsys, query):
    status, got = explorer.get("api/evaluate?" + urllib.parse.urlencode(query))
    assert status == 200 and got["error"] == "", got
    design = _options(query)
    payload = ["--payload", str(query["payload"])]
    flexibility = _cli(capsys, "flexibility", *design)
    leg = design[:6]  # one leg's commands take the lengths only
    workspace = _cli(capsys, "workspace", *leg, "--samples", "1")
    manipulability = _cli(capsys, "manipulability", *leg)
    loads = _cli(capsys, "loads", *design, *payload)
    gait = _cli(capsys, "gait", *design, *payload)
    expected = {
        "fb": flexibility["fb"],
        "improved_area": workspace["area"]["improved_closed_form"],
        "average_manipulability": manipulability["average"]["improved"],
        "payload_capacity": loads["payload_capacity"]["mass"],
        "walking_payload_capacity": loads["walking_payload_capacity"]["mass"],
        "max_speed": gait["max_speed"]["value"],
    }
    for name, value in expected.items():
        assert got[name] == pytest.approx(value, rel=RTOL), name
    for joint, value in gait["peak_torque"].items():
        assert got["peak_torque"][joint] == pytest.approx(value, rel=RTOL), joint
    assert got["limited_by"]["max_speed"]["description"] == str(
        gait["max_speed"]["limited_by"]["description"]
    )
    extremes = [(x["name"], x["limited_by"]) for x in got["extremes"]]
    printed = [
        (x["axis"] + ("+" if x["sign"] > 0 else "-"), x["description"])
        for x in flexibility["extremes"]
    ]
    assert extremes == printed
    for shown, printed in zip(got["extremes"], flexibility["extremes"], strict=True):
        assert shown["value"] == pytest.approx(printed["value"], rel=RTOL, abs=1e-12)
    rated = gait["design"]["rated_torques"]
    worst = max(
        gait["peak_torque"][j] / r for j, r in zip(("root", "hip", "knee"), rated, strict=True)
    )
    assert max(got["stance"]["utilisation"]) == pytest.approx(worst, rel=RTOL)


def test_the_gait_sliders_are_the_gait_command_s_speed_and_step_height(explorer, capsys):
    query = {"l3": 0.45, "speed": 0.2, "step_height": 0.07}
    status, got = explorer.get("api/evaluate?" + urllib.parse.urlencode(query))
    assert status == 200
    gait = _cli(capsys, "gait", "--l3", "0.45", "--speed", "0.2", "--step-height", "0.07")
    assert gait["gait"]["speed"] == pytest.approx(0.2)
    for joint, value in gait["peak_torque"].items():
        assert got["peak_torque"][joint] == pytest.approx(value, rel=RTOL), joint
    assert got["max_speed"] == pytest.approx(gait["max_speed"]["value"], rel=RTOL)


@pytest.mark.parametrize(
    ("query", "field"),
    [
        ("l1=abc", "l1"),
        ("l2=-0.4", "l2"),
        ("l3=nan", "l3"),
        ("body_width=1e9", "body_width"),
        ("payload=-3", "payload"),
        ("payload_at=0,0", "payload_at"),
        ("payload_at=0,0,500", "payload_at.z"),
        ("nominal_angles=0,0", "nominal_angles"),
        ("speed=1000", "speed"),
        ("step_height=x", "step_height"),
        ("colour=red", "colour"),
        ("theta2=0.9", "theta2"),
        ("theta3=-2.5", "theta3"),
        ("theta3=inf", "theta3"),
        ("theta2=0.1&nominal_angles=0,0.1,-1.5", "theta2"),
        ("slope_deg=61", "slope_deg"),
        ("slope_deg=-60.5", "slope_deg"),
        ("slope_deg=nan", "slope_deg"),
    ],
)
def test_a_bad_value_answers_400_naming_its_field_and_the_server_keeps_serving(
    explorer, query, field
):
    status, got = explorer.get("api/evaluate?" + query)
    assert status == 400
    assert got["field"] == field and got["allowed"] and field in got["error"]
    status, good = explorer.get("api/evaluate?l1=0.2")
    assert status == 200 and good["fb"] > 0


def test_it_binds_loopback_as_told_and_stops_on_sigterm_by_its_pid():
    with running("--host", "127.0.0.1") as server:
        listening = {
            (c.laddr.ip, c.laddr.port)
            for c in psutil.Process(server.process.pid).net_connections("inet")
            if c.status == psutil.CONN_LISTEN
        }
        port = int(server.url.rsplit(":", 1)[1].strip("/"))
        assert server.url == f"http://127.0.0.1:{port}/"
        assert listening == {("127.0.0.1", port)}
        status, err = server.stop(signal.SIGTERM)
    assert status == 0 and "stopped" in err and "Traceback" not in err


def test_ctrl_c_stops_it_cleanly():
    with running() as server:
        assert server.get("api/loaded")[0] == 200
        status, err = server.stop(signal.SIGINT)
    assert status == 0 and "stopped" in err and "Traceback" not in err


def test_a_host_beyond_loopback_is_served_only_when_asked_and_warned_about():
    with running("--host", "0.0.0.0") as server:
        listening = {
            c.laddr.ip
            for c in psutil.Process(server.process.pid).net_connections("inet")
            if c.status == psutil.CONN_LISTEN
        }
        status, err = server.stop()
    assert listening == {"0.0.0.0"}
    assert "beyond this machine" in err and status == 0


def test_save_writes_the_design_file_with_its_requirements(tmp_path):
    source = tmp_path / "robot.toml"
    assert main(["design", "init", str(source), "--l1", "0.18"]) == 0
    source.write_text(source.read_text() + "\n[requirements]\nmin_fb = 0.2\npayload = 10\n")
    loaded_design, before = load_design_file(source, Requirements.from_table)
    with running("--design", str(source)) as server:
        status, loaded = server.get("api/loaded")
        assert status == 200 and loaded["values"]["l1"] == pytest.approx(0.18)
        status, got = server.get("api/evaluate?l3=0.42")
        resolved = before.resolved(loaded_design)  # the loaded leg length, not the asked one
        assert [c["name"] for c in got["requirements"]] == list(resolved.given)
        leg_length = next(c for c in got["requirements"] if c["name"] == "leg_length")
        assert leg_length["required"] == pytest.approx(loaded_design.leg_length)
        assert all(c["met"] == (c["margin"] >= 0) for c in got["requirements"])
        status, wrote = server.post("api/save?l3=0.42&l2=0.39&theta2=0.1&theta3=-1.4&slope_deg=0")
        assert status == 200 and wrote["wrote"] == str(source)
        assert server.post("api/save?l3=-1")[0] == 400
        assert server.post("api/save?theta3=-3")[0] == 400  # beyond the stance limits
    design, requirements = load_design_file(source, Requirements.from_table)
    assert (design.l1, design.l2, design.l3) == pytest.approx((0.18, 0.39, 0.42))
    assert design.nominal_angles == (0.0, 0.1, -1.4)  # the posture slid, exactly
    assert requirements == before
    assert [p.name for p in tmp_path.iterdir()] == ["robot.toml"]  # no temporary file left


def test_a_query_sets_the_design_fields_by_their_file_keys_and_the_conditions():
    base = HexapodDesign()
    asked = parse_query(
        {"l1": "0.25", "nominal_angles": "0,0.1,-1.4", "payload": "5", "payload_at": "0.1,0,0.05",
         "speed": "0.25", "step_height": "0.05"},
        base,
        Conditions(),
    )  # fmt: skip
    assert asked.design == base.replace(l1=0.25, nominal_angles=(0.0, 0.1, -1.4))
    payload = asked.conditions.payload
    assert payload.mass == 5 and payload.position == (0.1, 0, 0.05)
    gait = asked.conditions.gait
    assert gait.speed == pytest.approx(0.25) and gait.step_height == 0.05
    assert gait.stride == Conditions().gait.stride  # the stride kept, the period set
    with pytest.raises(ParameterError, match=r"nominal_angles\.theta2"):
        parse_query({"nominal_angles": "0,x,-1"}, base, Conditions())
    posed = parse_query({"theta2": "0.1", "theta3": "-1.4"}, base, Conditions()).design
    assert posed == asked.design.replace(l1=base.l1)  # θ1 kept, θ2 and θ3 set
    knee = parse_query({"theta3": "-1.2"}, posed, Conditions()).design
    assert knee.nominal_angles == (0.0, 0.1, -1.2)


def test_the_walking_slope_is_checked_against_the_ground_s_bound_in_degrees():
    from hexaleg.explore.answer import walking_on

    base = HexapodDesign()
    for degrees in ("60", "-60", "0", "12.5"):  # the bound itself walks
        ground = parse_query({"slope_deg": degrees}, base, Conditions()).ground
        assert ground.slope == np.deg2rad(float(degrees)) and ground.heading is None
    assert parse_query({}, base, Conditions()).ground is None  # the loaded ground kept
    for degrees in ("60.0001", "-61", "inf", "ten"):
        with pytest.raises(ParameterError) as refused:
            parse_query({"slope_deg": degrees}, base, Conditions())
        assert refused.value.field == "slope_deg" and "[-60, 60] [°]" in refused.value.allowed
    assert walking_on(Conditions(), None) == Conditions()  # the loaded grounds
    sloped = parse_query({"slope_deg": "10"}, base, Conditions()).ground
    assert walking_on(Conditions(), sloped).grounds == (sloped,)


@pytest.mark.parametrize("degrees", ["10", "-7.5"])
def test_the_walking_slope_is_the_gait_command_s_slope(explorer, capsys, degrees):
    status, got = explorer.get(f"api/evaluate?l3=0.42&slope_deg={degrees}")
    assert status == 200 and got["error"] == "", got
    gait = _cli(capsys, "gait", "--l3", "0.42", "--slope-deg", degrees)
    assert [g["slope_deg"] for g in got["grounds"]] == pytest.approx([float(degrees)])
    assert got["max_speed"] == pytest.approx(gait["max_speed"]["value"], rel=RTOL)
    for joint, value in gait["peak_torque"].items():
        assert got["peak_torque"][joint] == pytest.approx(value, rel=RTOL), joint
    level = explorer.get("api/evaluate?l3=0.42")[1]
    assert level["peak_torque"]["hip"] != got["peak_torque"]["hip"]  # the slope is walked


def test_a_save_file_that_is_not_toml_is_refused_before_serving(capsys):
    assert main(["explore", "--save", "design.json"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "design.json" in err and ".toml" in err


MOTORS = {
    "actuators.root": "hd_cha_20a_100",
    "actuators.hip": "hd_cha_32a_50",
    "actuators.knee": "hd_cha_25a_100",
}
"""A catalog motor per joint type, chosen on the page by name."""


def _motors_file(folder, motors: dict[str, str]) -> str:
    """A design file naming the same catalog motors, as a user writes it."""
    path = folder / "motors.toml"
    path.write_text("".join(f'[{key}]\ncatalog = "{name}"\n' for key, name in motors.items()))
    return str(path)


def test_motors_chosen_by_name_measure_as_the_design_file_s_catalog_motors(
    explorer, capsys, tmp_path
):
    status, got = explorer.get("api/evaluate?" + urllib.parse.urlencode(MOTORS))
    assert status == 200 and got["error"] == "", got
    design = ["--design", _motors_file(tmp_path, MOTORS)]
    gait = _cli(capsys, "gait", *design)
    loads = _cli(capsys, "loads", *design)
    electrical = gait["electrical"]
    assert got["energy_per_km"] == pytest.approx(electrical["energy_per_km"], rel=RTOL)
    assert got["electrical_cost_of_transport"] == pytest.approx(
        electrical["cost_of_transport"], rel=RTOL
    )
    assert got["robot_mass"] == pytest.approx(loads["mass"], rel=RTOL)
    for joint, value in gait["peak_torque"].items():
        assert got["peak_torque"][joint] == pytest.approx(value, rel=RTOL), joint
    status, plain = explorer.get("api/evaluate")  # the loaded design: no motors
    assert plain["energy_per_km"] is None and "actuators" in plain["unmeasured"]["energy_per_km"]
    assert plain["robot_mass"] < got["robot_mass"]  # the motors weigh


def test_the_page_offers_the_shipped_catalog(explorer):
    from hexaleg.actuator_catalog import shipped_catalog

    assert explorer.get("api/loaded")[0] == 200
    loaded = explorer.get("api/loaded")[1]
    assert [m["name"] for m in loaded["catalog"]] == list(shipped_catalog().names)
    assert loaded["values"]["actuators"] == {"root": None, "hip": None, "knee": None}
    assert loaded["has_actuators"] is False


def test_the_reach_is_answered_on_its_own_for_the_design_asked(explorer):
    from hexaleg.explore.answer import feet_reach

    status, got = explorer.get("api/reach?l3=0.45&body_width=0.55")
    assert status == 200
    assert got["reach"] == feet_reach(HexapodDesign(l3=0.45, body_width=0.55))
    status, evaluated = explorer.get("api/evaluate?l3=0.45")
    assert status == 200 and "reach" not in evaluated["stance"]  # not paid by each redraw
    assert explorer.get("api/reach?l3=-1")[0] == 400


def test_a_query_chooses_motors_by_catalog_name_or_takes_them_away(tmp_path):
    file_design = load_design_file(_motors_file(tmp_path, MOTORS), Requirements.from_table)[0]
    base = HexapodDesign()
    chosen = parse_query(MOTORS, base, Conditions()).design
    assert chosen.actuators == file_design.actuators
    assert chosen.rated_torques == file_design.rated_torques
    one = parse_query({"actuators.hip": "hd_cha_25a_100"}, chosen, Conditions()).design
    assert one.actuators is not None and file_design.actuators is not None
    assert (one.actuators.root, one.actuators.knee) == (
        file_design.actuators.root, file_design.actuators.knee
    )  # fmt: skip
    assert one.actuators.hip.peak_torque == 157.0  # the catalog entry's (hexaleg actuators)
    none = {key: "" for key in MOTORS}
    assert parse_query(none, chosen, Conditions()).design.actuators is None
    with pytest.raises(ParameterError, match=r"actuators\.hip.*hd_cha_25a_100"):
        parse_query({"actuators.hip": "hd_cha_25a_10"}, base, Conditions())
    with pytest.raises(ParameterError, match=r"actuators\.root.*every joint type"):
        parse_query({"actuators.hip": "hd_cha_25a_100"}, base, Conditions())


@pytest.mark.parametrize(
    ("query", "field"),
    [
        ("actuators.root=hd_cha_20a_100&actuators.knee=hd_cha_25a_10", "actuators.knee"),
        ("actuators.root=hd_cha_20a_100", "actuators.hip"),  # the others have none
    ],
)
def test_a_bad_motor_answers_400_naming_its_key(explorer, query, field):
    status, got = explorer.get("api/evaluate?" + query)
    assert status == 400 and got["field"] == field, got


def test_each_extreme_is_drawn_with_the_feet_where_the_nominal_stance_plants_them():
    from hexaleg.explore.answer import answer

    got = answer(HexapodDesign(), Conditions(), Requirements())
    nominal = np.array(got["stance"]["chains"])  # (legs, 4 points, xyz)
    assert len(got["extremes"]) == 12
    for extreme in got["extremes"]:
        chains = np.array(extreme["chains"])
        # the closed chain: every stance foot stays on its foothold (all six stand)
        assert np.abs(chains[:, -1] - nominal[:, -1]).max() < 1e-5, extreme["name"]
        roots = chains[:, 0].mean(axis=0) - nominal[:, 0].mean(axis=0)
        axis, sign = extreme["name"][:-1], extreme["name"][-1]
        if axis in ("x", "y", "z"):  # a translation moves the body's centre by its value
            k = "xyz".index(axis)
            assert roots[k] == pytest.approx(extreme["value"], abs=1e-5)
            assert np.sign(extreme["value"]) == (1 if sign == "+" else -1)
        else:  # a rotation about the body's centre moves the roots' mean at most a little
            assert np.abs(chains[:, 0] - nominal[:, 0]).max() > 1e-3


def test_the_feet_s_reach_is_where_each_leg_can_put_its_foot_on_the_ground():
    from hexaleg.explore.answer import REACH_SLICE, answer, feet_reach

    design = HexapodDesign()
    got = answer(design, Conditions(), Requirements())["stance"] | {"reach": feet_reach(design)}
    l1, l2, l3 = design.lengths
    yaw_low, yaw_high = design.stance_limits.theta1
    for leg, (chain, reach) in enumerate(zip(got["chains"], got["reach"], strict=True)):
        root, coxa_end, foot = np.array(chain[0]), np.array(chain[1]), np.array(chain[-1])
        points = np.array(reach)
        assert len(points) > 50, leg
        out = points - root[:2]
        rho = np.hypot(out[:, 0], out[:, 1])  # from the yaw axis, on the ground
        drop = abs(foot[2] - root[2])
        # the femur and tibia span at most l2 + l3 from the coxa's end (the slice's slack)
        assert np.all((rho - l1) ** 2 + max(0.0, drop - REACH_SLICE) ** 2 <= (l2 + l3) ** 2)
        heading = np.arctan2(*(coxa_end - root)[1::-1])  # the leg's direction at θ1 = 0
        yaw = np.angle(np.exp(1j * (np.arctan2(out[:, 1], out[:, 0]) - heading)))
        assert np.all((yaw >= yaw_low - 1e-9) & (yaw <= yaw_high + 1e-9)), leg
        assert np.min(np.hypot(*(points - foot[:2]).T)) < 0.05  # the nominal foot is in it


def test_a_key_given_twice_answers_400_naming_it(explorer):
    status, got = explorer.get("api/evaluate?l2=0.4&l2=0.5")
    assert status == 400 and got["field"] == "l2" and "more than once" in got["error"]


def test_a_period_that_breaks_a_constraint_colours_no_leg(explorer):
    status, got = explorer.get("api/evaluate?stride=1.5")  # beyond any foot's reach
    assert status == 200 and got["walks"] is False
    assert got["stance"]["utilisation"] == [None] * 6


def test_a_page_that_goes_away_mid_answer_is_not_reported(capsys):
    from hexaleg.explore.server import ExplorerServer

    try:
        raise ConnectionResetError(104, "Connection reset by peer")
    except ConnectionResetError:
        ExplorerServer.handle_error(None, None, None)  # type: ignore[arg-type]
    assert capsys.readouterr().err == ""


REQUIRED = """[requirements]
payload = 10
slope_deg = 5
min_fb = 0.2
speed = 0.1
walking_payload = 5
"""
"""Requirements whose conditions (payload, slope, gait) the sliders start at."""


def _session(tmp_path, monkeypatch, text: str) -> Session:
    """The explorer's session of a design file ``text``, its study cloud left unmeasured."""
    from hexaleg.cli import build_parser
    from hexaleg.cli.inputs import inputs_from_args
    from hexaleg.explore.cloud import Cloud

    monkeypatch.setattr(Cloud, "start", lambda cloud: cloud)  # not measured: not counted
    path = tmp_path / "design.toml"
    path.write_text(text)
    args = build_parser("explore").parse_args(["explore", "--design", str(path)])
    inputs = inputs_from_args(args)
    return Session.start(inputs.robot, inputs.requirements, path)


def test_an_answer_evaluates_its_design_once_and_its_checks_read_the_numbers_shown(
    tmp_path, monkeypatch
):
    session = _session(tmp_path, monkeypatch, REQUIRED)
    evaluated: list[HexapodDesign] = []
    measure = _Measuring.evaluation

    def counted(self, metrics):
        evaluated.append(self.design)
        return measure(self, metrics)

    monkeypatch.setattr(_Measuring, "evaluation", counted)
    for query, unlike in [
        ({"l3": "0.42"}, []),  # the sliders at the requirements' conditions
        ({"l3": "0.42", "payload": "3", "speed": "0.2"}, ["payload.mass", "gait.period"]),
        ({"theta2": "0.1", "theta3": "-1.4", "slope_deg": "0"}, []),  # the posture is the design
    ]:
        evaluated.clear()
        got = session.evaluate(query)
        assert len(evaluated) == 1, query  # one evaluation, whoever reads it
        assert [c["name"] for c in got["requirements_conditions"]] == unlike
        checks = {c["name"]: c["value"] for c in got["requirements"]}
        assert checks["min_fb"] == got["fb"]
        assert checks["payload"] == got["payload_capacity"]
        assert checks["speed"] == got["max_speed"]
        assert checks["walking_payload"] == got["walking_payload_capacity"]
        for row in got["rows"]:  # the page's rows: each a number of this answer, by its key
            name, _, joint = row["key"].partition(".")
            assert name in got and (not joint or joint in got[name]), row


SIZED = """[structure]
material = "aluminium_7075_t6"
size = true

[requirements]
payload = 15
"""


def test_the_sized_tubes_are_the_loads_and_gait_commands(tmp_path, monkeypatch, capsys):
    session = _session(tmp_path, monkeypatch, SIZED)
    got = session.evaluate({"l2": "0.42"})["structure"]
    options = ["--design", str(tmp_path / "design.toml"), "--l2", "0.42", "--payload", "15"]
    loads = _cli(capsys, "loads", *options)["structure"]
    gait = _cli(capsys, "gait", *options)["structure"]
    assert got["sizing"] == {k: loads["sizing"][k] for k in ("found", "iterations", "settled")}
    for segment, tube in loads["tubes"].items():
        for key, value in tube.items():
            assert got["tubes"][segment][key] == pytest.approx(value, rel=RTOL), (segment, key)
    assert got["deflection"] == pytest.approx(loads["deflection"], rel=RTOL)
    worst = max((loads, gait), key=lambda check: check["worst_ratio"])
    assert got["worst_ratio"] == pytest.approx(worst["worst_ratio"], rel=RTOL)
    assert got["worst"]["case"] == worst["worst"]["case"]
    assert got["feasible"] is (loads["feasible"] and gait["feasible"])
    assert session.evaluate({})["structure"]["tubes"] != got["tubes"]  # sized per design


@pytest.mark.parametrize(
    ("params", "options", "field"),
    [
        ({}, (), None),
        ({"maximize": "fb"}, ("--maximize", "fb"), None),
        ({"minimize": "robot_mass"}, ("--minimize", "robot_mass"), None),
        ({"maximize": "robot_mass"}, None, "maximize"),  # made smallest, not largest
        ({"maximize": "fb", "minimize": "robot_mass"}, None, "minimize"),
    ],
)
def test_the_posture_job_takes_its_command_s_objective_and_nothing_else(params, options, field):
    from hexaleg.evaluation.metrics import objectives
    from hexaleg.exceptions import ParameterError
    from hexaleg.explore.jobs import job_options

    assert "robot_mass" in objectives("minimize") and "fb" in objectives("maximize")
    asked = {"l2": "0.41", **params}
    if field is None:
        assert job_options("posture", asked) == options
        assert asked == {"l2": "0.41"}  # taken out: the rest is the design's
        assert job_options("decide", {"maximize": "fb"}) == ()  # not decide's key: left
    else:
        with pytest.raises(ParameterError) as refused:
            job_options("posture", asked)
        assert refused.value.field == field


def test_the_slider_starts_at_the_required_walking_slope_and_names_it_once_moved(
    tmp_path, monkeypatch
):
    text = "[requirements]\nwalking_payload = 5\nwalking_slope_deg = 10\n"
    session = _session(tmp_path, monkeypatch, text)
    assert session.loaded()["values"]["slope_deg"] == pytest.approx(10)
    got = session.evaluate({})  # up, down and across the required slope, as decide walks it
    assert [g["slope_deg"] for g in got["grounds"]] == pytest.approx([10, -10, 10])
    assert got["requirements_conditions"] == []
    moved = session.evaluate({"slope_deg": "5"})
    assert [c["name"] for c in moved["requirements_conditions"]] == ["grounds"]
    shown = moved["requirements_conditions"][0]["shown"]
    assert [g["slope"] for g in shown] == pytest.approx([np.deg2rad(5)])  # one plane, uphill
    each = [session.evaluate({"slope_deg": s})["stance"]["utilisation"] for s in ("10", "-10")]
    worst = got["stance"]["utilisation"]  # the legs coloured by the worst of the walks
    assert all(u is not None for u in worst) and np.all(np.asarray(worst) >= np.max(each, axis=0))


def test_save_writes_the_slope_slid_as_the_walking_slope_the_requirements_declare(
    tmp_path, monkeypatch
):
    session = _session(tmp_path, monkeypatch, REQUIRED)
    before = session.requirements.to_dict()
    path = session.save({"slope_deg": "-12"})  # downhill 12°: a 12° slope must be walked
    _, saved = load_design_file(path, Requirements.from_table)
    assert saved.walking_slope == pytest.approx(np.deg2rad(12), abs=1e-15)
    assert {k: v for k, v in saved.to_dict().items() if k != "walking_slope"} == before
    again = _session(tmp_path, monkeypatch, path.read_text())  # the slider starts there
    assert again.loaded()["values"]["slope_deg"] == pytest.approx(12)
    _, level = load_design_file(again.save({"slope_deg": "0"}), Requirements.from_table)
    assert level.to_dict() == before  # level ground: no walking slope written
