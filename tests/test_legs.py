"""The general leg read from a URDF against Pinocchio on the same file, and against its drawing."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from robot_files import draw_hexapod

from hexaleg.kinematics import foot_jacobian, foot_position, leg_solution
from hexaleg.leg_frames import gravity_torques, link_frames
from hexaleg.robot.imported import robot_from_text

SEEDS = range(6)


def _pinocchio(text: str):
    model = pin.buildModelFromXML(text)
    return model, model.createData()


def _random_q(model, rng):
    """A configuration and its joint angles (nv,) [rad]; continuous joints store (cos, sin)."""
    angles = rng.uniform(-2.4, 2.4, model.nv)
    q = np.zeros(model.nq)
    for joint in model.joints[1:]:
        angle = angles[joint.idx_v]
        if joint.nq == 2:
            q[joint.idx_q : joint.idx_q + 2] = (np.cos(angle), np.sin(angle))
        else:
            q[joint.idx_q] = angle
    return q, angles


@pytest.mark.parametrize("seed", SEEDS)
def test_read_dimensions_equal_the_drawn_ones(seed):
    text, drawn = draw_hexapod(seed)
    robot = robot_from_text(text)
    by_root = {leg.chain.joints[0].name: leg for leg in robot.legs}
    for k, truth in enumerate(drawn):
        leg = by_root[f"leg{k}_j1"]
        g = leg.reading.geometry
        got = (g.coxa, g.hip_height, g.femur, g.tibia, g.foot_lateral)
        want = (truth.coxa, truth.hip_height, truth.femur, truth.tibia, truth.lateral)
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)
        np.testing.assert_allclose(leg.reading.mount, truth.mount, rtol=0, atol=1e-12)
        assert leg.reading.foot.rule == "frame"


@pytest.mark.parametrize("seed", SEEDS)
def test_fk_jacobian_link_frames_and_gravity_equal_pinocchio(seed):
    text, _ = draw_hexapod(seed)
    robot = robot_from_text(text)
    model, data = _pinocchio(text)
    rng = np.random.default_rng(100 + seed)
    for _ in range(5):
        q, angles = _random_q(model, rng)
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacements(model, data)
        pin.computeJointJacobians(model, data, q)
        gravity = pin.computeGeneralizedGravity(model, data, q)
        for leg in robot.legs:
            _check_leg(model, data, angles, gravity, leg)


def _check_leg(model, data, angles, gravity, leg):
    reading = leg.reading
    ids = [model.getJointId(name) for name in leg.joint_names]
    q_leg = np.array([angles[model.joints[i].idx_v] for i in ids])
    theta = reading.joint_map.from_file(q_leg)
    rotation, origin = reading.mount[:3, :3], reading.mount[:3, 3]
    foot_name = leg.chain.segments[2][-1]
    fid = model.getFrameId(foot_name)
    expected = rotation @ foot_position(reading.geometry, theta) + origin
    np.testing.assert_allclose(expected, data.oMf[fid].translation, rtol=0, atol=1e-12)
    jac = pin.getFrameJacobian(model, data, fid, pin.LOCAL_WORLD_ALIGNED)[:3]
    columns = jac[:, [model.joints[i].idx_v for i in ids]]
    closed = rotation @ foot_jacobian(reading.geometry, theta) * reading.joint_map.sign_array
    np.testing.assert_allclose(closed, columns, rtol=0, atol=1e-12)
    frames = reading.mount @ link_frames(reading.geometry, theta)
    for k in range(3):
        link = model.getFrameId(leg.chain.segments[k][0])
        np.testing.assert_allclose(frames[k], data.oMf[link].homogeneous, rtol=0, atol=1e-12)
    masses = [m.mass for m in leg.masses]
    coms = [m.com for m in leg.masses]
    g_leg = rotation.T @ model.gravity.linear
    tau = reading.joint_map.torques_to_file(
        gravity_torques(reading.geometry, theta, masses, coms, g_leg)
    )
    np.testing.assert_allclose(tau, gravity[[model.joints[i].idx_v for i in ids]], atol=1e-12)


@pytest.mark.parametrize("seed", SEEDS)
def test_ik_inverts_fk_on_drawn_legs(seed):
    text, _ = draw_hexapod(seed)
    robot = robot_from_text(text)
    rng = np.random.default_rng(200 + seed)
    for leg in robot.legs:
        g = leg.reading.geometry
        theta = np.column_stack(
            (rng.uniform(-1.2, 1.2, 40), rng.uniform(-1.0, 1.0, 40), rng.uniform(-2.8, -0.2, 40))
        )
        feet = foot_position(g, theta)
        solved, _ = leg_solution(g, feet)
        t2, t23 = theta[:, 1], theta[:, 1] + theta[:, 2]
        outward = g.femur * np.cos(t2) + g.tibia * np.cos(t23) > 1e-3  # foot beyond the hip
        # there the knee-down solution with the coxa toward the foot is unique: θ itself
        assert outward.sum() >= 10
        np.testing.assert_allclose(solved[outward], theta[outward], rtol=0, atol=1e-9)
