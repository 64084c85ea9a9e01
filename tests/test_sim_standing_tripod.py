"""Standing on a tripod in MuJoCo: the vertical foot forces are the statics' (`loads`)."""

from __future__ import annotations

import os

import numpy as np
import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.kinematics import foot_position
from hexaleg.statics.forces import GRAVITY, Payload
from hexaleg.statics.loads import analyze_loads

if not os.environ.get("CI"):  # CI installs hexaleg[test], which includes the sim extra
    pytest.importorskip("mujoco")

from conftest import random_designs

from hexaleg.sim.standing_tripod import LIFT, lifted_configuration, standing_check

CASES = [
    (HexapodDesign(), Payload(40.0)),
    (HexapodDesign(), Payload(30.0, (0.15, -0.05, 0.1))),
    (random_designs(1, seed=2501)[0], Payload(20.0)),
]


@pytest.fixture(scope="module", params=CASES, ids=["default", "off-centre-payload", "random"])
def case(request):
    design, payload = request.param
    model = HexapodModel(design)
    return design, payload, standing_check(model, payload)


def test_standing_forces_agree_with_loads_within_3_percent(case):
    design, payload, check = case
    loads = analyze_loads(design, payload, stance="tripod")
    assert check.legs == loads.nominal.legs == ("lf", "rm", "lr")
    for leg, force in zip(loads.nominal.legs, loads.nominal.foot_forces, strict=True):
        assert check.statics_foot_forces_z[leg] == pytest.approx(force[2], rel=1e-12)
        assert check.foot_forces_z[leg] == pytest.approx(force[2], rel=0.03)
    assert check.worst_relative_error < 0.03


def test_the_tripod_carries_the_whole_weight(case):
    design, payload, check = case
    weight = (design.total_mass + payload.mass) * GRAVITY  # the design's masses, not a model's
    assert sum(check.foot_forces_z.values()) == pytest.approx(weight, rel=0.005)
    assert check.duration == pytest.approx(2.0)


def test_the_other_feet_are_lifted_straight_up():
    model = HexapodModel(HexapodDesign())
    q = lifted_configuration(model, ("lf", "rm", "lr"), LIFT)
    feet = model.foot_positions(q)
    nominal = model.foot_positions(model.nominal_configuration())
    lift = np.array([0.0, 0.0, LIFT])
    for i, leg in enumerate(model.leg_names):
        expected = nominal[i] + (0.0 if leg in ("lf", "rm", "lr") else lift)
        np.testing.assert_allclose(feet[i], expected, atol=1e-12)
    design = model.design
    assert foot_position(design.lengths, design.nominal_angles)[2] < 0  # feet below the roots


def test_json_fields(case):
    _, _, check = case
    fields = check.to_dict()
    assert set(fields) == {"foot_forces_z", "statics_foot_forces_z"}
    assert set(fields["foot_forces_z"]) == set(fields["statics_foot_forces_z"]) == set(check.legs)
