"""Body layouts: where each layout puts the legs, the round body, and its flexibility.

Oracles: the layouts' definitions written out here (corners and mid-points; every 60°
at the radius), the D-H closed form of each foot, yourdfpy reading the URDF, and an
independent step-and-bisect on Pinocchio with coal measuring the body's distance to
the ground.
"""

from __future__ import annotations

import io
import math

import coal
import numpy as np
import pinocchio as pin
import pytest
import yourdfpy

from hexaleg import HexapodDesign, HexapodModel, LegMount
from hexaleg.exceptions import DesignError
from hexaleg.kinematics import foot_position
from hexaleg.stance import StanceGeometry, direction_poses, flexibility, stance_configuration
from hexaleg.stance.constraints import AXES

CUSTOM = (
    LegMount("a", 0.45, 0.25, 0.0, 0.6),
    LegMount("b", 0.0, 0.35, 0.0, 1.5),
    LegMount("c", -0.4, 0.2, 0.0, 2.4),
    LegMount("d", 0.45, -0.25, 0.0, -0.6),
    LegMount("e", 0.0, -0.35, 0.0, -1.5),
    LegMount("f", -0.4, -0.2, 0.0, -2.4),
)


def _expected_mounts(design: HexapodDesign) -> dict[str, tuple[float, float, float]]:
    """(x, y, yaw) of every leg, straight from each layout's definition."""
    if design.layout == "hexagon":
        around = ("lf", "lm", "lr", "rr", "rm", "rf")  # counter-clockwise from the first
        angles = {n: design.first_leg_angle + k * math.pi / 3 for k, n in enumerate(around)}
        r = design.body_radius
        return {n: (r * math.cos(a), r * math.sin(a), a) for n, a in angles.items()}
    if design.layout == "custom":
        return {m.name: (m.x, m.y, m.yaw) for m in CUSTOM}
    hx, hy = design.body_length / 2, design.body_width / 2
    wide = hy + design.middle_leg_offset
    front, rear = design.front_yaw, design.rear_yaw
    return {
        "lf": (hx, hy, front),
        "lm": (0.0, wide, math.pi / 2),
        "lr": (-hx, hy, rear),
        "rf": (hx, -hy, -front),
        "rm": (0.0, -wide, -math.pi / 2),
        "rr": (-hx, -hy, -rear),
    }


LAYOUTS = {
    "rectangle": HexapodDesign(),
    "rectangle, wide middle, angled ends": HexapodDesign(
        middle_leg_offset=0.15, front_yaw=0.5, rear_yaw=2.5, l1=0.15, l2=0.45, l3=0.4
    ),
    "hexagon": HexapodDesign(layout="hexagon", body_radius=0.35),
    "hexagon, first leg ahead": HexapodDesign(
        layout="hexagon", body_radius=0.3, first_leg_angle=0.2, nominal_angles=(0.1, 0.2, -1.8)
    ),
    "custom": HexapodDesign(mounts=CUSTOM),
}


@pytest.mark.parametrize("design", LAYOUTS.values(), ids=LAYOUTS.keys())
def test_urdf_puts_every_foot_where_the_layout_and_closed_forms_say(design):
    robot = yourdfpy.URDF.load(io.BytesIO(HexapodModel(design).urdf.encode()), load_meshes=False)
    robot.update_cfg(
        {
            f"{leg}_{joint}_joint": angle
            for leg in design.leg_names
            for joint, angle in zip(("root", "hip", "knee"), design.nominal_angles, strict=True)
        }
    )
    foot = foot_position(design.lengths, design.nominal_angles)  # D-H closed form, eq 7
    for leg, (x, y, yaw) in _expected_mounts(design).items():
        c, s = math.cos(yaw), math.sin(yaw)
        expected = np.array([x + c * foot[0] - s * foot[1], y + s * foot[0] + c * foot[1], foot[2]])
        found = robot.get_transform(f"{leg}_foot", "base_link")[:3, 3]
        np.testing.assert_allclose(found, expected, atol=1e-12, err_msg=leg)


