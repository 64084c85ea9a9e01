"""The compiled margins equal the oracle's (tests/margin_oracle.py), column by column."""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from margin_oracle import displaced, exact_margins, smooth_margins

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.limits import IMPROVED_LIMITS, STANCE_LIMITS, JointLimits
from hexaleg.stance.constraints import displacement_poses, stance_margins
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.stance.margin_kernel import kernel_geometry, margins_of

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


def _compiled(geometry: StanceGeometry, displacements: np.ndarray, smooth: bool) -> np.ndarray:
    """The kernel's margins of displacements (P, 6), as the searches ask for them."""
    flat = np.ascontiguousarray(displacements, dtype=float)
    return margins_of(kernel_geometry([geometry], smooth), flat, np.zeros(len(flat), np.int64))


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
def test_compiled_margins_equal_the_oracles(name, smooth, displacements):
    geometry = _geometry(name)
    compiled = _compiled(geometry, displacements, smooth)
    reference = displaced(geometry, displacements, smooth)
    np.testing.assert_allclose(compiled, reference, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("smooth", [True, False], ids=["smooth", "exact"])
def test_stance_margins_of_poses_in_any_batch_shape(smooth):
    geometry = _geometry("box, all legs, cos θ3 knee")
    rng = np.random.default_rng(3)
    batch = rng.uniform(-0.2, 0.2, size=(2, 3, 6))
    rotation, translation = displacement_poses(geometry, batch)
    margins = stance_margins(geometry, rotation, translation, smooth=smooth)
    oracle = smooth_margins if smooth else exact_margins
    reference = oracle(geometry, rotation, translation)
    assert margins.shape == reference.shape == (2, 3, 8 * 6 + (8 if smooth else 1))
    np.testing.assert_allclose(margins, reference, rtol=1e-12, atol=1e-12)
    one = stance_margins(geometry, rotation[0, 0], translation[0, 0], smooth=smooth)
    np.testing.assert_allclose(one, reference[0, 0], rtol=1e-12, atol=1e-12)
    level = stance_margins(geometry, np.eye(3), translation, smooth=smooth)  # broadcast
    np.testing.assert_allclose(level, oracle(geometry, np.eye(3), translation), atol=1e-12)
    nominal = stance_margins(geometry, np.eye(3), [0.0, 0.0, geometry.nominal_height])
    assert nominal.min() > 0  # the nominal stance is feasible
