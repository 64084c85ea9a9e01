"""Max stride and max speed at their boundaries; W⁺ and CoT as masses, payload and period change."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest
from conftest import random_designs
from hypothesis import given, settings
from hypothesis import strategies as st

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.gait import Gait, Walker, analyze_gait, max_speed, max_stride
from hexaleg.gait.limits import _zmp_room
from hexaleg.gait.metrics import positive_work
from hexaleg.statics import GRAVITY, Payload

JUST = 1e-7
"""How far past a limit [m, relative] the tests step to see it break."""


def _feasible(model: HexapodModel, gait: Gait) -> bool:
    walker = Walker(model, gait)
    return not walker.stride(gait.stride).violations


@pytest.mark.parametrize("pattern", ["tripod", "tetrapod", "wave"])
def test_the_max_stride_is_the_boundary(hexapod_model, pattern):
    gait = Gait(pattern=pattern, samples=60)
    limit = max_stride(Walker(hexapod_model, gait))
    assert 0.3 < limit.value < 1.0
    assert _feasible(hexapod_model, gait.replace(stride=limit.value))
    assert not _feasible(hexapod_model, gait.replace(stride=limit.value + JUST))
    beyond = analyze_gait(
        hexapod_model.design, gait.replace(stride=limit.value + JUST), model=hexapod_model,
        limits=False,
    )  # fmt: skip
    assert limit.limited_by in {v.cause for v in beyond.violations}


def test_the_max_stride_is_the_boundary_on_random_designs():
    checked = 0
    for design in random_designs(6, seed=23):
        model = HexapodModel(design)
        gait = Gait(step_height=0.02, heading=0.4, samples=40)
        limit = max_stride(Walker(model, gait))
        if limit.value == 0.0:  # even a standstill breaks a constraint: say which
            assert not _feasible(model, gait.replace(stride=1e-4))
            continue
        assert _feasible(model, gait.replace(stride=limit.value))
        assert not _feasible(model, gait.replace(stride=limit.value + JUST))
        # and the whole range below is feasible (the first crossing, not a later one)
        for stride in np.linspace(1e-4, limit.value, 7):
            assert _feasible(model, gait.replace(stride=float(stride)))
        checked += 1
    assert checked >= 3


def test_a_margin_leaving_zero_tangentially_names_its_constraint_not_the_range():
    """A short leg whose hip sits at its limit (margin 0) up to its max stride: past it the
    margin departs slowly, and the constraint is named, not "end of the searched range"."""
    walker = Walker(HexapodModel(HexapodDesign(l1=0.05, l2=0.1, l3=0.1)), Gait(samples=100))
    limit = max_stride(walker)
    assert 0 < limit.value < 0.3 and not walker.stride(limit.value).violations
    beyond = walker.stride(limit.value * 1.05).violations
    assert limit.limited_by.kind != "range" and limit.limited_by in {v.cause for v in beyond}


def _ratios(walked) -> tuple[np.ndarray, np.ndarray]:
    design = walked.design
    return (
        np.abs(walked.joint_torques) / np.array(design.rated_torques),
        np.abs(walked.joint_velocities) / np.array(design.rated_speeds),
    )


@pytest.mark.parametrize(
    ("design", "gait"),
    [
        (HexapodDesign(), Gait(samples=60)),  # hip torque binds
        (HexapodDesign(rated_speeds=(1.0, 1.0, 1.0)), Gait(samples=60)),  # a speed binds
        (HexapodDesign(l1=0.15, l2=0.45, l3=0.4), Gait(pattern="wave", stride=0.2, samples=60)),
    ],
)
def test_the_max_speed_puts_its_binding_joint_at_its_rating(design, gait):
    model = HexapodModel(design)
    limit = max_speed(Walker(model, gait))
    assert limit.value > 0
    at = gait.replace(stride=limit.stride, period=limit.period)
    assert at.speed == pytest.approx(limit.value, rel=1e-12)
    walked = analyze_gait(design, at, model=model, limits=False)
    torque, speed = _ratios(walked)
    binding = torque if limit.limited_by.kind == "torque" else speed
    leg = walked.legs.index(limit.limited_by.leg)
    joint = ("root", "hip", "knee").index(limit.limited_by.joint)
    assert binding[:, leg, joint].max() == pytest.approx(1.0, abs=1e-9)
    assert max(torque.max(), speed.max()) <= 1 + 1e-9 and walked.feasible
    faster = analyze_gait(design, at.replace(period=limit.period * (1 - JUST)), model=model,
                          limits=False)  # fmt: skip
    assert max(r.max() for r in _ratios(faster)) > 1


def test_min_torque_forces_raise_the_max_speed_by_bisection(hexapod_model):
    gait = Gait(samples=24)
    walker = Walker(hexapod_model, gait, distribution="min-torque")
    limit = max_speed(walker)
    norm = max_speed(Walker(hexapod_model, gait))
    assert limit.value >= norm.value - 1e-9  # least torque/rating never binds sooner
    at = gait.replace(stride=limit.stride, period=limit.period)
    walked = analyze_gait(
        hexapod_model.design, at, distribution="min-torque", model=hexapod_model, limits=False
    )
    assert max(r.max() for r in _ratios(walked)) == pytest.approx(1.0, abs=1e-5)


def test_an_over_rated_standstill_has_no_speed():
    design = HexapodDesign(rated_torques=(60.0, 80.0, 120.0))  # a tripod's hip holds ~146 N·m
    limit = max_speed(Walker(HexapodModel(design), Gait(samples=24)))
    assert limit.value == 0.0 and math.isinf(limit.period)
    assert limit.limited_by.kind == "torque" and limit.limited_by.joint == "hip"


# -- W⁺ and CoT ----------------------------------------------------------------------------


def _scaled(model: HexapodModel, factor: float) -> HexapodModel:
    copy = pin.Model(model.model)
    for k, inertia in enumerate(copy.inertias):
        copy.inertias[k] = pin.Inertia(
            factor * inertia.mass, inertia.lever, factor * inertia.inertia
        )
    return HexapodModel(model.design, _model=copy)


@given(
    factor=st.floats(0.2, 5.0),
    payload=st.floats(0.0, 60.0),
    period=st.floats(0.8, 6.0),
)
@settings(max_examples=15, deadline=None)
def test_scaling_every_mass_scales_the_work_and_keeps_the_cost_of_transport(
    hexapod_model, factor, payload, period
):
    gait, point = Gait(period=period, samples=30), (0.1, 0.05, 0.05)
    base = analyze_gait(hexapod_model.design, gait, Payload(payload, point),
                        model=hexapod_model, limits=False)  # fmt: skip
    heavy = analyze_gait(hexapod_model.design, gait, Payload(factor * payload, point),
                         model=_scaled(hexapod_model, factor), limits=False)  # fmt: skip
    assert heavy.mass == pytest.approx(factor * base.mass, rel=1e-12)
    np.testing.assert_allclose(heavy.joint_torques, factor * base.joint_torques, atol=1e-9 * factor)
    assert heavy.metrics.positive_work == pytest.approx(
        factor * base.metrics.positive_work, rel=1e-9
    )
    assert heavy.metrics.cost_of_transport == pytest.approx(
        base.metrics.cost_of_transport, rel=1e-9
    )


@given(factor=st.floats(0.3, 4.0), period=st.floats(0.8, 4.0))
@settings(max_examples=15, deadline=None)
def test_a_slower_walk_under_weaker_gravity_is_the_same_walk(hexapod_model, factor, period):
    # T → c·T with g → g/c²: every force scales by 1/c², every speed by 1/c, W⁺ by 1/c²
    gait = Gait(period=period, samples=30)
    fast = analyze_gait(hexapod_model.design, gait, model=hexapod_model, limits=False)
    slow = analyze_gait(hexapod_model.design, gait.replace(period=factor * period),
                        model=hexapod_model, limits=False, gravity=GRAVITY / factor**2)  # fmt: skip
    np.testing.assert_allclose(slow.joint_torques, fast.joint_torques / factor**2, atol=1e-9)
    np.testing.assert_allclose(slow.joint_velocities, fast.joint_velocities / factor, atol=1e-12)
    assert slow.metrics.positive_work == pytest.approx(
        fast.metrics.positive_work / factor**2, rel=1e-9
    )
    assert slow.metrics.cost_of_transport == pytest.approx(fast.metrics.cost_of_transport, rel=1e-9)


@given(
    masses=st.tuples(st.floats(0.0, 80.0), st.floats(0.0, 80.0)),
    periods=st.tuples(st.floats(0.8, 5.0), st.floats(0.8, 5.0)),
)
@settings(max_examples=15, deadline=None)
def test_torques_are_affine_and_work_convex_in_payload_and_in_one_over_period_squared(
    hexapod_model, masses, periods
):
    def walk(mass: float, period: float):
        return analyze_gait(hexapod_model.design, Gait(period=period, samples=30),
                            Payload(mass, (0.0, 0.1, 0.05)), model=hexapod_model,
                            limits=False)  # fmt: skip

    (m1, m2), (t1, t2) = masses, periods
    middle_period = 1 / math.sqrt((t1**-2 + t2**-2) / 2)
    for a, b, mid in (
        (walk(m1, t1), walk(m2, t1), walk((m1 + m2) / 2, t1)),
        (walk(m1, t1), walk(m1, t2), walk(m1, middle_period)),
    ):
        np.testing.assert_allclose(
            mid.joint_torques, (a.joint_torques + b.joint_torques) / 2, atol=1e-9
        )
        # W⁺ = Σ max(τ·q̇, 0)·T/N: convex along a line where τ·q̇·T is affine
        same_motion = a.gait.period == b.gait.period
        if same_motion:
            work = (a.metrics.positive_work + b.metrics.positive_work) / 2
            assert mid.metrics.positive_work <= work + 1e-9


def test_positive_work_and_cost_of_transport_follow_their_definitions(hexapod_model):
    walked = analyze_gait(hexapod_model.design, Gait(samples=40), Payload(20.0),
                          model=hexapod_model, limits=False)  # fmt: skip
    power = walked.joint_torques * walked.joint_velocities
    expected = sum(max(float(p), 0.0) * walked.gait.period / 40 for p in power.ravel())
    assert walked.metrics.positive_work == pytest.approx(expected, rel=1e-12)
    assert positive_work(walked.joint_torques, walked.joint_velocities, walked.gait.period) == (
        walked.metrics.positive_work
    )
    distance = walked.gait.speed * walked.gait.period
    assert walked.metrics.cost_of_transport == pytest.approx(
        expected / (walked.mass * GRAVITY * distance), rel=1e-12
    )
    assert walked.mass == pytest.approx(84.006 + 20.0, abs=1e-9)


# -- the ZMP: a gait that tips over is not feasible ----------------------------------------

STRONG = HexapodDesign(rated_torques=(1e5, 1e5, 1e5), rated_speeds=(1e3, 1e3, 1e3))
"""Ratings no walk reaches: only the ZMP can bound the speed."""


def _upright(model: HexapodModel, gait: Gait, payload: Payload) -> bool:
    """The oracle: the period's ZMP stays inside by the polygon's signed distances."""
    walked = analyze_gait(model.design, gait, payload, model=model, limits=False)
    return walked.min_zmp_margin >= 0


CASES = [("tripod", (0.0, 0.0, 0.05)), ("tripod", (0.25, -0.1, 0.3)), ("tetrapod", (0.1, 0.2, 0.1))]
"""Gaits and payload points whose speed only the feet's support bounds (:data:`STRONG`)."""


