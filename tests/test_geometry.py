"""Stance closed chain: IK/FK round trips, feet on footholds in Pinocchio, mobility (eq 1–2)."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.exceptions import HexalegError
from hexaleg.stance.geometry import (
    StanceGeometry,
    constraint_jacobian,
    constraint_residual,
    mobility,
    rigid_fit,
    stance_configuration,
    stance_forward_kinematics,
    stance_inverse_kinematics,
    stance_legs,
)

pose_strategy = st.tuples(
    *(st.floats(-0.08, 0.08) for _ in range(3)), *(st.floats(-0.12, 0.12) for _ in range(3))
)


def _pose(geometry, offsets):
    x, y, z, roll, pitch, yaw = offsets
    return pin.SE3(
        pin.rpy.rpyToMatrix(roll, pitch, yaw), np.array([x, y, geometry.nominal_height + z])
    )


@pytest.fixture(scope="module", params=["tripod", "all"])
def geometry(request, hexapod_model):
    return StanceGeometry.from_model(hexapod_model, request.param)


@settings(max_examples=200, deadline=None)
@given(offsets=pose_strategy)
def test_stance_ik_then_fk_returns_the_pose(hexapod_model, offsets):
    for stance in ("tripod", "all"):
        geometry = StanceGeometry.from_model(hexapod_model, stance)
        body = _pose(geometry, offsets)
        solution = stance_inverse_kinematics(geometry, body)
        assume(solution.reachable.all())  # the identity holds on the reachable set
        recovered = stance_forward_kinematics(geometry, solution.theta)
        np.testing.assert_allclose(recovered.homogeneous, body.homogeneous, atol=1e-12)


def test_after_stance_ik_pinocchio_puts_every_foot_on_its_foothold(hexapod_model, geometry):
    rng = np.random.default_rng(51)
    for offsets in rng.uniform(-0.1, 0.1, size=(25, 6)):
        body = _pose(geometry, offsets)
        q, solution = stance_configuration(hexapod_model, geometry, body)
        assert solution.reachable.all()
        assert np.abs(constraint_residual(hexapod_model, geometry, q)).max() < 1e-9


def test_constraint_jacobian_equals_finite_differences(hexapod_model, geometry):
    body = _pose(geometry, [0.02, -0.03, 0.01, 0.05, -0.04, 0.1])
    q, _ = stance_configuration(hexapod_model, geometry, body)
    jac = constraint_jacobian(hexapod_model, geometry, q)
    step = 1e-7
    for k in range(hexapod_model.model.nv):
        dv = np.zeros(hexapod_model.model.nv)
        dv[k] = step
        plus = constraint_residual(
            hexapod_model, geometry, pin.integrate(hexapod_model.model, q, dv)
        )
        minus = constraint_residual(
            hexapod_model, geometry, pin.integrate(hexapod_model.model, q, -dv)
        )
        np.testing.assert_allclose(jac[:, k], (plus - minus) / (2 * step), atol=1e-7)


@pytest.mark.parametrize(
    "legs", [("lf", "rm", "lr"), ("lf", "lm", "rf", "rr"), ("lf", "lm", "lr", "rf", "rm"), None]
)
def test_mobility_is_six_for_three_to_six_stance_legs(hexapod_model, legs):
    legs = legs or hexapod_model.leg_names
    geometry = StanceGeometry.from_model(hexapod_model, legs)
    q, _ = stance_configuration(
        hexapod_model, geometry, _pose(geometry, [0.01, 0.02, 0.0, 0.03, 0.0, 0.05])
    )
    assert mobility(hexapod_model, geometry, q) == 6  # eq 2: F = 3N + 3N − 6(N − 1) = 6


def test_pinocchio_anchor_constraints_agree_with_the_stacked_rows(hexapod_model):
    """Pinocchio 4.1's PointAnchorConstraintModel gives the same residual and Jacobian."""
    geometry = StanceGeometry.from_model(hexapod_model, "tripod")
    body = _pose(geometry, [0.03, 0.0, -0.02, 0.0, 0.05, 0.0])
    q, _ = stance_configuration(hexapod_model, geometry, body)
    body_off = _pose(geometry, [0.031, 0.0, -0.02, 0.0, 0.05, 0.0])
    q_off = hexapod_model.configuration(body_off, hexapod_model.joint_angles(q))
    model, data = hexapod_model.model, hexapod_model.data
    models, datas = [], []
    for leg, foothold in zip(geometry.legs, geometry.footholds, strict=True):
        frame = model.frames[hexapod_model.foot_frame_id(leg)]
        cm = pin.PointAnchorConstraintModel(
            model, 0, pin.SE3(np.eye(3), foothold), frame.parentJoint, frame.placement
        )
        models.append(cm)
        datas.append(cm.createData())
    pin.computeJointJacobians(model, data, q_off)
    pin.updateFramePlacements(model, data)
    for cm, cd in zip(models, datas, strict=True):
        cm.calc(model, data, cd)
    errors = np.concatenate([cd.constraint_position_error for cd in datas])
    jacobian = np.vstack(
        [cm.jacobian(model, data, cd) for cm, cd in zip(models, datas, strict=True)]
    )
    np.testing.assert_allclose(
        errors, constraint_residual(hexapod_model, geometry, q_off), atol=1e-14
    )
    np.testing.assert_allclose(
        jacobian, constraint_jacobian(hexapod_model, geometry, q_off), atol=1e-14
    )
    assert np.abs(errors).max() > 1e-4  # the offset pose really violates the anchors


