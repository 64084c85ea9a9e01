"""The planned gait walked in MuJoCo: each kind of robot walks; impossible gaits are refused.

Oracles: the plan itself (its distance, its peak torques from Pinocchio's inverse dynamics)
and the statics' foot forces for the robot standing on a tripod (the statics held to RNEA
on the raw file in ``test_robot_loads``, to closed forms in ``test_statics``).
"""

from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest
from robots import KINDS, robot_of

from hexaleg import HexapodDesign
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.gait import Gait, analyze_gait
from hexaleg.statics.forces import Payload

if not os.environ.get("CI"):  # CI installs hexaleg[test], which includes the sim extra
    pytest.importorskip("mujoco")

from hexaleg.sim import simulate, simulate_gait

JSON_KEYS = {
    "design",
    "gait",
    "payload",
    "cycles",
    "controller",
    "diverged",
    "planned_distance",
    "distance",
    "max_tilt",
    "min_height",
    "fell",
    "tracking_rms",
    "slip",
    "internal_force",
    "peak_torque_measured",
    "over_rating",
    "peak_torque_planned",
    "standing",
}


SMALL = Gait(stride=0.03, step_height=0.02, period=0.8)
"""A short walk the small robot file takes (the default gait's stride is beyond its reach)."""


@pytest.fixture(scope="module", params=KINDS)
def walk(request):
    """The kind's robot walked: the template four default cycles, the robot file three small."""
    if request.param == "template":
        return simulate_gait(HexapodDesign(), Gait(), cycles=4), HexapodDesign(), None
    robot = robot_of(request.param)
    walked = simulate_gait(robot.design, SMALL, cycles=3, model=robot.model)
    return walked, robot.design, robot.model


def test_each_robot_walks_its_tripod_cycles_and_stands_as_the_statics_say(walk):
    walked, design, _ = walk
    metrics = walked.metrics
    gait = walked.gait
    assert gait.pattern == "tripod"
    assert not metrics.fell
    measured = walked.cycles - 1  # the first period is not measured
    assert metrics.planned_distance == pytest.approx(gait.speed * gait.period * measured)
    assert metrics.distance >= 0.9 * metrics.planned_distance
    assert metrics.distance <= 1.1 * metrics.planned_distance
    assert metrics.max_tilt < math.radians(5.0)
    assert metrics.min_height > 0.9 * design.nominal_height
    assert metrics.tracking_rms < 0.05
    standing = walked.standing
    for leg, force in standing.foot_forces_z.items():
        assert force == pytest.approx(standing.statics_foot_forces_z[leg], rel=0.03)


def test_measured_hip_and_knee_torques_are_near_the_plans(walk):
    # Pinocchio's inverse dynamics with min-norm feet against MuJoCo's contacts and servos
    walked, design, model = walk
    planned, measured = walked.planned_peak_torque, walked.metrics.peak_torque
    for joint in ("hip", "knee"):
        assert measured[joint] == pytest.approx(planned[joint], rel=0.10)
    again = analyze_gait(design, walked.gait, limits=False, model=model)
    assert planned == again.metrics.peak_torque


def test_json_has_exactly_the_documented_fields(walk):
    walked, design, _ = walk
    fields = json.loads(json.dumps(walked.to_dict()))
    assert set(fields) == JSON_KEYS
    assert set(fields["standing"]) == {"foot_forces_z", "statics_foot_forces_z"}
    assert set(fields["standing"]["foot_forces_z"]) == {"lf", "rm", "lr"}
    for key in ("peak_torque_measured", "peak_torque_planned"):
        assert set(fields[key]) == {"root", "hip", "knee"}
    assert fields["gait"]["pattern"] == "tripod"
    top = [0.0, 0.0, design.body_height / 2]  # none, on the centre of the body's top face
    assert fields["payload"] == {"mass": 0.0, "position": pytest.approx(top)}
    assert fields["fell"] is False
    assert fields["controller"] == "servo" and fields["diverged"] is None