def test_hexagon_body_is_a_cylinder_of_the_radius():
    design = LAYOUTS["hexagon"]
    robot = yourdfpy.URDF.load(io.BytesIO(HexapodModel(design).urdf.encode()), load_meshes=False)
    body = robot.link_map["base_link"]
    for geometry in (body.visuals[0].geometry, body.collisions[0].geometry):
        assert geometry.cylinder.radius == design.body_radius
        assert geometry.cylinder.length == design.body_height
    geometry = StanceGeometry.from_model(HexapodModel(design))
    assert geometry.body_round
    assert not StanceGeometry.from_model(HexapodModel(HexapodDesign())).body_round


def _with_ground(model: HexapodModel):
    """The body's collision geometry and a ground half-space, for coal's signed distance."""
    geometry = pin.buildGeomFromUrdfString(model.model, model.urdf, pin.GeometryType.COLLISION)
    ground = geometry.addGeometryObject(
        pin.GeometryObject(
            "ground", 0, pin.SE3.Identity(), coal.Halfspace(np.array([0.0, 0.0, 1.0]), 0.0)
        )
    )
    geometry.addCollisionPair(pin.CollisionPair(geometry.getGeometryId("base_link_0"), ground))
    return geometry, geometry.createData()


@pytest.mark.parametrize("design", [LAYOUTS["hexagon"], LAYOUTS["rectangle"]], ids=["round", "box"])
def test_lowest_body_point_is_coals_distance_to_the_ground(design):
    model = HexapodModel(design)
    stance = StanceGeometry.from_model(model)
    collision, data = _with_ground(model)
    rng = np.random.default_rng(3)
    for _ in range(40):
        rotation = pin.rpy.rpyToMatrix(*rng.uniform(-0.6, 0.6, 3))
        translation = np.array([*rng.uniform(-0.1, 0.1, 2), rng.uniform(0.0, 0.5)])
        q = model.configuration(pin.SE3(rotation, translation))
        pin.computeDistances(model.model, model.data, collision, data, q)
        lowest = stance.lowest_body_height(rotation, translation)
        assert lowest == pytest.approx(data.distanceResults[0].min_distance, abs=1e-9)


def _feasible(model, geometry, collision, data, axis, value) -> bool:
    """Independent test of a pose: stance IK → Pinocchio feet, joint limits, coal ground."""
    rotation, translation = direction_poses(geometry, AXES.index(axis), value)
    q, solution = stance_configuration(model, geometry, pin.SE3(rotation, translation))
    feet = model.foot_positions(q)[[model.leg_names.index(leg) for leg in geometry.legs]]
    on_footholds = np.abs(feet - geometry.footholds).max() < 1e-9
    within = bool(geometry.limits.contains(solution.theta).all())
    pin.computeDistances(model.model, model.data, collision, data, q)
    above = data.distanceResults[0].min_distance >= -1e-10  # coal's offset is ~5e-12 m
    return bool(on_footholds and within and above)


def _step_and_bisect(feasible, sign: float, step: float, limit: float) -> float:
    """The first infeasible value along ``sign``, by steps of ``step`` then bisection."""
    inside = 0.0
    while abs(inside) < limit:
        outside = inside + sign * step
        if not feasible(outside):
            break
        inside = outside
    else:
        return inside
    for _ in range(60):
        middle = (inside + outside) / 2
        inside, outside = (middle, outside) if feasible(middle) else (inside, middle)
    return inside


BIG_ROUND_BODY = HexapodDesign(
    layout="hexagon", body_radius=0.8, body_height=0.7, l1=0.1, l2=0.45, l3=0.45
)
"""A body so wide and tall that its rim reaches the ground before any joint limit."""


