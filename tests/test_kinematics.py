"""Closed forms (eq 7, 8–9, 22, 24) against Pinocchio, finite differences and each other."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import random_angles, random_designs
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hexaleg import (
    STANCE_LIMITS,
    WORKSPACE_LIMITS,
    HexapodModel,
    LegModel,
    foot_jacobian,
    foot_position,
    inverse_kinematics,
    manipulability,
    planar_foot_position,
)
from hexaleg.kinematics import manipulability_eq25

DESIGNS = random_designs(8, seed=7)


@pytest.mark.parametrize("design", DESIGNS, ids=lambda d: f"l={d.l1:.3f},{d.l2:.3f},{d.l3:.3f}")
def test_pinocchio_leg_equals_eq7_and_eq22(design):
    leg = LegModel(design)
    rng = np.random.default_rng(1)
    thetas = random_angles(rng, 50)
    np.testing.assert_allclose(
        leg.foot_positions(thetas), foot_position(design.lengths, thetas), rtol=0, atol=1e-12
    )
    closed = foot_jacobian(design.lengths, thetas)
    for theta, jac in zip(thetas, closed, strict=True):
        np.testing.assert_allclose(leg.foot_jacobian(theta), jac, rtol=0, atol=1e-12)


@pytest.mark.parametrize("design", DESIGNS[:4], ids=lambda d: f"l={d.l1:.3f},{d.l2:.3f},{d.l3:.3f}")
def test_hexapod_legs_equal_eq7_in_each_root_frame(design):
    model = HexapodModel(design)
    rng = np.random.default_rng(2)
    for _ in range(10):
        angles = random_angles(rng, 6)
        base = pin_random_pose(rng)
        q = model.configuration(base, angles)
        feet = model.foot_positions(q)
        roots = model.root_placements()
        for i, leg in enumerate(model.leg_names):
            world_root = base * roots[leg]
            expected = world_root.act(foot_position(design.lengths, angles[i]))
            np.testing.assert_allclose(feet[i], expected, rtol=0, atol=1e-12)
            # the leg's own 3×3 Jacobian block, rotated into world axes, is eq 22
            jac = model.leg_foot_jacobian(q, leg)
            np.testing.assert_allclose(
                jac, world_root.rotation @ foot_jacobian(design.lengths, angles[i]), atol=1e-12
            )


def pin_random_pose(rng):
    import pinocchio as pin

    rotation = pin.rpy.rpyToMatrix(*rng.uniform(-np.pi, np.pi, size=3))
    return pin.SE3(rotation, rng.uniform(-1, 1, size=3))


def test_jacobians_equal_finite_differences(leg_model, default_design):
    rng = np.random.default_rng(3)
    step = 1e-6
    for theta in random_angles(rng, 40):
        numeric = np.empty((3, 3))
        for j in range(3):
            delta = np.zeros(3)
            delta[j] = step
            numeric[:, j] = (
                leg_model.foot_position(theta + delta) - leg_model.foot_position(theta - delta)
            ) / (2 * step)
        # central differences: truncation O(step²·L) ≈ 1e-12, round-off ≈ 1e-16/step
        np.testing.assert_allclose(leg_model.foot_jacobian(theta), numeric, atol=1e-8)
        np.testing.assert_allclose(foot_jacobian(default_design.lengths, theta), numeric, atol=1e-8)


def test_planar_form_is_eq7_at_zero_root_angle(default_design):
    rng = np.random.default_rng(4)
    thetas = random_angles(rng, 100)
    thetas[:, 0] = 0.0
    spatial = foot_position(default_design.lengths, thetas)
    planar = planar_foot_position(default_design.lengths, thetas[:, 1], thetas[:, 2])
    np.testing.assert_allclose(planar, spatial[:, [0, 2]], atol=1e-15)
    np.testing.assert_allclose(spatial[:, 1], 0.0, atol=1e-15)


@pytest.mark.parametrize("lengths", [(0.2, 0.4, 0.4), (0.05, 0.475, 0.475), (0.1, 0.3, 0.6)])
def test_printed_eq24_simplification_equals_abs_det_j(lengths):
    rng = np.random.default_rng(5)
    thetas = random_angles(rng, 2000)
    det = np.abs(np.linalg.det(foot_jacobian(lengths, thetas)))
    np.testing.assert_allclose(
        manipulability_eq25(lengths, thetas[:, 1], thetas[:, 2]), det, atol=1e-13
    )
    np.testing.assert_allclose(manipulability(lengths, thetas[:, 1], thetas[:, 2]), det, atol=1e-13)


def test_manipulability_from_pinocchio_equals_closed_form(leg_model, default_design):
    rng = np.random.default_rng(6)
    for theta in random_angles(rng, 50):
        w_model = abs(np.linalg.det(leg_model.foot_jacobian(theta)))
        w_closed = manipulability(default_design.lengths, theta[1], theta[2])
        np.testing.assert_allclose(w_model, w_closed, atol=1e-13)


# -- inverse kinematics ----------------------------------------------------------------

lengths_strategy = st.tuples(st.floats(0.01, 1.0), st.floats(0.05, 1.0), st.floats(0.05, 1.0))
angle_strategy = st.tuples(
    st.floats(-np.pi / 2 + 1e-3, np.pi / 2 - 1e-3),
    st.floats(-np.pi / 2, np.pi / 2),
    st.floats(-np.pi + 1e-2, -1e-2),
)


@settings(max_examples=500, deadline=None)
@given(lengths=lengths_strategy, theta=angle_strategy)
def test_fk_of_ik_is_identity_on_the_reachable_set(lengths, theta):
    target = foot_position(lengths, theta)
    solution = inverse_kinematics(lengths, target)
    assert solution.reachable
    np.testing.assert_allclose(foot_position(lengths, solution.theta), target, atol=1e-9)


@settings(max_examples=500, deadline=None)
@given(lengths=lengths_strategy, theta=angle_strategy)
def test_ik_of_fk_is_identity_on_the_knee_down_branch(lengths, theta):
    l1, l2, l3 = lengths
    _, t2, t3 = theta
    outward = l1 + l2 * np.cos(t2) + l3 * np.cos(t2 + t3)
    # on the root axis or at the knee singularity the angles are not unique
    assume(abs(outward) > 1e-3 * (l1 + l2 + l3) and abs(np.sin(t3)) > 1e-3)
    solution = inverse_kinematics(lengths, foot_position(lengths, theta))
    assert solution.reachable
    wrapped = np.angle(np.exp(1j * (solution.theta - np.array(theta))))
    # conditioning: near-singular poses amplify round-off by 1/|sin θ3|
    np.testing.assert_allclose(wrapped, 0.0, atol=1e-6)


def test_ik_is_vectorized_and_flags_unreachable_targets():
    lengths = (0.2, 0.4, 0.4)
    targets = np.array(
        [
            [0.8, 0.0, -0.4],  # reachable
            [2.0, 0.0, 0.0],  # too far: beyond l1 + l2 + l3
            [0.2, 0.0, 0.0],  # at the hip: r = 0 < |l2 - l3| is fine only if l2 = l3 ...
            [0.0, 0.0, 5.0],  # far above
        ]
    )
    solution = inverse_kinematics(lengths, targets)
    assert solution.theta.shape == (4, 3)
    assert np.all(np.isfinite(solution.theta))
    assert solution.reachable.tolist() == [True, False, False, False]
    np.testing.assert_allclose(foot_position(lengths, solution.theta[0]), targets[0], atol=1e-12)


def test_ik_flags_targets_outside_limits():
    lengths = (0.2, 0.4, 0.4)
    inside = foot_position(lengths, [0.1, 0.0, -1.5])
    outside = foot_position(lengths, [0.1, 0.9, -0.2])  # hip 0.9 > π/6 stance limit
    solution = inverse_kinematics(lengths, np.stack([inside, outside]), limits=STANCE_LIMITS)
    assert solution.reachable.tolist() == [True, False]
    assert inverse_kinematics(lengths, outside, limits=WORKSPACE_LIMITS).reachable


def test_ik_annulus_inner_boundary_is_flagged():
    lengths = (0.1, 0.5, 0.2)  # |l2 - l3| = 0.3: points closer than that to the hip are unreachable
    hip = np.array([0.1, 0.0, 0.0])
    close = hip + np.array([0.1, 0.0, 0.0])
    assert not inverse_kinematics(lengths, close).reachable
    edge = hip + np.array([0.3, 0.0, 0.0])
    assert inverse_kinematics(lengths, edge).reachable
