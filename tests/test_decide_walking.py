"""decide with walking: the speed requirement and the gait objectives against analyze_gait."""

from __future__ import annotations

import json
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest
from conftest import random_designs

from hexaleg import Gait, HexapodDesign, Payload, analyze_gait
from hexaleg.evaluation.goal import Goal, Objective
from hexaleg.evaluation.metrics import METRICS
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.robot.robot import Robot
from hexaleg.study.decide import CheckedDesign, decide
from hexaleg.study.optimize import SearchSettings
from hexaleg.study.search_space import SEGMENT_FLOOR
from hexaleg.study.sweep import base_model

STEP = 0.08
"""The step height the tests require [m] (the gait's default is 0.1 m)."""


def _walks(design, speed, payload, step_height=STEP):
    """The forward oracle: one period at ``speed`` is feasible and no peak |τ| or |q̇| is
    over its rating (GaitAnalysis.over_rating, from the time series)."""
    gait = Gait(step_height=step_height).with_speed(speed)
    walked = analyze_gait(design, gait, Payload(payload), limits=False)
    return walked.feasible and not walked.over_rating


def _walking_designs(count, seed):
    """Random legs on the default body, most of which walk the gait's 0.3 m stride, with
    random payloads [kg] and step heights [m]; and random designs of random bodies and
    postures (most of which cannot reach that stride)."""
    rng = np.random.default_rng(seed)
    drawn = [
        (HexapodDesign(l1=rng.uniform(0.05, 0.3), l2=rng.uniform(0.2, 0.35),
                       l3=rng.uniform(0.3, 0.6)), rng.uniform(0, 20), rng.uniform(0.03, 0.12))
        for _ in range(count)
    ]  # fmt: skip
    return drawn + [(design, 5.0, STEP) for design in random_designs(1, seed=seed)]


@pytest.mark.parametrize(("design", "payload", "step_height"), _walking_designs(3, seed=11))
def test_your_design_meets_the_speed_as_the_gait_analysis_says(design, payload, step_height):
    """The requirement's margin comes from the closed-form max speed; the forward walk at
    2 % below it stays within every rating, 2 % above it does not."""

    def requirements(speed):
        return Requirements(speed=speed, payload=payload, step_height=step_height)

    goal = Goal(requirements(0.2).resolved(design))
    fastest = goal.evaluate(design).metrics.value(METRICS.max_speed)
    if fastest == 0:  # cannot walk the stride within its ratings at any speed
        assert not _walks(design, 0.05, payload, step_height)
        return
    for scale, met in ((0.98, True), (1.02, False)):
        goal = Goal(requirements(fastest * scale).resolved(design))
        check = {c.name: c for c in goal.checks(goal.evaluate(design))}
        assert check["speed"].met == met == _walks(design, fastest * scale, payload, step_height)


def _decide(design, requirements, objective, evaluations):
    """The lengths searched (the posture the design's): the walk, not the posture, is tested."""
    with ThreadPoolExecutor(1) as here:
        return decide(design, requirements, objective, executor=here, progress=False,
                      settings=SearchSettings(seed=3, evaluations=evaluations),
                      free_posture=False)  # fmt: skip


def test_the_best_design_walks_at_the_reported_speed_and_not_two_percent_faster():
    design = HexapodDesign()
    requirements = Requirements(speed=0.3, payload=10.0, step_height=STEP)
    result = _decide(design, requirements, Objective("improved_area"), 90)
    assert result.feasible, result.best.checks
    best = result.best
    speed = best.evaluation.metrics.value(METRICS.max_speed)
    assert speed >= 0.3
    assert _walks(best.design, speed * (1 - 1e-9), 10.0)
    assert not _walks(best.design, speed * 1.02, 10.0)
    assert best.walking_over_rating == ()  # at the required speed: met, so within ratings
    yours_met = {c.name: c.met for c in result.yours.checks}["speed"]
    assert yours_met == _walks(design, 0.3, 10.0)
    out = result.to_dict()
    assert out["gait"]["speed"] == pytest.approx(0.3) and out["gait"]["payload"] == 10.0
    assert out["gait"]["step_height"] == STEP
    assert out["requirements"]["speed"]["limited_by"]["kind"] in ("torque", "speed")
    assert isinstance(out["yours"]["over_rating"], list)


