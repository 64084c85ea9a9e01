"""decide: the search against closed forms and a dense grid, conflicts, yours against loads."""

from __future__ import annotations

import json
import math
import shutil
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from conftest import random_designs, run_cli

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.evaluation.goal import Goal, Objective
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError
from hexaleg.kinematics import foot_position
from hexaleg.stance.axis_locked import axis_locked_flexibility_many
from hexaleg.stance.flexibility import flexibility
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.statics import Payload, Statics, analyze_loads, slope_gravity
from hexaleg.statics.standing_limits import Standing
from hexaleg.study.decide import decide
from hexaleg.study.executors import local_pool
from hexaleg.study.optimize import SearchSettings
from hexaleg.study.search_space import SEGMENT_FLOOR

AREA = Objective("improved_area")


def _decide(design, requirements, objective=AREA, free_posture=False, **kwargs):
    """A decision evaluated in this process (a thread), without a progress bar.

    The posture fixed unless asked: the closed forms below hold at the design's posture.
    """
    with ThreadPoolExecutor(1) as here:
        return decide(design, requirements, objective, executor=here, progress=False,
                      free_posture=free_posture, **kwargs)  # fmt: skip


def _clearance(design):
    """Body underside above the ground at the nominal stance, by the D-H foot position (eq 7)."""
    foot_z = foot_position(design.lengths, design.nominal_angles)[2]
    return -(design.legs[0].z + foot_z) - design.body_height / 2


# -- the search against closed forms -------------------------------------------------------


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_search_finds_the_closed_form_optimum_of_a_random_problem(seed):
    """Largest improved area 2π·l2·l3/3 with l1 ≥ c, l1+l2+l3 ≤ L and a clearance h: the
    best puts l1 = c and splits the rest evenly unless the tibia must be longer. On the 1 mm
    grid, the best grid point: l1 the first millimetre at or above c, and of the tibias on the
    grid long enough, the one whose femur (the millimetres left) gives the largest area."""
    rng = np.random.default_rng(seed)
    total, coxa = rng.uniform(0.6, 1.4), rng.uniform(0.05, 0.2)
    design = HexapodDesign(l1=coxa, l2=0.45 * total, l3=0.45 * total, body_height=0.1)
    clearance = rng.uniform(0.2, 0.55) * total
    requirements = Requirements(leg_length=total, min_coxa=coxa, ground_clearance=clearance)
    result = _decide(design, requirements, settings=SearchSettings(seed=seed))
    tibia = max((total - coxa) / 2, clearance + 0.05)
    best = 2 * math.pi * (total - coxa - tibia) * tibia / 3
    found = result.best.evaluation.metrics.improved_area
    assert result.feasible and all(c.met for c in result.best.checks)
    assert found == pytest.approx(best, rel=1e-2) and found <= best * (1 + 1e-9)
    mm = np.arange(1, 1401)  # every length on the grid [mm]
    l1 = math.ceil(coxa * 1000 - 1e-9)
    tibias = mm[mm >= (clearance + 0.05) * 1000]
    femurs = np.floor(total * 1000 + 1e-9) - l1 - tibias
    areas = 2 * math.pi * np.where(femurs > 0, femurs, 0) * tibias / 3 / 1e6
    k = int(np.argmax(areas))
    assert result.best.design.lengths == pytest.approx((l1 / 1e3, femurs[k] / 1e3, tibias[k] / 1e3))
    assert found == pytest.approx(areas[k], rel=1e-12)
    binds = {c.name for c in result.best.checks if c.binds}
    assert "leg_length" in binds
    assert result.bounds_binding == ()  # l1 at min_coxa: that requirement's row says it binds
    assert ("ground_clearance" in binds) == (clearance + 0.05 > (total - coxa) / 2)


