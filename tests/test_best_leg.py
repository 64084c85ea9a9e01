"""The searches behind the recommendation, held against brute force on seeded random legs.

Oracle: a brute-force grid over the hip and knee angles (and the tibia ratio) within the
stance limits, each point measured and costed exactly as the search costs it
(:meth:`~hexaleg.study.best_leg.Legs.cost`: feasibility first, then −log score). The
search must find a cost no higher than the grid's best, and never above the posture given.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from hexaleg import HexapodDesign
from hexaleg.evaluation.evaluate import Conditions, evaluate
from hexaleg.robot.recipe import RobotSource
from hexaleg.robot.robot import robot_of
from hexaleg.study.best_leg import Legs, best_leg_at, best_posture_of
from hexaleg.study.ranking import RANKED_METRICS, WALKING, WalkingConstraint

METRICS_ = (*RANKED_METRICS, WALKING)
GRID = 6


def _random_legs(seed: int):
    rng = np.random.default_rng(seed)
    l1, l3 = rng.uniform(0.1, 0.2), rng.uniform(0.35, 0.5)
    base = HexapodDesign(l1=l1, l2=1.0 - l1 - l3, l3=l3)
    limits = base.stance_limits
    theta2 = rng.uniform(*limits.theta2) * 0.3
    theta3 = -np.pi / 2 + rng.uniform(-0.15, 0.15)
    design = HexapodDesign(l1=l1, l2=1.0 - l1 - l3, l3=l3, nominal_angles=(0.0, theta2, theta3))
    robot = robot_of(RobotSource(), design)
    conditions = Conditions()
    yours = evaluate(design, METRICS_, conditions, model=robot.model)
    return robot, Legs(robot, METRICS_, conditions, WalkingConstraint(), yours.metrics)


@pytest.mark.slow  # ~300 legs walked per seed
@pytest.mark.parametrize("seed", [11, 12])
def test_the_best_posture_is_no_worse_than_a_brute_force_grid_or_the_posture_given(seed):
    robot, legs = _random_legs(seed)
    found = best_posture_of(legs, robot)
    assert found.design.lengths == robot.design.lengths  # only the posture changes
    given = legs.posed(robot, robot.design.nominal_angles[1:])
    assert legs.cost(found) <= legs.cost(given)
    limits = robot.design.stance_limits
    grid = [
        legs.posed(robot, (a, b))
        for a, b in itertools.product(
            np.linspace(*limits.theta2, GRID), np.linspace(*limits.theta3, GRID)
        )
    ]
    assert legs.cost(found) <= min(legs.cost(leg) for leg in grid)
    if given is not None and given.ranked:  # your posture ranked: the re-posed scores ≥ 1
        assert found.score >= 1.0


@pytest.mark.slow  # ~500 legs walked
def test_the_best_leg_at_a_coxa_ratio_is_no_worse_than_a_brute_force_grid():
    robot, legs = _random_legs(13)
    l3_range = (0.3, 0.6)
    found = best_leg_at(legs, 0.1, l3_range)
    assert found is not None and found.l1_ratio == pytest.approx(0.1)
    limits = robot.design.stance_limits
    grid = [
        legs.at(0.1, r3, (a, b))
        for r3, a, b in itertools.product(
            np.linspace(*l3_range, 4),
            np.linspace(*limits.theta2, 4),
            np.linspace(*limits.theta3, 4),
        )
    ]
    assert legs.cost(found) <= min(legs.cost(leg) for leg in grid)
