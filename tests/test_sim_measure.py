"""The walk's measures, on synthetic traces whose answers are known by construction."""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.sim.measure import (
    FALL_TILT,
    Trace,
    WalkMeter,
    fell,
    foot_slip,
    internal_forces,
    measure_walk,
    peak_torques,
    roll_pitch,
)

LEGS = ("lf", "lm", "lr", "rf", "rm", "rr")
RATED = (60.0, 150.0, 120.0)


def _quaternion(roll: float, pitch: float, yaw: float) -> np.ndarray:
    q = pin.Quaternion(pin.rpy.rpyToMatrix(roll, pitch, yaw))
    return np.array([q.w, q.x, q.y, q.z])


def test_roll_pitch_are_pinocchios_rpy():
    rng = np.random.default_rng(5)
    angles = rng.uniform(-1.2, 1.2, size=(20, 3))
    quats = np.array([_quaternion(*a) for a in angles])
    np.testing.assert_allclose(roll_pitch(quats), angles[:, :2], atol=1e-12)


def test_foot_slip_is_the_largest_move_within_one_stance():
    xy = np.zeros((8, 2, 2))
    standing = np.zeros((8, 2), dtype=bool)
    standing[0:3, 0] = standing[5:8, 0] = True
    xy[:, 0, 0] = [0.0, 0.01, 0.02, 0.5, 0.9, 1.0, 1.0, 1.03]  # swing moves 0.98 m: not slip
    standing[:, 1] = True
    xy[:, 1, 1] = [0.0, 0.004, -0.01, 0.0, 0.0, 0.0, 0.0, 0.0]
    assert foot_slip(xy, standing) == pytest.approx(0.03)
    assert foot_slip(xy[:, 1:], standing[:, 1:]) == pytest.approx(0.01)
    assert foot_slip(xy, np.zeros_like(standing)) == 0.0


def test_peak_torques_per_joint_type():
    torques = np.zeros((4, 6, 3))
    torques[2, 3] = [-5.0, 7.0, -9.0]
    torques[1, 0] = [4.0, -8.0, 1.0]
    assert peak_torques(torques) == {"root": 5.0, "hip": 8.0, "knee": 9.0}


def _trace(period: float, cycles: int, velocity, roll, height: float, dt: float = 0.01) -> Trace:
    time = np.arange(0.0, period * cycles + 1e-9, dt)
    k = len(time)
    base = np.zeros((k, 3))
    base[:, :2] = np.outer(time, velocity)
    base[:, 2] = height
    quats = np.array([_quaternion(r, -0.5 * r, 0.3) for r in roll(time)])
    angles = np.zeros((k, 6, 3))
    reference = angles + 0.02  # every joint 0.02 rad behind
    torques = np.zeros((k, 6, 3))
    torques[:, :, 1] = 10.0 * np.sin(time)[:, None]
    feet = np.zeros((k, 6, 3))
    standing = np.ones((k, 6), dtype=bool)
    return Trace(time, base, quats, angles, reference, torques, feet, standing)


def test_measure_walk_on_a_known_motion():
    period, cycles = 1.5, 4
    velocity = np.array([0.12, -0.05])
    trace = _trace(period, cycles, velocity, lambda t: 0.03 * np.sin(t) * (t >= 0), 0.4)
    metrics = measure_walk(trace, period, cycles, velocity, 0.4, legs=LEGS, rated_torques=RATED)
    speed = math.hypot(*velocity)
    assert metrics.planned_distance == pytest.approx(speed * period * 3)
    assert metrics.distance == pytest.approx(speed * period * 3, rel=1e-9)
    assert metrics.distance_ratio == pytest.approx(1.0)
    measured = trace.time[trace.time >= period]
    assert metrics.max_roll == pytest.approx(np.abs(0.03 * np.sin(measured)).max(), rel=1e-9)
    assert metrics.max_pitch == pytest.approx(0.5 * metrics.max_roll, rel=1e-9)
    assert metrics.max_tilt == metrics.max_roll
    assert metrics.min_height == pytest.approx(0.4)
    assert metrics.tracking_rms == pytest.approx(0.02)
    assert metrics.slip == 0.0
    assert metrics.peak_torque["hip"] == pytest.approx(10.0 * np.abs(np.sin(measured)).max())
    assert not metrics.fell


