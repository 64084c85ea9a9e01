"""The multi-start driver: global among local optima, agreement, and exact acceptance."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.numerics.multistart import CoordinateProblem, Start, box_starts, maximize_coordinate

# Feasible set: two disks, radius 1 at the origin and radius 0.5 at (2.2, 0): the
# largest x is 2.7 in the small disk; starts near the origin find only 1.0.


def _constraints(x):
    big = 1.0 - x[0] ** 2 - x[1] ** 2
    small = 0.25 - (x[0] - 2.2) ** 2 - x[1] ** 2
    return np.array([max(big, small)])


def _jacobian(x):
    big = 1.0 - x[0] ** 2 - x[1] ** 2
    small = 0.25 - (x[0] - 2.2) ** 2 - x[1] ** 2
    if big >= small:
        return np.array([[-2 * x[0], -2 * x[1]]])
    return np.array([[-2 * (x[0] - 2.2), -2 * x[1]]])


def _feasible(x):
    return bool(_constraints(x)[0] >= -1e-9)


def _maximize(k, sign, constraints, jacobian, points, accept, enough=None, guided=0, scales=None):
    """The driver on plain points: the first ``guided`` of them do not vote."""
    problem = CoordinateProblem(k, sign, constraints, jacobian, accept)
    scales = scales or [None] * len(points)
    starts = [
        Start(
            np.asarray(p, dtype=float),
            None if s is None else np.asarray(s, dtype=float),
            i >= guided,
        )
        for i, (p, s) in enumerate(zip(points, scales, strict=True))
    ]
    return maximize_coordinate(problem, starts, enough=enough)


def test_the_best_local_optimum_wins_and_agreement_is_counted():
    starts = [
        np.array([0.1, 0.0]),
        np.array([-0.2, 0.3]),
        np.array([2.1, 0.1]),
        np.array([2.3, -0.1]),
    ]
    result = _maximize(0, 1, _constraints, _jacobian, starts, _feasible)
    assert result.value == pytest.approx(2.7, abs=1e-7)
    assert result.agreed  # two starts in the small disk reached 2.7
    assert sorted(np.round(result.values, 6)) == [1.0, 1.0, 2.7, 2.7]
    lone = _maximize(0, 1, _constraints, _jacobian, starts[:3], _feasible)
    assert lone.value == pytest.approx(2.7, abs=1e-7) and not lone.agreed


def test_minimizing_and_rejected_answers():
    starts = [np.array([0.0, 0.5]), np.array([0.2, -0.4])]
    result = _maximize(1, -1, _constraints, _jacobian, starts, _feasible)
    assert result.value == pytest.approx(1.0, abs=1e-7)  # min y = -1
    assert _maximize(1, -1, _constraints, _jacobian, starts, lambda x: False) is None


def test_early_stop_once_enough_starts_agree():
    def disk(x):
        return np.array([1.0 - x[0] ** 2 - x[1] ** 2])

    def disk_jacobian(x):
        return np.array([[-2 * x[0], -2 * x[1]]])

    starts = [np.array([0.1 * k - 0.3, 0.1]) for k in range(8)]
    result = _maximize(0, 1, disk, disk_jacobian, starts, _feasible, enough=(3, 3))
    assert len(result.values) == 3 and result.value == pytest.approx(1.0, abs=1e-7)
    everything = _maximize(0, 1, disk, disk_jacobian, starts, _feasible)
    assert len(everything.values) == 8


def test_starts_are_deterministic_and_inside_the_box():
    a = box_starts(np.array([1.0, 2.0, 0.0]), 8, seed=3)
    b = box_starts(np.array([1.0, 2.0, 0.0]), 8, seed=3)
    np.testing.assert_array_equal(np.array(a), np.array(b))
    assert np.all(np.abs(np.array(a)) <= [1.0, 2.0, 0.0])


def test_guided_starts_that_agree_on_a_local_optimum_do_not_stop_the_search():
    # three promising-looking starts all climb to x = 1 in the big disk; the fourth and
    # fifth reach 2.7 in the small one
    starts = [
        np.array([0.1, 0.0]),
        np.array([-0.2, 0.3]),
        np.array([0.0, -0.3]),
        np.array([2.1, 0.1]),
        np.array([2.3, -0.1]),
    ]
    fooled = _maximize(0, 1, _constraints, _jacobian, starts, _feasible, enough=(3, 3))
    assert fooled.value == pytest.approx(1.0, abs=1e-7) and len(fooled.values) == 3
    guided = _maximize(0, 1, _constraints, _jacobian, starts, _feasible, enough=(3, 2), guided=3)
    assert guided.value == pytest.approx(2.7, abs=1e-7)
    assert len(guided.values) == 5 and guided.agreed  # two unguided starts agree on 2.7


def test_scaled_starts_answer_in_the_callers_coordinates():
    # an ellipse 100 units long in x: max x = 100 at (100, 0), whatever the scale
    def ellipse(x):
        return np.array([1.0 - (x[0] / 100) ** 2 - x[1] ** 2])

    def ellipse_jacobian(x):
        return np.array([[-2 * x[0] / 100**2, -2 * x[1]]])

    def inside(x):
        return bool(ellipse(x)[0] >= -1e-9)

    starts = [np.array([10.0, 0.5]), np.array([-30.0, -0.2])]
    plain = _maximize(0, 1, ellipse, ellipse_jacobian, starts, inside)
    scaled = _maximize(
        0, 1, ellipse, ellipse_jacobian, starts, inside, scales=[None, np.array([100.0, 1.0])]
    )
    for result in (plain, scaled):
        assert result.value == pytest.approx(100.0, rel=1e-7)
        np.testing.assert_allclose(result.x, [100.0, 0.0], atol=1e-3)
        assert result.agreed
    # one point run twice, scaled and not, agrees only with itself
    twice = _maximize(
        0, 1, ellipse, ellipse_jacobian, starts[:1] * 2, inside, scales=[None, [100.0, 1.0]]
    )
    assert twice.value == pytest.approx(100.0, rel=1e-7) and not twice.agreed
    with pytest.raises(ValueError, match="scale must be positive"):
        _maximize(0, 1, ellipse, ellipse_jacobian, starts[:1], inside, scales=[[0.0, 1.0]])


def test_a_rejected_answer_counts_through_its_repair_flagged_not_converged():
    # The exact check is stricter than SLSQP's tolerance: only points 1e-3 inside the big
    # disk pass. Without a repair the boundary answer (x = 1) is dropped; the repair pulls
    # it back along the radius, and the answer counts, its success false.
    def strict(x):
        return bool(1.0 - np.hypot(*x) >= 1e-3 - 1e-12)

    def pulled_in(x):
        return x * (1.0 - 1e-3) / np.hypot(*x)

    start = [Start(np.array([0.1, 0.0]))]
    plain = CoordinateProblem(0, 1, _constraints, _jacobian, strict)
    assert maximize_coordinate(plain, start) is None
    repaired = CoordinateProblem(0, 1, _constraints, _jacobian, strict, repair=pulled_in)
    result = maximize_coordinate(repaired, start)
    assert result is not None and not result.success
    assert result.value == pytest.approx(1.0 - 1e-3, abs=1e-7) and strict(result.x)
    hopeless = CoordinateProblem(0, 1, _constraints, _jacobian, strict, repair=lambda x: None)
    assert maximize_coordinate(hopeless, start) is None
