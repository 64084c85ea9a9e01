"""A design's model derived from its body's equals the one built from its URDF."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.design import HexapodDesign
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.model_cache import body_key, model_of
from hexaleg.stance.geometry import _read_body_shape, body_collision_shape


def _designs() -> list[HexapodDesign]:
    rng = np.random.default_rng(5)
    return [
        HexapodDesign(
            l1=float(rng.uniform(0.1, 0.3)), l2=float(rng.uniform(0.35, 0.5)),
            l3=float(rng.uniform(0.35, 0.5)), body_width=0.55,
            rated_torques=tuple(float(x) for x in rng.uniform(50, 200, 3)),
            nominal_angles=(0.0, float(rng.uniform(-0.2, 0.2)), -1.5),
        )
        for _ in range(3)
    ]  # fmt: skip


@pytest.mark.parametrize("design", _designs())
def test_a_derived_model_is_the_model_built_from_the_urdf(design):
    derived, built = model_of(design), HexapodModel(design)
    assert derived.design == design
    q = built.nominal_configuration()
    np.testing.assert_allclose(derived.foot_positions(q), built.foot_positions(q), atol=1e-12)
    np.testing.assert_allclose(
        pin.crba(derived.model, derived.data, q), pin.crba(built.model, built.data, q), atol=1e-9
    )
    np.testing.assert_array_equal(derived.model.effortLimit, built.model.effortLimit)
    shape, round_body = body_collision_shape(derived)
    np.testing.assert_array_equal(shape, _read_body_shape(built)[0])
    assert round_body == _read_body_shape(built)[1]


def test_designs_of_one_body_share_it_and_another_body_gets_its_own():
    one, two = _designs()[:2]
    assert body_key(one) == body_key(two)
    wider = one.replace(body_width=0.7)
    assert body_key(wider) != body_key(one)
    q = HexapodModel(wider).nominal_configuration()
    np.testing.assert_allclose(
        model_of(wider).foot_positions(q), HexapodModel(wider).foot_positions(q), atol=1e-12
    )


def test_what_a_caller_does_to_its_model_does_not_reach_the_next_one():
    design = _designs()[0]
    first = model_of(design)
    first.model.inertias[1] = pin.Inertia.Zero()
    again = model_of(design)
    assert again.model.inertias[1].mass > 0
