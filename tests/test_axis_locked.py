"""Axis-locked flexibility: extremes at the first failure, with their causes, against Pinocchio."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from margin_oracle import exact_margins

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.stance import StanceGeometry, direction_poses, flexibility, stance_configuration
from hexaleg.stance.constraints import AXES, constraint_labels

DESIGNS = [
    HexapodDesign(),
    HexapodDesign.from_ratios(0.05, 0.3),
    HexapodDesign.from_ratios(0.15, 0.6),
    HexapodDesign(l1=0.1, l2=0.5, l3=0.3, nominal_angles=(0.0, 0.2, -1.9)),
]


def _feasible_in_pinocchio(model, geometry, axis, value):
    """Independent check: stance IK pose → Pinocchio FK, limits and the body box."""
    rotation, translation = direction_poses(geometry, AXES.index(axis), value)
    body = pin.SE3(rotation, translation)
    q, solution = stance_configuration(model, geometry, body)
    feet = model.foot_positions(q)[[model.leg_names.index(leg) for leg in geometry.legs]]
    on_footholds = np.abs(feet - geometry.footholds).max() < 1e-9
    within = geometry.limits.contains(solution.theta, tol=0.0).all()
    above = geometry.body_corners(body.rotation, body.translation)[:, 2].min() >= 0
    return bool(on_footholds and within and above)


@pytest.mark.parametrize("design", DESIGNS, ids=lambda d: f"l={d.l1:.2f},{d.l2:.2f},{d.l3:.2f}")
@pytest.mark.parametrize("stance", ["all", "tripod"])
def test_each_extreme_is_feasible_inside_and_infeasible_outside(design, stance):
    model = HexapodModel(design)
    geometry = StanceGeometry.from_model(model, stance)
    result = flexibility(design, "axis", stance, model)
    labels = constraint_labels(geometry.legs)
    for extreme in result.extremes:
        assert extreme.limited_by.kind != "range"
        inside = extreme.value - extreme.sign * 1e-7
        outside = extreme.value + extreme.sign * 1e-7
        assert _feasible_in_pinocchio(model, geometry, extreme.axis, inside), extreme
        assert not _feasible_in_pinocchio(model, geometry, extreme.axis, outside), extreme
        # the reported cause is the constraint that breaks just outside
        rotation, translation = direction_poses(geometry, AXES.index(extreme.axis), outside)
        margins = exact_margins(geometry, rotation, translation)
        broken = {str(labels[k]) for k in np.flatnonzero(margins < 0)}
        assert str(extreme.limited_by) in broken
        # continuous motion: every pose between nominal and the extreme is feasible
        for value in np.linspace(0, inside, 60):
            rotation, translation = direction_poses(geometry, AXES.index(extreme.axis), value)
            assert exact_margins(geometry, rotation, translation).min() >= 0


def test_symmetric_robot_has_symmetric_extremes(hexapod_model, default_design):
    result = flexibility(default_design, "axis", "all", hexapod_model)
    for axis in ("x", "y", "roll", "pitch", "yaw"):
        assert result.extreme(axis, 1).value == pytest.approx(
            -result.extreme(axis, -1).value, abs=1e-9
        )


@pytest.mark.parametrize("l1_ratio", [0.05, 0.2])
@pytest.mark.parametrize("l3_ratio", [0.1, 0.3, 0.45, 0.7])
def test_fb_lies_in_0_1(l1_ratio, l3_ratio):
    result = flexibility(HexapodDesign.from_ratios(l1_ratio, l3_ratio), "axis", "all")
    assert 0 <= result.fb <= 1


@pytest.mark.parametrize("layout", ["rectangle", "hexagon"])
def test_many_designs_searched_together_equal_each_searched_alone(layout):
    from hexaleg.design import l3_ratio_grid
    from hexaleg.stance.axis_locked import axis_locked_extremes, axis_locked_extremes_many

    base = HexapodDesign(layout=layout)
    template = StanceGeometry.from_model(HexapodModel(base))
    geometries = [
        template.with_design(base.with_ratios(r1, r3))
        for r1 in (0.05, 0.2)
        for r3 in l3_ratio_grid(9)
    ]
    together = axis_locked_extremes_many(geometries)
    for geometry, extremes in zip(geometries, together, strict=True):
        alone = axis_locked_extremes(geometry)
        assert [e.value for e in extremes] == pytest.approx([e.value for e in alone], abs=1e-12)
        assert [e.binding for e in extremes] == [e.binding for e in alone]
        assert [e.pose for e in extremes] == [e.pose for e in alone]