def test_a_seed_gives_the_same_design_on_any_executor():
    design = HexapodDesign()
    requirements = Requirements(ground_clearance=0.4, min_coxa=0.1)
    settings = SearchSettings(seed=5, evaluations=240)
    here = _decide(design, requirements, settings=settings)
    with local_pool(2) as pool:
        there = decide(design, requirements, AREA, settings=settings, executor=pool,
                       free_posture=False)  # fmt: skip
    assert here.best.design == there.best.design
    assert here.to_dict() == there.to_dict()


def test_a_resumed_journal_ends_where_an_uninterrupted_search_does(tmp_path):
    design = HexapodDesign()
    requirements = Requirements(ground_clearance=0.4, min_coxa=0.1)
    settings = SearchSettings(seed=2, evaluations=240)
    journal = tmp_path / "decide.jsonl"
    whole = _decide(design, requirements, settings=settings, journal=journal)
    lines = journal.read_text().splitlines()
    points = [json.dumps(json.loads(line)["x"]) for line in lines[1:]]  # after the header
    assert len(points) == len(set(points)) and 0.9 * whole.evaluations < len(points)
    cut = tmp_path / "cut.jsonl"
    cut.write_text("\n".join(lines[:100]) + "\n" + lines[100][:20])  # killed mid-line
    resumed = _decide(design, requirements, settings=settings, journal=cut, resume=True)
    assert resumed.to_dict() == whole.to_dict()
    assert sorted(cut.read_text().splitlines()[100:]) == sorted(lines[100:])
    with pytest.raises(Exception, match="exists: pass --resume"):
        _decide(design, requirements, settings=settings, journal=journal)
    other = tmp_path / "other.jsonl"
    shutil.copy(journal, other)
    with pytest.raises(Exception, match="no decision with these options"):
        _decide(design, requirements.replace(ground_clearance=0.3), settings=settings,
                journal=other, resume=True)  # fmt: skip


# -- conflicts --------------------------------------------------------------------------


@pytest.mark.parametrize("seed", [5, 6])
def test_a_free_variable_pressed_against_its_search_bound_binds(seed):
    """Largest improved area 2π·l2·l3/3 with only l1+l2+l3 ≤ L: the best puts l1 at the
    search's floor (SEGMENT_FLOOR·L) and splits the rest evenly, so l1's bound binds."""
    from hexaleg.cli.decide import render

    total = np.random.default_rng(seed).uniform(0.6, 1.4)
    design = HexapodDesign(l1=0.1 * total, l2=0.45 * total, l3=0.45 * total)
    result = _decide(design, Requirements(leg_length=total), settings=SearchSettings(seed=seed))
    floor = SEGMENT_FLOOR * total
    assert result.best.design.l1 == pytest.approx(floor, abs=1e-3 * total)
    assert [(at.variable.name, at.bound, at.value) for at in result.bounds_binding] == [
        ("l1", "lower", pytest.approx(floor))
    ]
    text = render(result).split("Your design")[0]
    row = next(line for line in text.splitlines() if "l1 searched in" in line)
    assert f"{floor:.4g} m" in row and "its lower bound" in row and "binds" in row
    assert "--min-coxa" in row
    (entry,) = result.to_dict()["best"]["bounds_binding"]
    assert entry["variable"] == "l1" and entry["bound"] == "lower" and entry["binds"] is True
    assert entry["value"] == pytest.approx(floor) and entry["unit"] == "m"