@pytest.mark.parametrize(
    "design",
    [LAYOUTS["hexagon"], LAYOUTS["hexagon, first leg ahead"], BIG_ROUND_BODY],
    ids=["hexagon", "first leg ahead", "big round body"],
)
def test_hexagon_flexibility_equals_an_independent_step_and_bisect(design):
    model = HexapodModel(design)
    geometry = StanceGeometry.from_model(model)
    collision, data = _with_ground(model)
    result = flexibility(design, "axis", "all", model)
    for extreme in result.extremes:
        found = _step_and_bisect(
            lambda v, axis=extreme.axis: _feasible(model, geometry, collision, data, axis, v),
            extreme.sign,
            step=0.01,
            limit=1.5,
        )
        assert extreme.value == pytest.approx(found, abs=1e-6), extreme


def test_big_round_body_tilts_until_its_rim_touches_the_ground():
    result = flexibility(BIG_ROUND_BODY)
    for axis in ("z", "roll", "pitch"):
        assert result.extreme(axis, -1).limited_by.kind == "ground"
    # the rim is round: rolling and pitching reach the ground at the same angle
    assert result.extreme("roll", 1).value == pytest.approx(result.extreme("pitch", 1).value)


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"layout": "hexagon", "body_radius": 0.01}, "mounts"),  # six legs on one spot
        ({"mounts": (*CUSTOM[:5], LegMount("f", 0.45, 0.25, 0.0, 0.0))}, "mounts"),
        ({"layout": "hexagon", "body_radius": 0.1, "l1": 0.01, "l2": 0.2, "l3": 1.0,
          "nominal_angles": (0.0, 0.5, -2.35)}, "nominal footholds"),  # feet tucked inward
        ({"layout": "hexagon", "body_radius": -0.2}, "body_radius"),
        ({"layout": "octagon"}, "layout"),
        ({"layout": "hexagon", "first_leg_angle": 1.2}, "first_leg_angle"),
        ({"layout": "rectangle", "mounts": CUSTOM}, "mounts"),
    ],
)  # fmt: skip
def test_impossible_layouts_are_refused_naming_the_field(changes, field):
    with pytest.raises(DesignError) as caught:
        HexapodDesign(**changes)
    assert caught.value.field == field
    assert "\n" not in str(caught.value)


def test_layout_fields_move_the_legs_and_custom_mounts_stay():
    design = HexapodDesign(layout="hexagon")
    assert design.replace(body_radius=0.5).legs[1].y == pytest.approx(0.5)
    custom = HexapodDesign(mounts=CUSTOM)
    assert custom.layout == "custom"
    assert custom.replace(body_length=2.0).legs == CUSTOM
    assert HexapodDesign().replace(mounts=CUSTOM).layout == "custom"
    assert custom.replace(layout="rectangle").legs == HexapodDesign().legs


def test_a_custom_robots_tripod_is_every_other_leg_around_the_body():
    design = HexapodDesign(mounts=CUSTOM)  # around from straight ahead: a b c f e d
    result = flexibility(design, "axis", "tripod")
    assert set(result.legs) == {"a", "c", "e"}
    assert set(flexibility(HexapodDesign(layout="hexagon"), "axis", "tripod").legs) == {
        "lf",
        "rm",
        "lr",
    }


def test_round_bodys_smooth_ground_margins_hold_exactly_where_the_rim_is_above_ground():
    from hexaleg.stance.constraints import displacement_poses, stance_margins

    geometry = StanceGeometry.from_model(HexapodModel(BIG_ROUND_BODY))
    rng = np.random.default_rng(8)
    displacements = rng.uniform(-1, 1, size=(20_000, 6)) * [0.1, 0.1, 0.15, 0.3, 0.3, 0.3]
    rotation, translation = displacement_poses(geometry, displacements)
    exact = geometry.lowest_body_height(rotation, translation)
    smooth = stance_margins(geometry, rotation, translation, smooth=True)[:, -2:]  # the rim's two
    clear = np.abs(exact) > 1e-9
    np.testing.assert_array_equal(exact[clear] > 0, smooth[clear].min(axis=1) > 0)
    assert 0.05 < (exact < 0).mean() < 0.95  # both sides were sampled