def _shortest_period(model: HexapodModel, gait: Gait, payload: Payload, holds) -> float:
    """The oracle: the shortest period [s] at which ``holds(walked)``, bisected to 1e-9."""
    low, high = 0.05, 50.0  # periods [s]: broken at the first, held at the second

    def held(period: float) -> bool:
        walked = analyze_gait(model.design, gait.replace(period=period), payload, model=model,
                              limits=False)  # fmt: skip
        return bool(holds(walked))

    assert not held(low) and held(high)
    while high - low > 1e-9 * high:
        middle = (low + high) / 2
        low, high = (low, middle) if held(middle) else (middle, high)
    return high


@pytest.mark.parametrize(("pattern", "position"), CASES)
def test_the_max_speed_stops_where_a_foot_cannot_grip_as_a_bisection_finds(pattern, position):
    """Faster, the ZMP nears the polygon's edge and the far feet unload: their planned
    tangential force leaves the friction cone just before the ZMP would leave the feet."""
    model, gait = HexapodModel(STRONG), Gait(pattern=pattern, samples=60)
    payload = Payload(20.0, position)
    limit = max_speed(Walker(model, gait, payload))
    assert limit.limited_by.kind == "slide" and limit.stride == gait.stride
    high = _shortest_period(model, gait, payload, lambda walked: walked.feasible)
    assert limit.period == pytest.approx(high, rel=1e-8)
    assert limit.value == pytest.approx(gait.replace(period=high).speed, rel=1e-8)
    walked = analyze_gait(STRONG, gait.replace(period=limit.period * (1 + JUST)), payload,
                          model=model, limits=False)  # fmt: skip
    assert walked.feasible and not walked.slips
    faster = analyze_gait(STRONG, gait.replace(period=limit.period * (1 - JUST)), payload,
                          model=model, limits=False)  # fmt: skip
    assert not faster.feasible and faster.walkable and faster.tipping is None
    assert limit.limited_by in {slip.cause for slip in faster.slips}  # mirror legs tie