def test_an_infeasible_problem_names_the_conflict_and_the_nearest_relaxations():
    """Clearance 0.6 m needs l3 ≥ 0.65 and the coxa 0.5 m, but the leg is 1 m: relaxing the
    clearance leaves l3 = 1 − 0.5 − floor, the coxa 1 − floor − 0.65, the leg 0.5 + floor + 0.65."""
    design = HexapodDesign()  # 0.1 m body: clearance = l3 − 0.05
    requirements = Requirements(ground_clearance=0.6, min_coxa=0.5)
    result = _decide(design, requirements, settings=SearchSettings(seed=0, evaluations=720))
    floor = SEGMENT_FLOOR * 1.0
    assert not result.feasible
    conflict = result.conflict
    assert conflict is not None
    assert set(conflict.requirements) == {"ground_clearance", "min_coxa", "leg_length"}
    relaxed = {r.name: r.relaxed for r in conflict.relaxations}
    assert relaxed["ground_clearance"] == pytest.approx(1 - 0.5 - floor - 0.05, rel=5e-3)
    assert relaxed["min_coxa"] == pytest.approx(1 - floor - 0.65, rel=5e-3)
    assert relaxed["leg_length"] == pytest.approx(0.5 + floor + 0.65, rel=5e-3)
    assert "cannot all hold" in conflict.description
    assert result.to_dict()["conflict"]["requirements"] == list(conflict.requirements)


# -- the user's design, exactly -------------------------------------------------------------


def _stands(statics, mass, slope, headings=90):
    """The statics' verdict: standing with ``mass`` on every slope up to ``slope``, all headings."""
    q = statics.model.nominal_configuration()
    payload = statics.payload.with_mass(mass)
    for alpha in np.linspace(0.0, slope, 5):
        for heading in np.linspace(-math.pi, math.pi, headings, endpoint=False):
            state = statics.state(q, gravity=slope_gravity(alpha, heading), payload=payload)
            if np.any(np.abs(state.joint_torques) > statics.rated) or state.stability_margin <= 0:
                return False
    return math.tan(slope) <= statics.friction


@pytest.mark.parametrize("design", random_designs(2, seed=4))
def test_your_design_passes_or_fails_as_loads_and_flexibility_say(design):
    point = (0.1, -0.05, design.body_height / 2)
    loads = analyze_loads(design, Payload(0.0, point))
    fb = flexibility(design, "axis").fb
    capacity = loads.capacity.mass
    for scale in (0.98, 1.02):
        requirements = Requirements(
            payload=max(capacity * scale, 1e-3),
            payload_at=point,
            min_fb=fb * scale,
            ground_clearance=_clearance(design) * scale,
            leg_length=design.leg_length / scale,
            min_coxa=design.l1 * scale,
        )
        goal = Goal(requirements.resolved(design))
        met = {c.name: c.met for c in goal.checks(goal.evaluate(design))}
        payload = requirements.payload_mass
        carried = analyze_loads(design, Payload(payload, point)).capacity.mass
        assert met["payload"] == (carried >= payload - 1e-9) == (scale < 1)
        assert met["min_fb"] == (fb >= fb * scale) == (scale < 1)
        assert met["ground_clearance"] == met["leg_length"] == met["min_coxa"] == (scale < 1)
    model = HexapodModel(design)
    statics = Statics(model, model.leg_names, Payload(0.0, point))
    for slope in (math.radians(5), math.radians(20)):
        mass = 0.3 * capacity
        goal = Goal(Requirements(payload=mass, payload_at=point, slope=slope).resolved(design))
        checks = {c.name: c for c in goal.checks(goal.evaluate(design))}
        assert checks["slope"].met == checks["payload"].met == _stands(statics, mass, slope)


def test_the_search_fast_path_measures_as_the_exact_one():
    """Models derived without Xacro and geometry from a template, against each design's own
    URDF: payload and slope, FB, clearance agree to round-off, posture changed too."""
    base = HexapodDesign()
    template = StanceGeometry.from_model(HexapodModel(base))
    requirements = Requirements(payload=20.0, slope=0.2, ground_clearance=0.1, min_fb=0.1)
    goal = Goal(requirements.resolved(base), Objective("average_manipulability"))
    rng = np.random.default_rng(9)
    designs = []
    while len(designs) < 3:
        l1, l2, l3 = rng.uniform(0.05, 0.5, 3)
        angles = (0.0, rng.uniform(-0.4, 0.4), rng.uniform(-2.0, -1.0))
        try:
            designs.append(base.replace(l1=l1, l2=l2, l3=l3, nominal_angles=angles))
        except HexalegError:  # its feet above the body: draw again
            continue
    for design in designs:
        fast = goal.evaluate(design, HexapodModel(base).with_design(design), template)
        exact = goal.evaluate(design)
        assert not exact.error, exact.error
        assert fast.metrics.to_dict().keys() == exact.metrics.to_dict().keys()
        for name, value in exact.metrics.to_dict().items():
            assert fast.metrics.to_dict()[name] == pytest.approx(value, rel=1e-9, abs=1e-12), name


