"""The best posture against a brute-force grid over the stance limits, and its command.

The oracle of the search is a grid of θ2 × θ3 over the design's stance limits, every point
measured by the same single evaluation (a posture that cannot stand or misses a requirement
loses to any that does): the answer is never beaten by it, on seeded random designs. The
posture's body height and foothold radius are checked against the D-H closed form (eq 7)
written here.
"""

from __future__ import annotations

import contextlib
import io
import json
import math

import numpy as np
import pytest
from conftest import run_cli
from robots import KRABY

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.cli import main
from hexaleg.evaluation.evaluate import evaluate
from hexaleg.evaluation.goal import Goal, Objective
from hexaleg.evaluation.metrics import METRICS
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError
from hexaleg.study.posture import DEFAULT_OBJECTIVE, best_posture

GRID = 31
"""Grid points per angle of the brute-force oracle (961 postures)."""


def grid_best(design: HexapodDesign, goal: Goal) -> tuple[bool, float]:
    """(whether any grid posture meets every requirement, the best objective among those)."""
    model = HexapodModel(design)
    lower, upper = design.stance_limits.theta2, design.stance_limits.theta3
    best: tuple[bool, float] = (False, -math.inf)
    sign = 1.0 if goal.objective.sense == "maximize" else -1.0
    for theta2 in np.linspace(*lower, GRID):
        for theta3 in np.linspace(*upper, GRID):
            try:
                posed = design.replace(nominal_angles=(0.0, float(theta2), float(theta3)))
            except HexalegError:
                continue  # its feet above its body: it cannot stand
            found = evaluate(posed, goal.metrics, goal.conditions, model=model.with_design(posed))
            if found.error or not goal.meets(found):
                continue
            best = max(best, (True, sign * found.metrics.value(goal.objective.spec)))
    return best


def _designs(count: int, seed: int) -> list[HexapodDesign]:
    rng = np.random.default_rng(seed)
    designs: list[HexapodDesign] = []
    while len(designs) < count:
        try:
            designs.append(
                HexapodDesign.from_ratios(
                    rng.uniform(0.05, 0.3), rng.uniform(0.3, 0.6), body_mass=rng.uniform(30, 90),
                    body_width=rng.uniform(0.4, 0.8),
                )
            )  # fmt: skip
        except HexalegError:
            continue
    return designs


LEAST_PEAK_TORQUE = Objective(METRICS.gait_peak_torque.name, "minimize")
"""A second objective, held under a payload and a speed."""

CASES = [
    *((design, Requirements(), DEFAULT_OBJECTIVE) for design in _designs(3, seed=39)),
    *(
        (design, Requirements(payload=20.0, speed=0.2), LEAST_PEAK_TORQUE)
        for design in _designs(2, seed=40)
    ),
]


@pytest.mark.slow  # a 31 × 31 grid of evaluations per design: about 10 s each
@pytest.mark.parametrize(("design", "requirements", "objective"), CASES)
def test_the_best_posture_is_never_beaten_by_a_grid(design, requirements, objective):
    result = best_posture(design, requirements, objective)
    goal = Goal(requirements, objective)
    feasible, oracle = grid_best(design, goal)
    assert result.feasible or not feasible  # a grid posture meets them all: so does the answer
    if feasible:
        sign = 1.0 if objective.sense == "maximize" else -1.0
        value = sign * result.best.evaluation.metrics.value(objective.spec)
        assert value >= oracle - 1e-9 * max(abs(oracle), 1.0)
    theta1, theta2, theta3 = result.best.design.nominal_angles
    limits = design.stance_limits
    assert theta1 == 0.0
    assert limits.theta2[0] <= theta2 <= limits.theta2[1]
    assert limits.theta3[0] <= theta3 <= limits.theta3[1]


@pytest.fixture(scope="module")
def printed() -> dict:
    """``hexaleg posture --json`` on the default design (one search for the fast tests)."""
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["posture", "--json"]) == 0
    return json.loads(out.getvalue())


def test_the_default_legs_stand_better_than_as_posed(printed):
    best, yours = printed["best"], printed["yours"]
    assert printed["feasible"] and yours["design"] == HexapodDesign().as_dict()
    assert best["objective"]["name"] == METRICS.walking_payload_capacity.name
    assert best["objective"]["value"] > 10 * yours["objective"]["value"]  # the issue: 2 → 48 kg
    assert best["design"]["l1"] == 0.2 and best["design"]["l3"] == 0.4  # only the posture moves
    assert set(printed["search"]["free"]) == {"theta2", "theta3"}


def test_the_printed_posture_measures_the_printed_value_again(printed):
    best = printed["best"]
    posed = HexapodDesign(nominal_angles=tuple(best["design"]["nominal_angles"]))
    again = evaluate(posed, [METRICS.walking_payload_capacity])  # its own URDF, nothing derived
    value = again.metrics.walking_payload_capacity
    assert value == pytest.approx(best["objective"]["value"], rel=1e-9)


def test_the_posture_states_body_height_and_foothold_radius(printed):
    best = printed["best"]
    assert best["nominal_angles"] == best["design"]["nominal_angles"]
    theta1, theta2, theta3 = best["nominal_angles"]
    l1, l2, l3 = 0.2, 0.4, 0.4  # eq 7 at θ1 = 0: the foot's reach and depth from the root
    reach = l1 + l2 * math.cos(theta2) + l3 * math.cos(theta2 + theta3)
    depth = l2 * math.sin(theta2) + l3 * math.sin(theta2 + theta3)
    assert theta1 == 0.0
    assert best["foothold_radius"] == pytest.approx(reach, rel=1e-12)
    assert best["nominal_height"] == pytest.approx(-depth, rel=1e-12)  # roots at z = 0
    assert printed["yours"]["nominal_angles"] == [0.0, 0.0, -math.pi / 2]


@pytest.mark.slow  # one more posture search each
@pytest.mark.parametrize("command", ["gait", "loads", "flexibility"])
def test_best_posture_stands_the_design_at_the_posture_commands_answer(printed, capsys, command):
    assert run_cli([command, "--best-posture", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["design"]["nominal_angles"] == printed["best"]["design"]["nominal_angles"]
    if command == "loads":
        walking = got[METRICS.walking_payload_capacity.name]["mass"]
        assert walking == pytest.approx(printed["best"]["objective"]["value"], rel=1e-9)


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (["gait", "--best-posture", "--nominal-angles", "0", "0", "-1"], "--nominal-angles"),
        (["posture", "--maximize", "speed"], "--maximize"),
        (["posture", "--payload", "-3"], "payload"),
        (["loads", "--urdf", KRABY, "--best-posture"], "--best-posture on an imported robot"),
        (["posture", "--urdf", KRABY], "posture on an imported robot"),
    ],
)
def test_bad_posture_options_are_one_line_and_exit_2(capsys, argv, fragment):
    assert run_cli(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err and fragment in err
