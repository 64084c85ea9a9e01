"""Gait patterns, foot paths and joint motion, against the definitions and finite differences."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hexaleg import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.gait import Gait, analyze_gait, duty_factor, gait_phases, legs_around
from hexaleg.gait.feasibility import COLUMNS, violations
from hexaleg.gait.jacobian import inverse_times, leg_partials, rate_times, transpose_times
from hexaleg.gait.trajectory import LegFrames, knee_heights
from hexaleg.kinematics import foot_jacobian, foot_position, leg_solution
from hexaleg.layouts import LegMount
from hexaleg.leg_geometry import LegGeometry


@given(samples=st.integers(12, 2000))
@settings(max_examples=60, deadline=None)
def test_exactly_three_feet_stand_at_every_instant_of_a_tripod(samples):
    design = HexapodDesign()
    phases = gait_phases(design, "tripod", samples)
    assert (phases.stance.sum(axis=1) == 3).all()
    names = design.leg_names
    for k in range(samples):
        a_swings = Fraction(k, samples) < Fraction(1, 2)  # group A swings on [0, T/2)
        for leg in ("lf", "rm", "lr"):
            assert phases.swing[k, names.index(leg)] == a_swings
        for leg in ("rf", "lm", "rr"):
            assert phases.swing[k, names.index(leg)] != a_swings


@pytest.mark.parametrize(
    ("pattern", "groups"),
    [
        ("tripod", [("lf", "rm", "lr"), ("rf", "lm", "rr")]),
        ("tetrapod", [("lf", "rr"), ("rf", "lr"), ("lm", "rm")]),
        ("wave", [("lf",), ("rf",), ("rm",), ("rr",), ("lr",), ("lm",)]),
    ],
)
def test_patterns_swing_their_documented_groups_in_turn(pattern, groups):
    design, samples = HexapodDesign(), 60
    phases = gait_phases(design, pattern, samples)
    n = len(groups)
    assert duty_factor(pattern) == pytest.approx(1 - 1 / n)
    assert (phases.stance.sum(axis=1) == 6 - 6 // n).all()
    for g, legs in enumerate(groups):
        for k in range(samples):
            swings = Fraction(g, n) <= Fraction(k, samples) < Fraction(g + 1, n)
            for leg in legs:
                assert phases.swing[k, design.leg_names.index(leg)] == swings


def test_custom_legs_go_around_the_body_from_straight_ahead():
    mounts = tuple(
        LegMount(
            f"leg{k}",
            0.5 * math.cos(a),
            0.5 * math.sin(a),
            0.0,
            math.atan2(math.sin(a), math.cos(a)),
        )
        for k, a in enumerate(np.radians([200, 20, 80, 320, 140, 260]))
    )
    design = HexapodDesign(mounts=mounts, body_radius=0.5)
    assert legs_around(design) == ("leg1", "leg2", "leg4", "leg0", "leg5", "leg3")
    phases = gait_phases(design, "tripod", 20)
    first = [design.leg_names.index(leg) for leg in ("leg1", "leg4", "leg5")]
    assert phases.swing[0, first].all() and phases.stance[0].sum() == 3


@pytest.fixture(scope="module")
def fine(hexapod_model):
    """A finely sampled walk (dt = 0.25 ms) for finite differences."""
    gait = Gait(period=1.0, stride=0.25, step_height=0.08, heading=0.3, samples=4000)
    return analyze_gait(hexapod_model.design, gait, model=hexapod_model, limits=False)


def _derivative(values: np.ndarray, dt: float, swing: np.ndarray) -> np.ndarray:
    """Second-order differences in time (N, 6, 3), each from samples of the same phase.

    The paths are C² where a foot lifts off or touches down, not C³: a stencil across the
    switch would err by O(dt·jerk). So the first and last sample of each swing or stance
    take one-sided stencils; the period repeats, so the others wrap around.
    """
    ahead, behind = np.roll(values, -1, 0), np.roll(values, 1, 0)
    out = (ahead - behind) / (2 * dt)
    forward = (-3 * values + 4 * ahead - np.roll(values, -2, 0)) / (2 * dt)
    backward = (3 * values - 4 * behind + np.roll(values, 2, 0)) / (2 * dt)
    starts = swing != np.roll(swing, 1, 0)  # (N, 6): a phase begins here
    ends = swing != np.roll(swing, -1, 0)
    out = np.where(starts[..., None], forward, out)
    return np.where(ends[..., None], backward, out)


def test_joint_velocities_and_accelerations_are_the_angles_derivatives(fine):
    # second-order differences err by dt²/3·|d³/dt³| ≈ 2e-8·(≤ 3e2): 1e-5 of each scale
    dt, swing = fine.times[1], ~fine.stance
    for exact, of in (
        (fine.joint_velocities, fine.joint_angles),
        (fine.joint_accelerations, fine.joint_velocities),
    ):
        scale = np.abs(exact).max()
        np.testing.assert_allclose(exact, _derivative(of, dt, swing), atol=1e-5 * scale, rtol=0)
    assert np.abs(fine.joint_velocities).max() > 0.5 and np.abs(fine.joint_accelerations).max() > 5


def test_the_angles_put_every_foot_on_its_path(fine, hexapod_model):
    frames = LegFrames.from_model(hexapod_model)
    in_roots = foot_position(frames.lengths, fine.joint_angles)
    in_body = frames.root_positions + np.einsum("nij,knj->kni", frames.root_rotations, in_roots)
    np.testing.assert_allclose(in_body, fine.feet, atol=1e-12)


def test_standing_feet_stay_put_and_swinging_feet_follow_the_definition(fine, hexapod_model):
    gait, beta = fine.gait, fine.gait.duty_factor
    u = np.array([math.cos(gait.heading), math.sin(gait.heading), 0.0])
    base = fine.configurations[:, :3]
    step = np.broadcast_to(gait.speed * fine.times[1] * u, (len(base) - 1, 3))
    np.testing.assert_allclose(base[1:] - base[:-1], step, atol=1e-12)
    world = fine.feet + base[:, None, :]
    footholds = LegFrames.from_model(hexapod_model).footholds
    for leg in range(6):
        standing = np.flatnonzero(fine.stance[:, leg])
        runs = np.split(standing, np.flatnonzero(np.diff(standing) > 1) + 1)
        for run in runs:  # fixed in the world, on the ground
            still = np.broadcast_to(world[run[0], leg], (len(run), 3))
            np.testing.assert_allclose(world[run, leg], still, atol=1e-12)
            assert world[run, leg, 2] == pytest.approx(0.0, abs=1e-12)
        swing = np.flatnonzero(~fine.stance[:, leg])
        s = (np.arange(len(swing))) / len(swing)
        lift_off = world[swing[0], leg] - (footholds[leg] - gait.stride / 2 * u) - base[swing[0]]
        assert np.abs(lift_off[:2]).max() < 1e-12  # it lifts off where its stance ended
        h = 10 * s**3 - 15 * s**4 + 6 * s**5
        expected = world[swing[0], leg][:2] + np.outer(h, gait.speed * gait.period * u[:2])
        np.testing.assert_allclose(world[swing, leg, :2], expected, atol=1e-12)
        heights = gait.step_height * 64 * s**3 * (1 - s) ** 3
        np.testing.assert_allclose(world[swing, leg, 2], heights, atol=1e-12)
        assert beta == 0.5


def test_the_closed_form_jacobian_products():
    rng = np.random.default_rng(7)
    lengths = (0.17, 0.43, 0.38)
    theta = rng.uniform(-1.2, 1.2, (40, 3))
    theta[:, 2] = -rng.uniform(0.3, 2.5, 40)
    rates, push = rng.normal(size=(2, 40, 3))
    jac, leg = foot_jacobian(lengths, theta), leg_partials(lengths, theta)
    np.testing.assert_allclose(
        inverse_times(leg, push), np.linalg.solve(jac, push[..., None])[..., 0], atol=1e-10
    )
    np.testing.assert_allclose(
        transpose_times(leg, push), (np.swapaxes(jac, 1, 2) @ push[..., None])[..., 0], atol=1e-14
    )
    h = 1e-6  # J̇·θ̇ = d/dε J(θ + ε·θ̇)·θ̇, central differences (error ~h²)
    ahead = foot_jacobian(lengths, theta + h * rates) @ rates[..., None]
    behind = foot_jacobian(lengths, theta - h * rates) @ rates[..., None]
    np.testing.assert_allclose(
        rate_times(leg, rates), (ahead - behind)[..., 0] / (2 * h), atol=1e-7
    )


def test_the_jacobian_products_of_six_general_legs_side_by_side():
    # each leg its own coxa, femur, tibia, hip height h and lateral offset e, as an imported
    # robot's rows; the oracle takes each leg alone (a LegGeometry, no broadcasting)
    rng = np.random.default_rng(11)
    rows = np.column_stack(
        (
            rng.uniform(0.0, 0.1, 6),
            rng.uniform(0.05, 0.2, 6),
            rng.uniform(0.06, 0.25, 6),
            rng.uniform(-0.05, 0.05, 6),
            rng.uniform(-0.04, 0.04, 6),
        )
    )
    theta = rng.uniform(-1.2, 1.2, (30, 6, 3))
    theta[..., 2] = -rng.uniform(0.3, 2.5, (30, 6))
    rates, push = rng.normal(size=(2, 30, 6, 3))
    leg = leg_partials(rows, theta)
    h = 1e-6
    for i, row in enumerate(rows):
        alone = LegGeometry(*row)
        jac = foot_jacobian(alone, theta[:, i])
        solved = np.linalg.solve(jac, push[:, i, :, None])[..., 0]
        np.testing.assert_allclose(inverse_times(leg, push)[:, i], solved, atol=1e-10)
        pushed = (np.swapaxes(jac, 1, 2) @ push[:, i, :, None])[..., 0]
        np.testing.assert_allclose(transpose_times(leg, push)[:, i], pushed, atol=1e-14)
        ahead = foot_jacobian(alone, theta[:, i] + h * rates[:, i]) @ rates[:, i, :, None]
        behind = foot_jacobian(alone, theta[:, i] - h * rates[:, i]) @ rates[:, i, :, None]
        expected = (ahead - behind)[..., 0] / (2 * h)
        np.testing.assert_allclose(rate_times(leg, rates)[:, i], expected, atol=1e-7)
        # and the rows' FK and IK are each leg's own
        targets = foot_position(alone, theta[:, i])
        np.testing.assert_allclose(foot_position(rows, theta)[:, i], targets, atol=1e-15)
        angles, reach = leg_solution(rows, foot_position(rows, theta))
        own, own_reach = leg_solution(alone, targets)
        np.testing.assert_allclose(angles[:, i], own, atol=1e-15)
        np.testing.assert_allclose(reach[:, i], own_reach, atol=1e-15)


def test_knee_heights_are_the_femur_tips(hexapod_model):
    frames = LegFrames.from_model(hexapod_model)
    theta = np.random.default_rng(2).uniform(-1, 1, (9, 6, 3))
    knee = foot_position((frames.lengths[0], frames.lengths[1], 0.0), theta)
    expected = (
        frames.height
        + (frames.root_positions + np.einsum("nij,knj->kni", frames.root_rotations, knee))[..., 2]
    )
    np.testing.assert_allclose(knee_heights(frames, theta), expected, atol=1e-14)


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("pattern", "gallop", "pattern = 'gallop' is not valid: use one of 'tripod'"),
        ("period", 0.0, "period = 0 is not valid: must lie in [0.05, 1000] [s]"),
        ("stride", -0.1, "stride = -0.1 is not valid: must lie in [0.0001, 100] [m]"),
        ("step_height", math.nan, "step_height = nan is not valid: must be finite"),
        ("heading", 4.0, "heading = 4 is not valid: must lie in [-3.14159, 3.14159] [rad]"),
        ("samples", 5, "samples = 5 is not valid: must lie in [12, 100000]"),
        ("samples", 20.0, "samples = 20 is not valid: must be an integer"),
    ],
)
def test_a_bad_gait_is_refused_in_one_line_naming_the_field(field, value, message):
    with pytest.raises(HexalegError) as error:
        Gait(**{field: value})
    assert str(error.value).startswith(message) and "\n" not in str(error.value)


def test_speed_sets_the_period_from_the_stride():
    gait = Gait(stride=0.4).with_speed(0.5)
    assert gait.period == pytest.approx(0.4 / (0.5 * 0.5)) and gait.speed == pytest.approx(0.5)
    with pytest.raises(HexalegError, match="speed = 1e-06 is not valid"):
        Gait().with_speed(1e-6)


def test_violations_name_each_broken_constraint_once_earliest_first():
    margins = np.ones((10, 6, COLUMNS))
    margins[5:, 2, 8] = -1e-3  # lr's knee below the ground from t5
    margins[7, 0, 4] = -1e-3  # lf's hip under its lower limit at t7
    margins[3, 4, 0] = -1e-13  # within the tolerance: not broken
    found = violations(margins, HexapodDesign().leg_names, np.arange(10) * 0.1)
    assert [str(v) for v in found] == [
        "t = 0.500 s: lr knee touches the ground",
        "t = 0.700 s: lf hip joint at its lower limit",
    ]
    assert found[0].to_dict()["time"] == 0.5 and found[1].to_dict()["bound"] == "lower"


def test_a_period_out_of_reach_is_infeasible_and_says_why():
    design = HexapodDesign()
    walked = analyze_gait(design, Gait(stride=0.9), limits=False)
    assert not walked.feasible
    first = walked.violations[0].cause
    assert first.kind in ("reach", "joint") and first.leg in design.leg_names