# -- the answer's shape and the command ---------------------------------------------------


def test_the_json_answer_has_exactly_the_documented_fields():
    result = _decide(HexapodDesign(), Requirements(ground_clearance=0.3), free_posture=True,
                     settings=SearchSettings(evaluations=100))  # fmt: skip
    out = result.to_dict()
    assert set(out) == {"requirements", "best", "yours", "feasible", "rounded", "search"}
    posture = {"nominal_angles", "nominal_height", "foothold_radius"}
    assert set(out["best"]) >= {"design", "objective", "bounds_binding"} | posture
    assert set(out["best"]["objective"]) >= {"name", "value", "limited_by"}
    assert set(out["yours"]) >= {"design", "requirements"} | posture
    assert set(out["search"]) >= {"method", "evaluations", "seed"}
    assert set(out["rounded"]) == {"resolution", "angle_step", "searched", "grid_points_measured"}
    assert set(out["rounded"]["searched"]) == {"l1", "l2", "l3", "theta2", "theta3"}
    for entry in out["requirements"].values():
        assert set(entry) >= {"required", "value", "margin", "binds", "at_limit"}
    for entry in out["yours"]["requirements"].values():
        assert set(entry) >= {"required", "value", "margin", "met"}
    json.dumps(out, allow_nan=False)


def test_every_requirement_says_what_limits_it_and_joints_over_ratings_are_flagged():
    """The user's design, carrying more than its capacity: its flags are the loads
    analysis's (nominal stance and the 12 extremes) with that payload."""
    design = HexapodDesign()
    payload = 1.2 * analyze_loads(design).capacity.mass
    requirements = Requirements(payload=payload, ground_clearance=0.2, min_fb=0.1, min_coxa=0.1)
    result = _decide(design, requirements, settings=SearchSettings(evaluations=60))
    out = result.to_dict()
    for block in (out["requirements"], out["yours"]["requirements"]):
        for entry in block.values():
            assert entry["limited_by"]["description"]
    assert out["yours"]["requirements"]["payload"]["limited_by"]["kind"] == "torque"
    loads = analyze_loads(design, Payload(payload))
    assert loads.over_rating  # more than its capacity: some joint is over its rating
    assert result.yours.standing_over_rating == loads.over_rating
    assert [f["description"] for f in out["yours"]["over_rating"]] == [
        str(f) for f in loads.over_rating
    ]
    assert {f["while"] for f in out["yours"]["over_rating"]} == {"standing"}
    best_loads = analyze_loads(result.best.design, Payload(payload))
    assert result.best.standing_over_rating == best_loads.over_rating


