"""Self-collision: adjacent legs of a short body touch under yaw; coal distances confirm it."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.cli import main
from hexaleg.exceptions import HexalegError
from hexaleg.stance import AXES, StanceGeometry, flexibility
from hexaleg.stance.collisions import SelfCollision
from hexaleg.stance.constraints import direction_poses, displacement_poses

SHORT_BODY = HexapodDesign(body_length=0.1, body_width=0.4)


@pytest.fixture(scope="module")
def short_body():
    model = HexapodModel(SHORT_BODY)
    geometry = StanceGeometry.from_model(model)
    return model, geometry, SelfCollision(model, geometry)


def test_every_pair_but_those_joined_by_a_joint(short_body):
    _, _, collision = short_body
    assert len(collision.pairs) == 19 * 18 // 2 - 18  # 19 parts; 18 joints join two each
    pairs = {frozenset(p) for p in collision.pairs}
    for leg in ("lf", "lm", "lr", "rf", "rm", "rr"):
        assert frozenset(("base_link", f"{leg}_coxa")) not in pairs
        assert frozenset((f"{leg}_coxa", f"{leg}_femur")) not in pairs
        assert frozenset((f"{leg}_femur", f"{leg}_tibia")) not in pairs
        assert frozenset((f"{leg}_coxa", f"{leg}_tibia")) in pairs
    assert frozenset(("lf_coxa", "lm_coxa")) in pairs


def test_adjacent_legs_of_a_short_body_collide_under_yaw(short_body):
    model, geometry, collision = short_body
    free_of_collisions = flexibility(SHORT_BODY, "axis", model=model)
    result = flexibility(SHORT_BODY, "axis", model=model, collisions=True)
    yaw = result.extreme("yaw", 1)
    assert yaw.limited_by.kind == "collision"
    # the mirror-image pairs touch together, both named, the first in pair order first
    assert [set(c.links) for c in yaw.binding] == [{"lf_coxa", "lm_coxa"}, {"rm_coxa", "rr_coxa"}]
    assert abs(yaw.value) < abs(free_of_collisions.extreme("yaw", 1).value)
    assert result.fb < free_of_collisions.fb
    for extreme in result.extremes:
        if extreme.limited_by.kind != "collision":
            continue
        k = AXES.index(extreme.axis)
        at = collision.distances(*direction_poses(geometry, k, extreme.value))
        assert 5e-6 < at.min() < 2e-5  # coal: clear, by the 10 µm contact distance
        beyond = direction_poses(geometry, k, extreme.value + extreme.sign * 1e-3)
        touching = _colliding_pairs(collision, *beyond)
        assert touching and tuple(extreme.limited_by.links) in touching
        for cause in extreme.binding:  # every pair named is as close as the closest
            assert at[collision.pairs.index(tuple(cause.links))] <= at.min() + 1e-6


@pytest.mark.slow
def test_free_extremes_with_collisions_are_collision_free(short_body):
    import warnings

    model, geometry, collision = short_body
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = flexibility(SHORT_BODY, "free", model=model, collisions=True)
    locked = flexibility(SHORT_BODY, "axis", model=model, collisions=True)
    for extreme, axis_locked in zip(result.extremes, locked.extremes, strict=True):
        distances = collision.distances(*displacement_poses(geometry, np.array(extreme.pose)))
        assert distances.min() >= -1e-9
        assert extreme.sign * extreme.value >= extreme.sign * axis_locked.value - 1e-12


@pytest.mark.parametrize("mode", ["axis", pytest.param("free", marks=pytest.mark.slow)])
def test_a_design_without_a_model_is_rendered_once(mode, monkeypatch, short_body):
    import warnings

    import hexaleg.robot.model

    renders = []
    render = hexaleg.robot.model.render_hexapod

    def counted(design):
        renders.append(design)
        return render(design)

    monkeypatch.setattr(hexaleg.robot.model, "render_hexapod", counted)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = flexibility(SHORT_BODY, mode, collisions=True)
    assert renders == [SHORT_BODY]
    reference = flexibility(SHORT_BODY, "axis", model=short_body[0], collisions=True)
    if mode == "axis":
        assert result.extremes == reference.extremes


def test_a_design_that_collides_standing_is_refused():
    # the left front coxa turned back across the middle one (legs 5 cm apart, feet apart)
    crossed = HexapodDesign(body_length=0.1, body_width=0.4, front_yaw=2.0)
    with pytest.raises(HexalegError, match="at the nominal stance, lf_coxa touches lm_coxa"):
        flexibility(crossed, "axis", collisions=True)


def test_cli_reports_the_two_links(capsys):
    argv = ["flexibility", "--collisions", "--body-length", "0.1", "--body-width", "0.4", "--json"]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["collisions"] is True
    yaw = next(e for e in data["extremes"] if e["axis"] == "yaw" and e["sign"] == 1)
    assert yaw["limited_by"]["kind"] == "collision"
    assert sorted(yaw["limited_by"]["links"]) == ["lf_coxa", "lm_coxa"]
    assert yaw["description"] == "lf_coxa touches lm_coxa (also rm_coxa touches rr_coxa)"


def _colliding_pairs(collision, rotation, translation):
    """Pairs coal finds intersecting (a boolean query, independent of the distances)."""
    import pinocchio as pin

    q = collision.configurations(rotation, translation)[0]
    pin.computeCollisions(
        collision.model.model,
        collision.model.data,
        collision.geometry_model,
        collision.geometry_data,
        q,
        False,
    )
    results = collision.geometry_data.collisionResults
    return {collision.pairs[i] for i, r in enumerate(results) if r.isCollision()}


def test_a_pose_distances_do_not_depend_on_the_queries_before_it(short_body):
    """Bit for bit: SLSQP's steps (and the free search's answer) must not follow the order
    in which poses are asked about (a warm-started GJK moves these by up to 5e-7 m)."""
    _, geometry, collision = short_body
    poses = np.random.default_rng(0).uniform(-1, 1, (40, 1, 6)) * [0.05, 0.05, 0.03, 0.1, 0.1, 0.3]

    def clearances(pose):
        return collision.pair_clearances(*displacement_poses(geometry, pose))

    first = [clearances(pose) for pose in poses]
    again = [clearances(pose) for pose in poses[::-1]][::-1]
    for a, b in zip(first, again, strict=True):
        np.testing.assert_array_equal(a, b)