@pytest.mark.parametrize(("pattern", "position"), CASES)
def test_the_zmp_bounds_the_speed_where_it_leaves_the_feet_as_a_bisection_finds(pattern, position):
    model, gait = HexapodModel(STRONG), Gait(pattern=pattern, samples=60)
    payload = Payload(20.0, position)
    walker = Walker(model, gait, payload)
    walk = walker.stride(gait.stride)
    room = _zmp_room(walker, walk, walker.generalized_forces(gait.stride, walk))
    high = _shortest_period(model, gait, payload, lambda walked: walked.min_zmp_margin >= 0)
    assert 1 / math.sqrt(room) == pytest.approx(high, rel=1e-8)
    faster = analyze_gait(STRONG, gait.replace(period=high * (1 - JUST)), payload,
                          model=model, limits=False)  # fmt: skip
    assert faster.tipping is not None and faster.tipping.cause.kind == "zmp"


def test_a_gait_whose_zmp_leaves_the_feet_is_infeasible_and_names_the_zmp():
    model, gait = HexapodModel(HexapodDesign()), Gait(samples=40)
    payload = Payload(30.0, (100.0, 100.0, 100.0))  # far off the body: the robot tips
    walked = analyze_gait(model.design, gait, payload, model=model)
    margins = walked.zmp_margin
    assert walked.walkable and margins.min() < -1.0
    assert not walked.feasible and walked.tipping is not None
    assert walked.tipping.time == walked.times[np.flatnonzero(margins < 0)[0]]
    assert str(walked.tipping.cause) == "ZMP leaves the support polygon"
    assert walked.infeasible_because.startswith(f"{walked.tipping} (min ZMP margin ")
    data = walked.to_dict()
    assert data["feasible"] is False and data["tipping"]["kind"] == "zmp"
    # even infinitely slowly it tips: no speed at all, and the ZMP is what binds
    assert walked.max_speed.value == 0 and walked.max_speed.limited_by.kind == "zmp"
    upright = analyze_gait(model.design, gait, model=model, limits=False)
    assert upright.tipping is None and upright.to_dict()["tipping"] is None