def test_a_walk_that_goes_sideways_covers_no_distance_along_its_heading():
    trace = _trace(1.0, 3, np.array([0.0, 0.2]), lambda t: 0 * t, 0.4)
    metrics = measure_walk(trace, 1.0, 3, np.array([0.2, 0.0]), 0.4, legs=LEGS, rated_torques=RATED)
    assert metrics.distance == pytest.approx(0.0, abs=1e-12)
    assert metrics.distance_ratio == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize(
    ("roll", "height", "expected"),
    [
        (FALL_TILT * 0.99, 0.4, False),
        (FALL_TILT * 1.01, 0.4, True),
        (0.0, 0.19, True),
        (0.0, 0.21, False),
    ],
)
def test_fell_when_tilted_past_30_degrees_or_below_half_height(roll, height, expected):
    trace = _trace(1.0, 2, np.array([0.1, 0.0]), lambda t: roll * (t > 0.2), height)
    assert fell(trace, nominal_height=0.4) is expected


def test_a_fall_in_the_first_cycle_counts():
    trace = _trace(1.0, 3, np.array([0.1, 0.0]), lambda t: 1.0 * (t < 0.5), 0.4)
    assert measure_walk(
        trace, 1.0, 3, np.array([0.1, 0.0]), 0.4, legs=LEGS, rated_torques=RATED
    ).fell


def test_servos_over_their_rating_are_flagged_with_when_they_peak():
    period, cycles = 1.0, 3
    trace = _trace(period, cycles, np.array([0.1, 0.0]), lambda t: 0 * t, 0.4)
    trace.joint_torques[5, 2, 0] = 500.0  # in the first period: not measured
    trace.joint_torques[250, 4, 2] = -130.0  # rm's knee, once, at t = 2.5 s
    legs, rated = LEGS, (60.0, 9.0, 120.0)
    metrics = measure_walk(
        trace, period, cycles, np.array([0.1, 0.0]), 0.4, legs=legs, rated_torques=rated
    )
    measured = trace.time[trace.time >= period]
    hip_peak = 10.0 * np.abs(np.sin(measured)).max()  # every leg's hip: 10 sin t > 9
    hip_time = measured[np.abs(np.sin(measured)).argmax()]
    flagged = {(o.leg, o.joint): o for o in metrics.over_rating}
    assert set(flagged) == {(leg, "hip") for leg in legs} | {("rm", "knee")}
    for leg in legs:
        hip = flagged[(leg, "hip")]
        assert (hip.quantity, hip.rated) == ("torque", 9.0)
        assert hip.peak == pytest.approx(hip_peak) and hip.at == f"t = {hip_time:.3f} s"
    knee = flagged[("rm", "knee")]
    assert (knee.peak, knee.rated, knee.at) == (130.0, 120.0, "t = 2.500 s")
    calm = measure_walk(trace, period, cycles, np.array([0.1, 0.0]), 0.4, legs=legs,
                        rated_torques=(60.0, 11.0, 131.0))  # fmt: skip
    assert calm.over_rating == ()


def _slip_by_loops(xy, standing) -> float:
    """Largest move from each stance's first position, stance by stance (the oracle)."""
    worst = 0.0
    for leg in range(standing.shape[1]):
        begin = None
        for k in range(len(standing)):
            if standing[k, leg] and begin is None:
                begin = k
            if not standing[k, leg]:
                begin = None
            if begin is not None:
                worst = max(worst, float(np.linalg.norm(xy[k, leg] - xy[begin, leg])))
    return worst