def test_decide_command_prints_json_and_reads_the_design_file_table(tmp_path, capsys):
    path = tmp_path / "robot.toml"
    path.write_text("l1 = 0.15\n\n[requirements]\nground_clearance = 0.3\nmin_coxa = 0.1\n")
    argv = ["decide", "--design", str(path), "--maximize", "improved_area", "--min-coxa", "0.12",
            "--evaluations", "100", "--workers", "1", "--json"]  # fmt: skip
    assert run_cli(argv) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["feasible"] is True
    assert out["requirements"]["min_coxa"]["required"] == 0.12  # the option overrides the file
    assert out["requirements"]["ground_clearance"]["required"] == 0.3
    assert out["yours"]["requirements"]["min_coxa"]["met"] is True
    assert out["yours"]["design"]["l1"] == 0.15


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["--payload", "-3"], "--payload = -3 is not valid"),
        (["--slope-deg", "95"], "--slope-deg = 95 is not valid"),
        (["--resume"], "--resume continues a --journal"),
        (["--free", "body_width=0.8:0.4"], "LOWER must be below UPPER"),
        (["--free", "wheels=1:2"], "a field among"),
        (["--speed", "50"], "--speed = 50 is not valid"),
        (["--step-height", "0.1"], "needs a speed"),
        (
            ["--walking-slope-deg", "61"],
            "--walking-slope-deg = 61 is not valid: must lie in [0, 60]",
        ),
        (
            ["--motor-safety-factor", "0.9"],
            "--motor-safety-factor = 0.9 is not valid: must lie in [1, 100]",
        ),
        (["--resolution", "0"], "--resolution = 0 is not valid: must lie in [1e-06, 0.1] [m]"),
    ],
)
def test_decide_refuses_bad_input_in_one_line(argv, words, capsys):
    assert run_cli(["decide", *argv]) == 2
    err = capsys.readouterr().err
    assert words in err and len(err.strip().splitlines()) == 1


def test_decide_help_gives_the_range_of_evaluations_its_error_names(capsys):
    assert run_cli(["decide", "--evaluations", "3"]) == 2
    allowed = capsys.readouterr().err.split("must be in ")[1].split()[0]
    assert allowed == "48..100000"
    assert run_cli(["decide", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "(at least 24), at most 100000 " in text


# -- the dense grid ---------------------------------------------------------------------


@pytest.mark.slow
def test_search_is_within_half_a_percent_of_a_dense_grid():
    """Three free lengths, payload and slope required, FB maximized: the best feasible design
    of a 2 cm grid of exact evaluations (written here from the analyses' APIs) vs the search."""
    design = HexapodDesign()
    slope = math.radians(20)
    requirements = Requirements(payload=60.0, slope=slope).resolved(design)
    result = _decide(design, requirements, Objective("fb"), settings=SearchSettings(seed=4))
    base = HexapodModel(design)
    template = StanceGeometry.from_model(base)
    steps = np.arange(SEGMENT_FLOOR, 1.0 + 1e-9, 0.02)
    best = 0.0
    for l1 in steps:
        designs = []
        for l2 in steps[steps <= 1.0 - l1 - SEGMENT_FLOOR + 1e-9]:
            for l3 in steps[steps <= 1.0 - l1 - l2 + 1e-9]:
                try:
                    designs.append(design.replace(l1=l1, l2=l2, l3=l3))
                except HexalegError:  # cannot stand: its feet above the body's underside
                    continue
        if not designs:
            continue
        found = axis_locked_flexibility_many(designs, template, [base] * len(designs))
        for candidate, flexible in zip(designs, found, strict=True):
            if flexible.fb <= best:
                continue
            model = base.with_design(candidate)
            standing = Standing.of(Statics(model, model.leg_names, Payload(0.0)))
            if standing.max_payload(slope)[0] >= requirements.payload_mass:
                best = flexible.fb
    found = result.best.evaluation.metrics.fb
    assert result.feasible and all(c.met for c in result.best.checks)
    assert found >= (1 - 5e-3) * best


def test_a_task_of_designs_that_cannot_exist_is_measured_as_errors():
    from hexaleg.study.optimize import _Task, evaluate_points
    from hexaleg.study.search_space import search_space

    design = HexapodDesign()
    goal = Goal(Requirements(min_fb=0.1).resolved(design))
    space = search_space(design, 1.0)
    found = evaluate_points(_Task(space, goal, ((0.5, 0.5, 0.01), (0.3, 0.3, 0.02))))
    assert all(e.error for e in found)
