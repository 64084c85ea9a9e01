"""The compiled margins equal the NumPy reference, column for column, for every geometry."""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.limits import IMPROVED_LIMITS, STANCE_LIMITS, JointLimits
from hexaleg.stance.constraints import displacement_poses, smooth_stance_margins, stance_margins
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.stance.margin_kernel import compiled_margins

# the knee's three smooth forms: cos θ3 (the stance limits), the hip-coupled bound, and
# θ3 itself where the knee may straighten past 0 (cos θ3 is then not monotonic)
THETA_KNEE = JointLimits(STANCE_LIMITS.theta1, STANCE_LIMITS.theta2, (-2.5, 0.3), name="theta")
VARIANTS = {
    "box, all legs, cos θ3 knee": ({}, "all"),
    "box, tripod": ({}, "tripod"),
    "cylinder body (hexagon)": ({"layout": "hexagon"}, "all"),
    "coupled knee (Table 4)": ({"stance_limits": IMPROVED_LIMITS}, "all"),
    "θ3 knee": ({"stance_limits": THETA_KNEE}, "all"),
    "long coxa, short femur": ({"l1": 0.3, "l2": 0.15, "l3": 0.55}, "all"),
}


@cache
def _geometry(name: str) -> StanceGeometry:
    fields, stance = VARIANTS[name]
    design = HexapodDesign(**fields)
    return StanceGeometry.from_model(HexapodModel(design), stance)


def _reference(geometry: StanceGeometry, displacements: np.ndarray, smooth: bool) -> np.ndarray:
    margins = smooth_stance_margins if smooth else stance_margins
    return margins(geometry, *displacement_poses(geometry, displacements))


def test_the_variants_cover_each_knee_form_and_body():
    assert _geometry("coupled knee (Table 4)").limits.coupled_knee
    cos_form = _geometry("box, all legs, cos θ3 knee").limits.theta3
    assert -math.pi <= cos_form[0] < cos_form[1] <= 0
    assert _geometry("θ3 knee").limits.theta3[1] > 0
    assert _geometry("cylinder body (hexagon)").body_round
    assert not _geometry("box, tripod").body_round and len(_geometry("box, tripod").legs) == 3


# displacements from small to far out of reach (clipped IK, negative margins)
DISPLACEMENTS = arrays(
    np.float64,
    (5, 6),
    elements=st.floats(-1.0, 1.0, allow_nan=False),
).map(lambda unit: unit * np.array([0.8, 0.8, 0.5, 1.2, 1.2, 2.5]))


@pytest.mark.parametrize("smooth", [True, False], ids=["smooth", "exact"])
@pytest.mark.parametrize("name", list(VARIANTS))
@settings(max_examples=40, deadline=None)
@given(displacements=DISPLACEMENTS)
def test_compiled_margins_equal_the_numpy_reference(name, smooth, displacements):
    geometry = _geometry(name)
    compiled = compiled_margins(geometry, smooth)(displacements)
    reference = _reference(geometry, displacements, smooth)
    np.testing.assert_allclose(compiled, reference, rtol=1e-12, atol=1e-12)


def test_any_batch_shape_and_a_single_displacement():
    geometry = _geometry("box, all legs, cos θ3 knee")
    margins = compiled_margins(geometry)
    rng = np.random.default_rng(3)
    batch = rng.uniform(-0.2, 0.2, size=(2, 3, 6))
    reference = _reference(geometry, batch, smooth=True)
    assert margins(batch).shape == reference.shape == (2, 3, 8 * 6 + 8)
    np.testing.assert_allclose(margins(batch), reference, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(margins(batch[0, 0]), reference[0, 0], rtol=1e-12, atol=1e-12)
    assert margins(np.zeros(6)).min() > 0  # the nominal stance is feasible