@pytest.mark.parametrize(
    "cuts", [[], [1], [137, 138, 151], [50, 100, 149, 150, 299, 400], list(range(7, 401, 7))]
)
def test_a_run_measured_in_parts_measures_as_the_whole(cuts):
    period, cycles = 1.0, 4
    trace = _trace(period, cycles, np.array([0.1, 0.0]), lambda t: 0.05 * np.sin(3 * t), 0.4)
    rng = np.random.default_rng(7)
    k = len(trace.time)
    trace.foot_positions[:] = np.cumsum(rng.normal(0.0, 1e-3, (k, 6, 3)), axis=0)
    trace.standing[:] = np.sin(np.arange(k)[:, None] / 17.0 + np.arange(6)) > -0.3
    trace.joint_torques[:] = rng.normal(0.0, 50.0, (k, 6, 3))
    trace.joint_torques[320, 1, 2] = 400.0  # one peak over its rating, at t = 3.2 s
    whole = measure_walk(trace, period, cycles, np.array([0.1, 0.0]), 0.4, legs=LEGS,
                         rated_torques=RATED)  # fmt: skip
    meter = WalkMeter(period, np.array([0.1, 0.0]), 0.4, legs=LEGS, rated_torques=RATED)
    for start, stop in zip([0, *cuts], [*cuts, k], strict=True):
        meter.add(trace.rows(slice(start, stop)))
    parts = meter.metrics(cycles)
    measured = trace.window(period)
    slip = _slip_by_loops(measured.foot_positions[..., :2], measured.standing)
    assert whole.slip == pytest.approx(slip, rel=1e-12) and slip > 0.01
    assert parts.slip == pytest.approx(slip, rel=1e-12)
    assert parts.tracking_rms == pytest.approx(whole.tracking_rms, rel=1e-12)
    for name in ("distance", "max_roll", "max_pitch", "min_height", "fell", "peak_torque"):
        assert getattr(parts, name) == getattr(whole, name), name
    assert parts.over_rating == whole.over_rating
    assert ("lm", "knee", "t = 3.200 s") in {(o.leg, o.joint, o.at) for o in parts.over_rating}


def _least_forces(feet: np.ndarray, weight: float) -> np.ndarray:
    """Vertical forces (n, 3) carrying ``weight`` [N] at the feet's centroid: the least-norm
    forces of that resultant when the centroid is the feet's mean (all equal)."""
    forces = np.zeros_like(feet)
    forces[:, 2] = weight / len(feet)
    return forces


@pytest.mark.parametrize("squeeze", [0.0, 7.5, 40.0])
def test_the_internal_force_is_the_squeeze_the_feet_cancel(squeeze):
    # oracle: three feet carrying a weight equally, plus a pair pushing 'squeeze' [N]
    # toward each other along their line (it sums to zero, force and moment)
    feet = np.array([[0.5, 0.0, 0.0], [-0.25, 0.4, 0.0], [-0.25, -0.4, 0.0]])
    forces = _least_forces(feet, 900.0)
    along = (feet[1] - feet[0]) / np.linalg.norm(feet[1] - feet[0])
    forces[0] += squeeze * along
    forces[1] -= squeeze * along
    everyone = np.zeros((1, 6, 3))
    everyone[0, :3] = forces
    where = np.zeros((1, 6, 3))
    where[0, :3], where[0, 3:] = feet, feet + np.array([0.0, 0.0, 0.3])  # swinging feet: up
    standing = np.array([[True, True, True, False, False, False]])
    found = internal_forces(everyone, where, standing)
    np.testing.assert_allclose(found, [squeeze], atol=1e-9)


def test_no_internal_force_while_the_load_is_handed_over_or_on_one_foot():
    feet = np.array([[[0.5, 0.0, 0.0], [-0.5, 0.0, 0.0]]])
    forces = np.array([[[5.0, 0.0, 100.0], [-5.0, 0.0, 100.0]]])
    assert internal_forces(forces, feet, [[True, True]])[0] == pytest.approx(5.0)
    assert internal_forces(forces, feet, [[True, False]])[0] == 0  # a swinging foot touches
    assert internal_forces(forces[:, :1], feet[:, :1], [[True]])[0] == 0  # alone
