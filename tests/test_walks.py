"""The walking slope and the motors' safety factor reach every walking metric of evaluate().

The oracle walks the same gait with the single-design analyses on three grounds written
here from their definitions (rising along the walk, falling along it, rising across it),
each with the safety factor F, and takes each metric's worst by hand.
"""

from __future__ import annotations

import math

import pytest

from hexaleg import HexapodDesign, HexapodModel, Payload, analyze_gait
from hexaleg.evaluation.evaluate import Conditions
from hexaleg.evaluation.goal import Goal, Objective
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import ParameterError
from hexaleg.gait.capacity import walking_payload_capacity
from hexaleg.statics.ground import Ground

SLOPE, F, PAYLOAD, SPEED = math.radians(8), 1.2, 5.0, 0.2


def test_each_walking_metric_is_the_worst_of_up_down_and_across():
    design = HexapodDesign(body_mass=30.0)  # light enough to walk 8° within ratings / F
    requirements = Requirements(payload=PAYLOAD, speed=SPEED, walking_payload=1.0,
                                walking_slope=SLOPE, motor_safety_factor=F)  # fmt: skip
    goal = Goal(requirements.resolved(design), Objective("gait_peak_torque", "minimize"))
    conditions = goal.conditions
    assert conditions.safety_factor == F and len(conditions.grounds) == 3
    found = goal.evaluate(design).metrics
    gait = requirements.gait
    grounds = [Ground(SLOPE, 0.0), Ground(SLOPE, math.pi), Ground(SLOPE, math.pi / 2)]
    model = HexapodModel(design)
    walked = [analyze_gait(design, gait, Payload(PAYLOAD), ground=ground, model=model,
                           limits=False, speed=True, safety_factor=F)
              for ground in grounds]  # fmt: skip
    speeds = [w.max_speed.value for w in walked]
    peaks = [max(w.metrics.peak_torque.values()) for w in walked]
    carried = [walking_payload_capacity(model, gait, ground=ground, safety_factor=F).mass
               for ground in grounds]  # fmt: skip
    assert found.max_speed == pytest.approx(min(speeds), rel=1e-9)
    assert found.gait_peak_torque == pytest.approx(max(peaks), rel=1e-9)
    assert found.walking_payload_capacity == pytest.approx(min(carried), rel=1e-6)
    assert max(carried) > min(carried) * (1 + 1e-6)  # the walks differ: the worst is chosen
    level = walking_payload_capacity(model, gait, safety_factor=F).mass
    assert found.walking_payload_capacity < level  # a slope walked carries less than level


def test_conditions_refuse_no_ground_and_a_factor_below_one():
    with pytest.raises(ParameterError, match="grounds"):
        Conditions(grounds=())
    with pytest.raises(ParameterError, match="safety_factor"):
        Conditions(safety_factor=0.9)
