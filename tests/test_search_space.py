"""The search space: free variables, their bounds, and which of them a design holds at a bound."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg import HexapodDesign
from hexaleg.exceptions import ParameterError
from hexaleg.study.search_space import AT_BOUND_SHARE, FreeVariable, bounds_reached, search_space


def _names(reached):
    return [(at.variable.name, at.bound, at.value) for at in reached]


def test_a_variable_within_a_thousandth_of_its_range_of_a_bound_is_at_it():
    l1, l2 = FreeVariable("l1", 0.02, 1.0), FreeVariable("l2", 0.1, 0.6)
    theta2 = FreeVariable("theta2", -math.pi / 6, 0.1)
    near = AT_BOUND_SHARE * 0.98 * 0.999  # just inside l1's band
    design = HexapodDesign(l1=0.02 + near, l2=0.6, nominal_angles=(0.0, 0.1, -math.pi / 2))
    assert _names(bounds_reached((l1, l2, theta2), design)) == [
        ("l1", "lower", 0.02), ("l2", "upper", 0.6), ("theta2", "upper", 0.1)]  # fmt: skip
    away = HexapodDesign(l1=0.02 + 2 * near, l2=0.35, nominal_angles=(0.0, -0.2, -1.5))
    assert bounds_reached((l1, l2, theta2), away) == ()


def test_bounds_reached_on_random_designs_matches_the_distance_to_each_bound():
    rng = np.random.default_rng(11)
    variables = (FreeVariable("l1", 0.05, 0.5), FreeVariable("l3", 0.2, 0.8))
    for _ in range(40):
        l1, l3 = rng.choice([0.05, 0.0502, 0.3, 0.4996, 0.5]), rng.uniform(0.2, 0.8)
        reached = {at.variable.name: at.bound for at in bounds_reached(
            variables, HexapodDesign(l1=l1, l3=l3))}  # fmt: skip
        band = AT_BOUND_SHARE * 0.45  # l1's range times the share: 4.5e-4 m
        expected = "lower" if l1 - 0.05 <= band else "upper" if 0.5 - l1 <= band else None
        assert reached.get("l1") == expected
        expected_l3 = "lower" if l3 - 0.2 <= 6e-4 else "upper" if 0.8 - l3 <= 6e-4 else None
        assert reached.get("l3") == expected_l3


def test_an_at_bound_says_what_binds_and_what_moves_it():
    (at,) = bounds_reached((FreeVariable("l1", 0.02, 1.0),), HexapodDesign(l1=0.02))
    assert str(at) == "l1 at its lower bound 0.02 m"
    assert "--min-coxa" in at.remedy and "--free l1=LOWER:UPPER" in at.remedy
    assert at.to_dict() == {
        "variable": "l1", "bound": "lower", "value": 0.02, "unit": "m", "binds": True,
        "description": f"l1 at its lower bound 0.02 m (binds: {at.remedy})"}  # fmt: skip


@pytest.mark.parametrize(("name", "unit"), [("l2", "m"), ("theta3", "rad"), ("front_yaw", "rad")])
def test_free_variables_know_their_unit(name, unit):
    assert FreeVariable(name, 0.1, 0.2).unit == unit


def test_bounds_on_the_stance_limits_and_the_leg_length_themselves_are_taken():
    free = [FreeVariable("theta2", -math.pi / 6, math.pi / 6),
            FreeVariable("theta3", -3 * math.pi / 4, -math.pi / 12),
            FreeVariable("l1", 0.001, 0.5)]  # fmt: skip
    space = search_space(HexapodDesign(), 0.5, free=free)
    bounds = dict(zip(space.names, zip(space.lower, space.upper, strict=True), strict=True))
    assert bounds == {"l1": (0.001, 0.5), "l2": (0.01, 0.5), "l3": (0.01, 0.5),
                      "theta2": (-math.pi / 6, math.pi / 6),
                      "theta3": (-3 * math.pi / 4, -math.pi / 12)}  # fmt: skip


@pytest.mark.parametrize(
    ("free", "min_coxa"),
    [(FreeVariable("theta2", -math.pi / 6 - 1e-9, 0.0), None),
     (FreeVariable("theta3", -1.0, -math.pi / 12 + 1e-9), None),
     (FreeVariable("l2", 0.1, 0.5 + 1e-9), None),
     (FreeVariable("l1", 0.09, 0.3), 0.1)],
)  # fmt: skip
def test_a_bound_just_beyond_its_range_is_refused(free, min_coxa):
    with pytest.raises(ParameterError, match=f"--free {free.name} = .* bounds within"):
        search_space(HexapodDesign(), 0.5, min_coxa, free=[free])


def test_the_floor_of_a_tiny_leg_is_the_shortest_segment_a_design_may_have():
    space = search_space(HexapodDesign(), 0.003)
    assert list(space.lower) == [0.001] * 3 and list(space.upper) == [0.003] * 3