def test_a_gait_objective_is_measured_at_the_required_speed():
    design = HexapodDesign(l2=0.3, l3=0.5)
    requirements = Requirements(speed=0.25, payload=5.0, step_height=STEP)
    goal = Goal(requirements.resolved(design), Objective("gait_peak_torque", "minimize"))
    measured = goal.evaluate(design)
    walked = analyze_gait(design, Gait(step_height=STEP).with_speed(0.25), Payload(5.0),
                          limits=False)  # fmt: skip
    assert measured.metrics.gait_peak_torque == pytest.approx(
        float(np.abs(walked.joint_torques).max()), rel=1e-12
    )
    goal = Goal(
        requirements.resolved(design), Objective("mechanical_cost_of_transport", "minimize")
    )
    assert goal.evaluate(design).metrics.mechanical_cost_of_transport == pytest.approx(
        walked.metrics.cost_of_transport, rel=1e-12
    )


def test_a_design_that_cannot_walk_the_stride_has_no_gait_objective():
    design = HexapodDesign(l1=0.05, l2=0.1, l3=0.1, nominal_angles=(0.0, 0.0, -1.2))
    goal = Goal(Requirements().resolved(design), Objective("gait_peak_torque", "minimize"))
    assert "cannot walk the gait" in goal.evaluate(design).error
    speed = Goal(Requirements(speed=0.1).resolved(design))
    found = speed.evaluate(design)
    cause = found.causes.max_speed
    assert found.metrics.max_speed == 0.0 and cause is not None and cause.kind in ("reach", "joint")


def test_a_speed_no_gait_period_reaches_is_refused_with_its_range():
    with pytest.raises(ParameterError, match=r"speed = 50 is not valid: must lie in"):
        Requirements(speed=50.0)
    with pytest.raises(HexalegError):
        Requirements(step_height=0.1)


@pytest.mark.slow
def test_a_speed_search_is_within_half_a_percent_of_a_grid_walked_forward():
    """Largest improved area with speed ≥ 0.33 m/s carrying 10 kg, l1+l2+l3 ≤ 1: the best
    design of a 4 cm grid, each walked forward at 0.33 m/s (peaks against ratings, no
    closed-form max speed), against the search."""
    design = HexapodDesign()
    requirements = Requirements(speed=0.33, payload=10.0, step_height=STEP)
    result = _decide(design, requirements, Objective("improved_area"), None)
    base = base_model(design)
    steps = np.arange(SEGMENT_FLOOR, 1.0 + 1e-9, 0.04)
    best = 0.0
    for l1 in steps:
        for l2 in steps[steps <= 1.0 - l1 - SEGMENT_FLOOR + 1e-9]:
            for l3 in steps[steps <= 1.0 - l1 - l2 + 1e-9]:
                area = 2 * np.pi * l2 * l3 / 3  # eq 16
                if area <= best:
                    continue
                try:
                    candidate = design.replace(l1=l1, l2=l2, l3=l3)
                except HexalegError:
                    continue
                gait = Gait(step_height=STEP).with_speed(0.33)
                walked = analyze_gait(candidate, gait, Payload(10.0),
                                      model=base.with_design(candidate), limits=False)  # fmt: skip
                if walked.feasible and not walked.over_rating:
                    best = area
    found = result.best.evaluation.metrics.improved_area
    assert best > 0 and result.feasible
    assert found >= (1 - 5e-3) * best
    assert _walks(result.best.design, 0.33, 10.0)


def test_a_gait_the_design_cannot_walk_is_said_so_and_no_speed_is_infinite():
    """A stride beyond every foot's reach: the walk is not measured joint by joint (its
    speeds would be unbounded), its first broken constraint is given instead, and the JSON
    holds no number JSON cannot (the oracle: the gait analysis' own violations)."""
    design, gait = HexapodDesign(), Gait(stride=1.2)
    required = Requirements(walking_payload=0.05, walked=gait).resolved(design)
    checked = CheckedDesign.of(Robot.build(over=design), Goal(required))
    walked = analyze_gait(design, required.gait, limits=False)
    assert walked.violations and not np.isfinite(np.abs(walked.joint_velocities).max())
    assert checked.walking_violation == str(walked.violations[0])
    assert checked.walking_over_rating == ()
    json.dumps([o for o in checked.over_rating()], allow_nan=False)
