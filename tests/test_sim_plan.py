"""The plan's reference between samples: exact at samples, exact on cubics, periodic."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.exceptions import HexalegError
from hexaleg.sim.plan import Plan


def _plan(samples: int, period: float, angle, rate, torque) -> Plan:
    t = np.arange(samples) * period / samples
    shape = (samples, 2, 3)
    standing = np.zeros((samples, 2), dtype=bool)
    standing[: samples // 2, 0] = True
    return Plan(
        period=period,
        angles=np.broadcast_to(angle(t)[:, None, None], shape).copy(),
        rates=np.broadcast_to(rate(t)[:, None, None], shape).copy(),
        torques=np.broadcast_to(torque(t)[:, None, None], shape).copy(),
        standing=standing,
        velocity=np.array([0.1, 0.0]),
    )


def test_reference_is_the_samples_at_sample_times():
    rng = np.random.default_rng(1)
    plan = Plan(
        2.0,
        rng.normal(size=(10, 6, 3)),
        rng.normal(size=(10, 6, 3)),
        rng.normal(size=(10, 6, 3)),
        rng.random((10, 6)) > 0.5,
        np.zeros(2),
    )
    times = np.arange(10) * 0.2
    for got, expected in zip(
        plan.reference(times), (plan.angles, plan.rates, plan.torques, plan.standing), strict=True
    ):
        np.testing.assert_allclose(got, expected, atol=1e-12)
    later = plan.reference(times + 3 * plan.period)  # it repeats every period
    np.testing.assert_allclose(later[0], plan.angles, atol=1e-12)


def test_angles_between_samples_follow_a_cubic_exactly_and_speeds_and_torques_a_line():
    def cubic(t):
        return 0.3 - 0.2 * t + 0.5 * t**2 - 0.4 * t**3

    def slope(t):
        return -0.2 + t - 1.2 * t**2

    plan = _plan(8, 8.0, cubic, slope, lambda t: 2.0 * t)  # one sample a second
    times = np.array([0.25, 1.5, 2.9, 6.01])
    angles, rates, torques, standing = plan.reference(times)
    np.testing.assert_allclose(angles[:, 0, 0], cubic(times), atol=1e-12)
    k = np.floor(times)
    expected_rate = slope(k) + (times - k) * (slope(k + 1) - slope(k))
    np.testing.assert_allclose(rates[:, 1, 2], expected_rate, atol=1e-12)
    np.testing.assert_allclose(torques[:, 0, 1], 2.0 * times, atol=1e-12)
    np.testing.assert_array_equal(standing[:, 0], [True, True, True, False])


def test_the_last_sample_joins_the_first():
    plan = _plan(4, 4.0, lambda t: np.where(t < 2.5, 0.0, 1.0), lambda t: 0 * t, lambda t: t)
    angles, _, torques, _ = plan.reference(np.array([3.5]))
    assert angles[0, 0, 0] == pytest.approx(0.5)  # from 1 at t = 3 back to 0 at t = 4
    assert torques[0, 0, 0] == pytest.approx(1.5)  # from 3 at t = 3 back to 0 at t = 4


def test_malformed_plans_are_refused():
    with pytest.raises(HexalegError, match="shape"):
        Plan(
            1.0,
            np.zeros((4, 6, 2)),
            np.zeros((4, 6, 2)),
            np.zeros((4, 6, 2)),
            np.zeros((4, 6), bool),
            np.zeros(2),
        )
    with pytest.raises(HexalegError, match="period"):
        Plan(
            0.0,
            np.zeros((4, 6, 3)),
            np.zeros((4, 6, 3)),
            np.zeros((4, 6, 3)),
            np.zeros((4, 6), bool),
            np.zeros(2),
        )
