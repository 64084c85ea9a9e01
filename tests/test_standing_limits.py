"""Standing on a slope with a payload against brute force: the statics at every heading."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import random_designs

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.statics import Payload, Statics, payload_capacity, slope_gravity
from hexaleg.statics.standing_limits import Standing


def _headings(count):
    return np.linspace(-math.pi, math.pi, count + 1)[:-1]


def _brute_force(statics, mass, slopes, headings=120):
    """The statics' own verdict on each heading and slope: worst |τ| per joint and whether
    every pose stands (torques within ratings, gravity line inside, no sliding)."""
    q = statics.model.nominal_configuration()
    payload = statics.payload.with_mass(mass)
    worst = np.zeros((len(statics.legs), 3))
    stands = True
    for slope in slopes:
        for heading in _headings(headings):
            state = statics.state(q, gravity=slope_gravity(slope, heading), payload=payload)
            worst = np.maximum(worst, np.abs(state.joint_torques))
            stands &= bool(state.stability_margin > 0)
        stands &= math.tan(slope) <= statics.friction
    return worst, stands and bool(np.all(worst <= statics.rated))


@pytest.fixture(scope="module")
def cases():
    """Statics of random designs, each with a payload at a random point on the body."""
    rng = np.random.default_rng(7)
    found = []
    for design in random_designs(3, seed=11):
        point = (*rng.uniform(-0.2, 0.2, 2), rng.uniform(0.0, 0.2))
        model = HexapodModel(design)
        found.append(Statics(model, model.leg_names, Payload(0.0, point)))
    return found


def test_level_payload_equals_the_statics_payload_capacity(cases):
    for statics in cases:
        capacity = payload_capacity(statics, statics.model.nominal_configuration())
        mass, _ = Standing.of(statics).max_payload(0.0)
        assert mass == pytest.approx(capacity.mass, rel=1e-9, abs=1e-9)


def test_worst_torques_are_the_largest_over_every_heading_and_lower_slope(cases):
    rng = np.random.default_rng(3)
    for statics in cases[:2]:
        standing = Standing.of(statics)
        mass, slope = rng.uniform(0, 60), rng.uniform(0.05, 0.5)
        worst, _ = _brute_force(statics, mass, np.linspace(0.0, slope, 9))
        found = standing.worst_torques(mass, slope)
        # 3° apart, sampled headings reach the largest |τ| to 1 − cos 1.5° = 3.4e-4 of it;
        # the largest over slopes lies at the end or where the curve is flat
        assert np.all(found >= worst - 1e-9)
        np.testing.assert_allclose(found, worst, rtol=1e-3, atol=1e-6)


@pytest.mark.slow
def test_max_slope_is_where_brute_force_first_fails(cases):
    for statics in cases:
        standing = Standing.of(statics)
        for mass in (0.0, 40.0):
            slope, cause = standing.max_slope(mass)
            if slope <= 0.01:
                assert not _brute_force(statics, mass, [slope + 0.01])[1]
                continue
            below = np.linspace(0.0, slope - 0.005, 8)
            assert _brute_force(statics, mass, below, headings=360)[1], cause
            assert not _brute_force(statics, mass, [slope + 0.005], headings=360)[1], cause


def test_max_payload_on_a_slope_is_where_brute_force_first_fails():
    design = HexapodDesign(l1=0.15, l2=0.45, l3=0.4)
    model = HexapodModel(design)
    for point in (None, (0.25, -0.1, 0.15)):
        statics = Statics(model, model.leg_names, Payload(0.0, point))
        slope = math.radians(15)
        mass, cause = Standing.of(statics).max_payload(slope)
        slopes = np.linspace(0.0, slope, 6)
        assert 0 < mass < 1e4
        assert _brute_force(statics, mass * (1 - 1e-3), slopes)[1], cause
        assert not _brute_force(statics, mass * (1 + 1e-3), slopes)[1], cause


def test_a_slope_steeper_than_friction_holds_nothing(cases):
    standing = Standing.of(cases[0])
    mass, cause = standing.max_payload(math.atan(standing.friction) + 0.01)
    assert mass == 0.0 and cause.kind == "slide"
    slope, _ = standing.max_slope(0.0)
    assert slope <= math.atan(standing.friction)


def test_tip_payload_is_where_the_footprint_reaches_an_edge():
    """A payload far outside the polygon tips the robot where the centre of mass's
    footprint crosses the polygon's edge: found here by the statics' own margin."""
    design = HexapodDesign()
    model = HexapodModel(design)
    statics = Statics(model, model.leg_names, Payload(0.0, (3.0, 0.0, 0.05)))
    standing = Standing.of(statics)
    mass = standing.tip_payload(0.0)
    q = model.nominal_configuration()
    assert statics.state(q, payload=statics.payload.with_mass(mass * 0.999)).stability_margin > 0
    assert statics.state(q, payload=statics.payload.with_mass(mass * 1.001)).stability_margin < 0
