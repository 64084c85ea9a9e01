"""The walking payload capacity against a bisection on the gait analysis itself."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg import HexapodDesign, HexapodModel, analyze_gait
from hexaleg.gait.capacity import walking_payload_capacity
from hexaleg.gait.spec import Gait
from hexaleg.statics.forces import Payload


def _walks(design, model, gait, mass, position) -> bool:
    """The oracle's predicate: the period is feasible, within every rating, the ZMP inside."""
    walked = analyze_gait(design, gait, Payload(mass, position), model=model, limits=False)
    return walked.feasible and not walked.over_rating and walked.min_zmp_margin >= 0


def _bisect(design, model, gait, position, upper) -> float:
    low, high = 0.0, upper
    while high - low > 1e-7:
        middle = (low + high) / 2
        low, high = (
            (middle, high) if _walks(design, model, gait, middle, position) else (low, middle)
        )
    return low


def _cases(count: int, seed: int):
    rng = np.random.default_rng(seed)
    for _ in range(count):
        ratings = tuple(rng.uniform([60, 180, 150], [120, 300, 250]))
        design = HexapodDesign.from_ratios(
            rng.uniform(0.08, 0.2), rng.uniform(0.35, 0.6), rated_torques=ratings
        )
        position = tuple(rng.uniform([-0.3, -0.2, 0.0], [0.3, 0.2, 0.2]))
        gait = Gait(period=rng.uniform(1.5, 3.0), stride=rng.uniform(0.15, 0.3))
        yield design, position, gait


@pytest.mark.parametrize(("design", "position", "gait"), list(_cases(4, seed=2)))
def test_the_capacity_equals_a_bisection_on_analyze_gait(design, position, gait):
    model = HexapodModel(design)
    found = walking_payload_capacity(model, gait, position)
    assert found.walks and found.limited_by.kind == "torque"
    oracle = _bisect(design, model, gait, position, 2 * found.mass + 1)
    assert found.mass == pytest.approx(oracle, abs=1e-6)


def test_a_payload_far_out_is_limited_by_the_zmp_leaving_the_feet():
    design = HexapodDesign(rated_torques=(1e5, 1e5, 1e5))
    model, gait, position = HexapodModel(design), Gait(), (2.0, 0.0, 0.05)
    found = walking_payload_capacity(model, gait, position)
    assert found.limited_by.kind == "zmp" and str(found.limited_by) == (
        "ZMP leaves the support polygon"
    )
    assert found.mass == pytest.approx(_bisect(design, model, gait, position, 100.0), abs=1e-6)


def test_a_design_that_cannot_walk_unloaded_carries_nothing_and_says_why():
    slow = HexapodDesign(rated_speeds=(0.2, 0.2, 0.2))  # the gait's joints turn faster
    found = walking_payload_capacity(HexapodModel(slow))
    assert not found.walks and found.mass == 0.0 and found.limited_by.kind == "speed"
    weak = HexapodDesign(rated_torques=(60.0, 40.0, 120.0))  # the hips cannot hold the body
    found = walking_payload_capacity(HexapodModel(weak))
    assert not found.walks and found.mass == 0.0
    assert str(found.limited_by).endswith("hip torque at its rating")
    assert not _walks(weak, HexapodModel(weak), Gait(), 0.0, None)


def test_the_capacity_bound_by_the_zmp_is_where_the_gait_turns_infeasible():
    """The capacity and ``feasible`` agree: just under it feasible, just over it tipping."""
    design = HexapodDesign(rated_torques=(1e5, 1e5, 1e5))
    model, gait, position = HexapodModel(design), Gait(samples=60), (1.0, 0.3, 0.05)
    found = walking_payload_capacity(model, gait, position)
    assert found.walks and found.limited_by.kind == "zmp" and found.mass > 0
    below, above = (
        analyze_gait(design, gait, Payload(found.mass * f, position), model=model, limits=False)
        for f in (1 - 1e-6, 1 + 1e-6)
    )
    assert below.feasible and below.tipping is None
    assert not above.feasible and above.walkable and above.tipping.cause == found.limited_by