def test_frames_cover_the_run(walk):
    walked = walk[0]
    frames = walked.frames
    duration = walked.cycles * walked.gait.period
    assert len(frames) == pytest.approx(duration * walked.frame_rate, abs=1)
    travelled = frames[-1, 0] - frames[0, 0]  # every cycle, the measured ones' distance
    whole = walked.metrics.distance * walked.cycles / (walked.cycles - 1)
    assert travelled == pytest.approx(whole, rel=0.15)
    mid = frames[walked.mid_stride_frame]
    assert np.isfinite(mid).all()


def test_an_over_long_stride_is_refused_before_simulating(monkeypatch):
    design = HexapodDesign()
    gait = Gait(stride=0.9)  # the default robot's max stride is about 0.62 m at H = 0.1 m

    def no_simulation(*args, **kwargs):
        raise AssertionError("simulated an infeasible gait")

    monkeypatch.setattr(simulate, "SimModel", no_simulation)
    monkeypatch.setattr(simulate, "run_plan", no_simulation)
    with pytest.raises(
        ParameterError, match=r"stride = 0\.9 is not valid: must be at most 0\.6"
    ) as e:
        simulate_gait(design, gait)
    assert "\n" not in str(e.value) and "max stride" in str(e.value)


def test_a_step_too_high_is_refused_by_its_first_violation(monkeypatch):
    monkeypatch.setattr(simulate, "run_plan", None)  # never reached
    with pytest.raises(HexalegError, match="cannot walk the gait: t = "):
        simulate_gait(HexapodDesign(), Gait(stride=0.2, step_height=0.5))


@pytest.mark.parametrize("cycles", [1, 0, 201, 2.5, True])
def test_cycles_out_of_range_are_refused(cycles):
    with pytest.raises(ParameterError, match="cycles"):
        simulate_gait(HexapodDesign(), cycles=cycles)


@pytest.mark.slow
def test_the_default_robot_walks_with_a_payload():
    walk = simulate_gait(HexapodDesign(), Gait(), Payload(40.0), cycles=4)
    metrics = walk.metrics
    assert not metrics.fell
    assert metrics.distance >= 0.85 * metrics.planned_distance
    assert metrics.max_tilt < math.radians(5.0)
    assert walk.standing.worst_relative_error < 0.03
    assert walk.to_dict()["payload"]["mass"] == 40.0


@pytest.mark.slow
def test_random_designs_walk_half_their_max_stride():
    from conftest import random_designs

    walked = 0
    for design in random_designs(8, seed=77):
        stride = 0.5 * analyze_gait(design).max_stride.value
        gait = Gait(stride=max(stride, 1e-3), step_height=min(0.1, 0.25 * design.nominal_height))
        if stride < 0.02 or not analyze_gait(design, gait, limits=False).feasible:
            continue  # postures that barely step, or a step too high for the legs
        metrics = simulate_gait(design, gait).metrics
        assert not metrics.fell, design
        assert metrics.distance >= 0.85 * metrics.planned_distance, design
        assert metrics.max_tilt < math.radians(5.0), design
        walked += 1
    assert walked >= 3


@pytest.mark.slow  # two simulated walks, seconds each
def test_a_torque_controlled_robot_needs_what_the_plan_says():
    """The plan's torques with a low-gain PD: every joint type's measured peak within 10 %
    of the plan's (the oracle: the gait analysis' own peaks, Pinocchio's inverse dynamics),
    the standing feet barely pushing on each other; stiff servos need far more at the
    roots and squeeze the feet."""
    planned = analyze_gait(HexapodDesign(), Gait(), limits=False).metrics.peak_torque
    torque = simulate_gait(HexapodDesign(), Gait(), controller="torque")
    servo = simulate_gait(HexapodDesign(), Gait(), controller="servo")
    assert torque.controller == "torque" and not torque.diverged and not torque.metrics.fell
    for joint, value in torque.metrics.peak_torque.items():
        assert value == pytest.approx(planned[joint], rel=0.10), joint
    assert servo.metrics.peak_torque["root"] > 2 * planned["root"]
    assert servo.metrics.internal_force > 3 * torque.metrics.internal_force
    assert torque.metrics.distance >= 0.95 * torque.metrics.planned_distance


def test_a_bad_controller_is_refused_naming_it():
    with pytest.raises(ParameterError, match="controller = 'position' is not valid"):
        simulate_gait(HexapodDesign(), controller="position")
