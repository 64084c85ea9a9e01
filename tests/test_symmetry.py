"""Mirror symmetry: which robots are their own mirror image, and mirrored extremes are real."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from hexaleg import HexapodDesign, HexapodModel, JointLimits
from hexaleg.limits import STANCE_LIMITS
from hexaleg.stance import StanceGeometry
from hexaleg.stance.axis_locked import axis_locked_extremes
from hexaleg.stance.constraints import AXES, DIRECTIONS
from hexaleg.stance.free_coupled import _Search
from hexaleg.stance.free_problem import FreeProblem
from hexaleg.stance.symmetry import MIRRORS, keeping, mirror_flips, mirror_sources

LEFT_RIGHT, FRONT_BACK = (tuple(flip) for _, flip in MIRRORS.values())


@pytest.mark.parametrize(
    ("design", "stance", "expected"),
    [
        (HexapodDesign(), "all", {LEFT_RIGHT, FRONT_BACK}),
        (HexapodDesign(layout="hexagon"), "all", {LEFT_RIGHT, FRONT_BACK}),
        (HexapodDesign(layout="hexagon", first_leg_angle=0.3), "all", set()),  # 0.3 ≠ −0.3 mod 60°
        (HexapodDesign(front_yaw=0.5), "all", {LEFT_RIGHT}),
        (HexapodDesign(), "tripod", {FRONT_BACK}),  # (lf, rm, lr): front and back swap
        (
            HexapodDesign(
                stance_limits=JointLimits(
                    (-0.5, 0.7), STANCE_LIMITS.theta2, STANCE_LIMITS.theta3, name="lopsided"
                )
            ),
            "all",
            set(),
        ),
    ],
    ids=["box", "hexagon", "hexagon turned", "front legs angled", "tripod", "lopsided root"],
)
def test_mirror_flips_find_exactly_the_robots_symmetries(design, stance, expected):
    geometry = StanceGeometry.from_model(HexapodModel(design), stance)
    assert {tuple(flip) for flip in mirror_flips(geometry)} == expected


def test_a_mirrored_free_extreme_equals_solving_it_directly():
    design = HexapodDesign(l1=0.15, l2=0.5, l3=0.35)
    geometry = StanceGeometry.from_model(HexapodModel(design))
    locked = axis_locked_extremes(geometry)
    problem = FreeProblem(geometry, None)
    search = _Search(problem, locked)
    left_right = MIRRORS["left-right"][1]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for axis in ("y", "roll", "yaw"):
            plus, minus = (
                next(e for e in locked if (e.axis, e.sign) == (axis, s)) for s in (1, -1)
            )
            mirrored = search.mirrored(minus, search.solve(plus, *search.basins(plus)), left_right)
            direct = search.solve(minus, *search.basins(minus))
            assert mirrored is not None
            assert mirrored.value == pytest.approx(direct.value, abs=1e-6)
            assert problem.feasible(np.asarray(mirrored.pose))


def test_each_mirrored_direction_comes_from_its_opposite_solved_first():
    left_right, front_back = (flip for _, flip in MIRRORS.values())
    sources = mirror_sources(DIRECTIONS, [left_right, front_back])
    taken = {
        DIRECTIONS[i]: (DIRECTIONS[source], tuple(flip)) for i, (source, flip) in sources.items()
    }
    # y, roll reverse under left-right; x, pitch under front-back; yaw under either (the first)
    assert set(taken) == {("x", -1), ("y", -1), ("roll", -1), ("pitch", -1), ("yaw", -1)}
    for (axis, _), (source, flip) in taken.items():
        assert source == (axis, 1) and flip[AXES.index(axis)] == -1
    assert mirror_sources(DIRECTIONS, []) == {}


def test_the_symmetries_that_keep_a_coordinate():
    left_right, front_back = (flip for _, flip in MIRRORS.values())
    both = left_right * front_back
    as_sets = lambda flips: {tuple(f) for f in flips}  # noqa: E731
    assert as_sets(keeping(2, [left_right, front_back])) == as_sets([left_right, front_back, both])
    assert as_sets(keeping(5, [left_right, front_back])) == as_sets([both])  # yaw
    assert as_sets(keeping(0, [left_right, front_back])) == as_sets([left_right])  # x
    assert keeping(1, [left_right]) == []  # y: the one mirror reverses it


def test_mirror_image_optima_are_reported_as_one_pose():
    geometry = StanceGeometry.from_model(HexapodModel(HexapodDesign()), "all")
    problem = FreeProblem(geometry, None)
    assert len(problem.flips) == 2
    z = 2  # z−'s optimum of the default design (as found): yaw and a sideways shift
    pose = np.array(
        [
            -0.11845213835774489,
            -0.14288266234399993,
            -0.23744482708278944,
            -0.03959812194043945,
            0.012492998212773257,
            0.3107475359124815,
        ]
    )
    images = [pose, *(flip * pose for flip in keeping(z, problem.flips))]
    assert all(problem.feasible(image) for image in images)
    chosen = [problem.canonical(image, z) for image in images]
    for image in chosen[1:]:
        np.testing.assert_array_equal(image, chosen[0])
    assert chosen[0][z] == pose[z]