def test_with_design_equals_reading_the_model(hexapod_model):
    template = StanceGeometry.from_model(hexapod_model, "all")
    for design in [
        HexapodDesign.from_ratios(0.1, 0.3),
        HexapodDesign.from_ratios(0.05, 0.6),
        HexapodDesign(l1=0.15, l2=0.5, l3=0.35, nominal_angles=(0.1, 0.2, -1.7)),
    ]:
        fast = template.with_design(design)
        slow = StanceGeometry.from_model(HexapodModel(design), "all")
        np.testing.assert_allclose(fast.footholds, slow.footholds, atol=1e-12)
        assert fast.nominal_height == pytest.approx(slow.nominal_height, abs=1e-15)
        np.testing.assert_allclose(fast.root_positions, slow.root_positions)
        np.testing.assert_allclose(fast.body_half_extents, slow.body_half_extents)


def test_of_design_takes_the_template_or_reads_the_model(hexapod_model):
    design = HexapodDesign.from_ratios(0.1, 0.45)
    template = StanceGeometry.from_model(hexapod_model, "tripod")
    fast = StanceGeometry.of_design(design, "all", template=template)
    assert fast.legs == template.legs  # a template's stance legs win
    np.testing.assert_array_equal(fast.footholds, template.with_design(design).footholds)
    slow = StanceGeometry.of_design(design, "tripod")
    assert slow.legs == template.legs and slow.lengths == design.lengths
    np.testing.assert_allclose(slow.footholds, fast.footholds, atol=1e-12)


def test_body_box_is_read_from_the_urdf(hexapod_model, default_design):
    geometry = StanceGeometry.from_model(hexapod_model)
    np.testing.assert_allclose(
        geometry.body_half_extents,
        np.array(
            [default_design.body_length, default_design.body_width, default_design.body_height]
        )
        / 2,
    )


def test_rigid_fit_recovers_a_random_transform():
    rng = np.random.default_rng(71)
    source = rng.normal(size=(6, 3))
    truth = pin.SE3(pin.rpy.rpyToMatrix(*rng.uniform(-3, 3, 3)), rng.normal(size=3))
    fitted = rigid_fit(source, source @ truth.rotation.T + truth.translation)
    np.testing.assert_allclose(fitted.homogeneous, truth.homogeneous, atol=1e-12)
    with pytest.raises(HexalegError):
        rigid_fit(source[:2], source[:2])


def test_stance_leg_sets(hexapod_model):
    assert stance_legs(hexapod_model, "tripod") == ("lf", "rm", "lr")
    assert len(stance_legs(hexapod_model, "all")) == 6
    for bad in ("bipod", ["lf", "lf", "rm"], ["lf", "rm"], ["lf", "rm", "xx"]):
        with pytest.raises(HexalegError):
            stance_legs(hexapod_model, bad)
