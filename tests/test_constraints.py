"""Stance constraints: rpy as Pinocchio's, smooth margins with the same feasible set."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.stance import StanceGeometry
from hexaleg.stance.constraints import (
    AXES,
    direction_poses,
    displacement_poses,
    rpy_rotation,
    stance_margins,
)


def test_rpy_rotation_is_pinocchios():
    rng = np.random.default_rng(5)
    angles = rng.uniform(-3, 3, size=(200, 3))
    expected = np.array([pin.rpy.rpyToMatrix(*a) for a in angles])
    np.testing.assert_allclose(rpy_rotation(angles), expected, atol=1e-15)


def test_direction_poses_are_one_hot_displacements(hexapod_model):
    geometry = StanceGeometry.from_model(hexapod_model)
    for k, _ in enumerate(AXES):
        rotation, translation = direction_poses(geometry, k, 0.1)
        displacement = np.zeros(6)
        displacement[k] = 0.1
        r2, t2 = displacement_poses(geometry, displacement)
        np.testing.assert_array_equal(rotation, r2)
        np.testing.assert_array_equal(translation, t2)


@pytest.mark.parametrize("stance", ["all", "tripod"])
def test_smooth_margins_have_the_same_feasible_set(hexapod_model, stance):
    geometry = StanceGeometry.from_model(hexapod_model, stance)
    rng = np.random.default_rng(6)
    displacements = rng.uniform(-1, 1, size=(20_000, 6)) * [0.25, 0.25, 0.2, 0.25, 0.25, 0.3]
    rotation, translation = displacement_poses(geometry, displacements)
    exact = stance_margins(geometry, rotation, translation)
    smooth = stance_margins(geometry, rotation, translation, smooth=True)
    legs = exact.shape[1] - 1  # the legs' columns match one to one; the ground is last
    clear = np.abs(exact[:, :legs]) > 1e-9  # away from the boundary, where signs are defined
    np.testing.assert_array_equal(np.sign(exact[:, :legs][clear]), np.sign(smooth[:, :legs][clear]))
    ground, smooth_ground = exact[:, legs], smooth[:, legs:]
    clear = np.abs(ground) > 1e-9
    np.testing.assert_array_equal(ground[clear] > 0, smooth_ground[clear].min(axis=1) > 0)
    assert 0.01 < (exact.min(axis=1) >= 0).mean() < 0.99  # both sides were sampled
    assert 0.001 < (ground < 0).mean()  # and the ground broke in some
