"""The motor equations: hand-worked samples, the mechanical work as oracle, and properties."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from hexaleg import Gait, HexapodDesign, analyze_gait
from hexaleg.actuators import Actuator, Actuators
from hexaleg.battery import Battery
from hexaleg.electrical import analyze_electrical, binding_rating, motor_samples
from hexaleg.exceptions import ParameterError

MOTOR = {
    "gear_ratio": 100.0,
    "torque_constant": 0.05,
    "resistance": 0.5,
    "gearbox_efficiency": 0.8,
    "peak_torque": 30.0,
    "continuous_torque": 10.0,
    "mass": 1.0,
    "voltage": 48.0,
}
"""The actuator of the hand-worked samples: N = 100, k_t = 0.05 N·m/A, R = 0.5 Ω, η = 0.8."""


def same(**changes) -> Actuators:
    actuator = Actuator(**{**MOTOR, **changes})
    return Actuators(actuator, actuator, actuator)


def hip_sample(tau: float, omega: float) -> tuple[np.ndarray, np.ndarray]:
    """One leg at one instant: the hip at τ, ω; root and knee at rest."""
    torques, speeds = np.zeros((1, 1, 3)), np.zeros((1, 1, 3))
    torques[0, 0, 1], speeds[0, 0, 1] = tau, omega
    return torques, speeds


# -- one joint, one instant, worked by hand -----------------------------------------------


def test_motoring_by_hand():
    motors = motor_samples(*hip_sample(20.0, 0.5), same())
    # ω_m = N·ω = 100·0.5 = 50 rad/s; τ·ω = 10 ≥ 0: τ_m = τ/(N·η) = 20/80 = 0.25 N·m
    # i = τ_m/k_t = 0.25/0.05 = 5 A; P_cu = i²R = 25·0.5 = 12.5 W
    # P_e = τ_m·ω_m + P_cu = 12.5 + 12.5 = 25 W ≥ 0: P_b = 25 W
    # voltage = |k_t·ω_m| + |i|·R = 0.05·50 + 5·0.5 = 2.5 + 2.5 = 5 V
    hip = (0, 0, 1)
    assert motors.motor_speed[hip] == pytest.approx(50.0, rel=1e-15)
    assert motors.motor_torque[hip] == pytest.approx(0.25, rel=1e-15)
    assert motors.current[hip] == pytest.approx(5.0, rel=1e-15)
    assert motors.copper_loss[hip] == pytest.approx(12.5, rel=1e-15)
    assert motors.electrical_power[hip] == pytest.approx(25.0, rel=1e-15)
    assert motors.battery_power[hip] == pytest.approx(25.0, rel=1e-15)
    assert motors.voltage[hip] == pytest.approx(5.0, rel=1e-15)


def test_motoring_backwards_by_hand():
    motors = motor_samples(*hip_sample(-20.0, -0.5), same())
    # τ·ω = +10 ≥ 0, motoring: τ_m = −20/80 = −0.25 N·m, ω_m = −50 rad/s, i = −5 A
    # P_e = (−0.25)(−50) + 25·0.5 = 12.5 + 12.5 = 25 W; voltage 2.5 + 2.5 = 5 V
    assert motors.current[0, 0, 1] == pytest.approx(-5.0, rel=1e-15)
    assert motors.electrical_power[0, 0, 1] == pytest.approx(25.0, rel=1e-15)
    assert motors.voltage[0, 0, 1] == pytest.approx(5.0, rel=1e-15)


@pytest.mark.parametrize(("regeneration", "battery_power"), [(0.0, 0.0), (0.5, -1.44)])
def test_braking_by_hand(regeneration, battery_power):
    motors = motor_samples(*hip_sample(20.0, -0.5), same(), regeneration)
    # ω_m = −50 rad/s; τ·ω = −10 < 0, braking: τ_m = τ·η/N = 20·0.8/100 = 0.16 N·m
    # i = 0.16/0.05 = 3.2 A; P_cu = 3.2²·0.5 = 10.24·0.5 = 5.12 W
    # P_e = 0.16·(−50) + 5.12 = −8 + 5.12 = −2.88 W < 0: P_b = r·P_e: 0 (r = 0), −1.44 W (r = ½)
    # voltage = |0.05·(−50)| + 3.2·0.5 = 2.5 + 1.6 = 4.1 V
    hip = (0, 0, 1)
    assert motors.motor_torque[hip] == pytest.approx(0.16, rel=1e-15)
    assert motors.current[hip] == pytest.approx(3.2, rel=1e-15)
    assert motors.copper_loss[hip] == pytest.approx(5.12, rel=1e-14)
    assert motors.electrical_power[hip] == pytest.approx(-2.88, rel=1e-14)
    assert motors.battery_power[hip] == pytest.approx(battery_power, rel=1e-14, abs=0.0)
    assert motors.voltage[hip] == pytest.approx(4.1, rel=1e-15)


def test_braking_slowly_still_draws_power():
    motors = motor_samples(*hip_sample(20.0, -0.05), same(), regeneration=0.5)
    # braking: τ_m = 0.16 N·m, i = 3.2 A, P_cu = 5.12 W; ω_m = −5 rad/s
    # P_e = 0.16·(−5) + 5.12 = −0.8 + 5.12 = 4.32 W ≥ 0: P_b = 4.32 W whatever r
    assert motors.battery_power[0, 0, 1] == pytest.approx(4.32, rel=1e-14)


def test_the_voltage_check_by_hand():
    # V = 4.5 V: motoring at 20 N·m, 0.5 rad/s needs 5 V (above), braking at 20 N·m,
    # −0.5 rad/s needs 4.1 V (within); one leg, samples t = 0 and t = 1 s (T = 2 s)
    torques = np.array([[[0.0, 20.0, 0.0]], [[0.0, 20.0, 0.0]]])
    speeds = np.array([[[0.0, 0.5, 0.0]], [[0.0, -0.5, 0.0]]])
    result = analyze_electrical(
        torques, speeds, 2.0, 0.1, 10.0, 9.81, same(voltage=4.5, continuous_torque=25.0),
        legs=["lf"],
    )  # fmt: skip
    assert [(o.leg, o.joint, o.quantity) for o in result.over_rating] == [("lf", "hip", "voltage")]
    record = result.over_rating[0]
    assert record.peak == pytest.approx(5.0, rel=1e-15) and record.rated == 4.5
    assert record.at == "t = 0.000 s"
    assert str(record) == "lf hip voltage needed 5.00 V over its rating 4.5 V (t = 0.000 s)"


# -- one period, worked by hand -----------------------------------------------------------

TWO_SAMPLES = (
    np.array([[[0.0, 20.0, 0.0]], [[0.0, 20.0, 0.0]]]),  # τ [N·m]: the hip holds 20 N·m
    np.array([[[0.0, 0.5, 0.0]], [[0.0, -0.5, 0.0]]]),  # ω [rad/s]: motoring, then braking
)
BATTERY = Battery(capacity=100.0, specific_energy=200.0, regeneration=0.5, electronics_power=3.0)


@pytest.fixture
def period():
    return analyze_electrical(*TWO_SAMPLES, 2.0, 0.1, 10.0, 9.81, same(), BATTERY, ["lf"])


def test_a_period_by_hand(period):
    # samples 1 s apart (T = 2 s, N_s = 2); P_b = 25 W then r·P_e = 0.5·(−2.88) = −1.44 W
    # E = (25 − 1.44)·1 + P₀·T = 23.56 + 3·2 = 29.56 J; average 29.56/2 = 14.78 W
    assert period.energy_per_period == pytest.approx(29.56, rel=1e-14)
    assert period.average_power == pytest.approx(14.78, rel=1e-14)
    # copper: (12.5 + 5.12)·1 = 17.62 J; shafts: (0.25·50 + 0.16·(−50))/2 = (12.5 − 8)/2 W
    assert period.copper_loss_per_period == pytest.approx(17.62, rel=1e-14)
    assert period.copper_power == pytest.approx(8.81, rel=1e-14)
    assert period.mechanical_power == pytest.approx(2.25, rel=1e-14)
    assert period.electronics_power == 3.0
    # CoT = E/(M·g·v·T) = 29.56/(10·9.81·0.1·2) = 29.56/19.62 = 1.506626 (to 7 digits)
    assert period.cost_of_transport == pytest.approx(1.506626, rel=1e-6)
    # E/(v·T) = 29.56/0.2 = 147.8 J/m = 147.8·1000/3600 Wh/km = 41.05556 Wh/km
    assert period.energy_per_km == pytest.approx(41.05556, rel=1e-6)
    # battery: 100 Wh / 200 Wh/kg = 0.5 kg; the default reserve keeps 20 %: runtime
    # 80 Wh / 14.78 W = 5.412720 h; range 5.412720 h · 0.1 m/s · 3.6 = 1.948579 km
    battery = period.battery
    assert (battery.mass, battery.capacity, battery.reserve) == (0.5, 100.0, 0.2)
    assert battery.runtime == pytest.approx(5.412720, rel=1e-6)
    assert battery.range == pytest.approx(1.948579, rel=1e-6)


def test_no_reserve_uses_the_whole_capacity():
    # reserve 0: runtime 100 Wh / 14.78 W = 6.765900 h; range 6.765900 · 0.36 = 2.435724 km
    whole = dataclasses.replace(BATTERY, reserve=0.0)
    found = analyze_electrical(*TWO_SAMPLES, 2.0, 0.1, 10.0, 9.81, same(), whole, ["lf"])
    assert found.battery.runtime == pytest.approx(6.765900, rel=1e-6)
    assert found.battery.range == pytest.approx(2.435724, rel=1e-6)


def test_a_period_per_joint_by_hand(period):
    hip = period.per_joint["hip"]
    assert hip.rms_torque == pytest.approx(20.0, rel=1e-15)  # √((20² + 20²)/2)
    assert hip.peak_current == pytest.approx(5.0, rel=1e-15)
    assert hip.peak_voltage == pytest.approx(5.0, rel=1e-15)
    assert hip.energy_per_period == pytest.approx(23.56, rel=1e-14)  # without P₀·T
    for joint in ("root", "knee"):
        assert vars(period.per_joint[joint]) == dict.fromkeys(vars(hip), 0.0)


def test_a_period_over_its_continuous_rating_and_what_binds(period):
    # the hip's RMS 20 N·m is twice its continuous 10 N·m; its peak 20 of 30 N·m, 5 of 48 V,
    # 0.5 of V/(k_t·N) = 48/5 = 9.6 rad/s
    (record,) = period.over_rating
    assert (record.leg, record.joint, record.quantity) == ("lf", "hip", "continuous_torque")
    assert (record.peak, record.rated, record.at) == (20.0, 10.0, "RMS over the period")
    binding = period.binding
    assert str(binding) == "hip continuous torque" and binding.leg == "lf"
    assert binding.ratio == pytest.approx(2.0, rel=1e-15)
    assert binding_rating(*TWO_SAMPLES, same(), ["lf"]) == binding
    within = binding_rating(*TWO_SAMPLES, same(continuous_torque=25.0), ["lf"])
    assert str(within) == "hip continuous torque" and within.ratio == pytest.approx(20 / 25)
    tied = binding_rating(*TWO_SAMPLES, same(peak_torque=25.0, continuous_torque=25.0), ["lf"])
    assert str(tied) == "hip peak torque"  # peak and RMS both 20 of 25: the first listed


def test_every_rating_exceeded_is_named_in_order():
    actuators = same(peak_torque=15.0, voltage=4.5, max_speed=0.4)
    result = analyze_electrical(*TWO_SAMPLES, 2.0, 0.1, 10.0, 9.81, actuators, legs=["lf"])
    quantities = [o.quantity for o in result.over_rating]
    assert quantities == ["peak_torque", "continuous_torque", "voltage", "speed"]
    assert [o.peak for o in result.over_rating] == pytest.approx([20.0, 20.0, 5.0, 0.5])
    assert [o.rated for o in result.over_rating] == [15.0, 10.0, 4.5, 0.4]


def test_the_json_form(period):
    out = json.loads(json.dumps(period.to_dict(), allow_nan=False))
    assert set(out) == {"electrical", "battery"}
    assert set(out["electrical"]) == {
        "supply",
        "winding_temperature",
        "energy_per_period",
        "copper_loss_per_period",
        "mechanical_power",
        "copper_power",
        "average_power",
        "cost_of_transport",
        "energy_per_km",
        "per_joint",
    }
    assert set(out["electrical"]["per_joint"]) == {"root", "hip", "knee"}
    assert set(out["electrical"]["per_joint"]["hip"]) == {
        "rms_torque",
        "peak_current",
        "peak_voltage",
        "energy_per_period",
    }
    assert set(out["battery"]) == {"mass", "capacity", "reserve", "runtime", "range"}
    assert out["electrical"]["supply"] == 48.0 and out["electrical"]["winding_temperature"] == 25


def test_without_a_battery_and_with_nothing_drawn():
    result = analyze_electrical(*TWO_SAMPLES, 2.0, 0.1, 10.0, 9.81, same(), legs=["lf"])
    assert result.battery is None and result.to_dict()["battery"] is None
    # r = 0, P₀ = 0: E = 25·1 J
    assert result.energy_per_period == pytest.approx(25.0, rel=1e-15)
    resting = analyze_electrical(*(np.zeros((4, 6, 3)),) * 2, 1.0, 0.1, 10.0, 9.81, same(),
                                 Battery(capacity=10.0, specific_energy=100.0))  # fmt: skip
    assert resting.energy_per_period == 0.0
    assert resting.to_dict()["battery"]["runtime"] is None  # never runs down


def test_the_time_series_columns(period):
    columns = period.time_series()
    assert len(columns) == 1 * 3 * 3
    np.testing.assert_allclose(columns["lf_hip_current"], [5.0, 3.2], rtol=1e-15)
    np.testing.assert_allclose(columns["lf_hip_voltage"], [5.0, 4.1], rtol=1e-15)
    np.testing.assert_allclose(columns["lf_hip_power"], [25.0, -2.88], rtol=1e-14)
    np.testing.assert_allclose(period.times, [0.0, 1.0])


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"torques": np.zeros((2, 1, 2))}, "torques"),
        ({"speeds": np.zeros((3, 1, 3))}, "speeds"),
        ({"speeds": np.full((2, 1, 3), np.nan)}, "speeds"),
        ({"period": 0.0}, "period"),
        ({"speed": -0.1}, "speed"),
        ({"mass": float("inf")}, "mass"),
        ({"gravity": 0}, "gravity"),
        ({"legs": ["lf", "rf"]}, "legs"),
        ({"actuators": MOTOR}, "actuators"),
        ({"battery": {"capacity": 1.0}}, "battery"),
    ],
)
def test_bad_inputs_are_refused_naming_them(changes, field):
    arguments = {
        "torques": TWO_SAMPLES[0],
        "speeds": TWO_SAMPLES[1],
        "period": 2.0,
        "speed": 0.1,
        "mass": 10.0,
        "gravity": 9.81,
        "actuators": same(),
        "battery": None,
        "legs": ["lf"],
    }
    with pytest.raises(ParameterError) as info:
        analyze_electrical(**{**arguments, **changes})
    assert info.value.field == field and "\n" not in str(info.value)


# -- the mechanical work as oracle --------------------------------------------------------


@pytest.fixture(scope="module")
def walked():
    return analyze_gait(HexapodDesign(), Gait(), limits=False)


IDEAL = Actuator(
    gear_ratio=50.0,
    torque_constant=0.1,
    resistance=0.0,
    gearbox_efficiency=1.0,
    peak_torque=1e3,
    continuous_torque=1e3,
    mass=0.0,
    voltage=1e3,
    rotor_inertia=0.0,
)
"""A lossless, massless actuator: η = 1, R = 0, no rotor inertia."""


def test_ideal_motors_without_regeneration_take_the_positive_mechanical_work(walked):
    result = analyze_electrical(
        walked.joint_torques,
        walked.joint_velocities,
        walked.gait.period,
        walked.gait.speed,
        walked.mass,
        9.81,
        Actuators(IDEAL, IDEAL, IDEAL),
        legs=walked.legs,
    )
    assert walked.metrics.positive_work > 10.0  # a real period, not a trivial zero
    assert result.energy_per_period == pytest.approx(walked.metrics.positive_work, rel=1e-12)
    assert result.cost_of_transport == pytest.approx(walked.metrics.cost_of_transport, rel=1e-12)
    assert result.copper_loss_per_period == 0.0
    for j, joint in enumerate(("root", "hip", "knee")):
        rms = np.sqrt((walked.joint_torques[..., j] ** 2).mean(axis=0)).max()
        assert result.per_joint[joint].rms_torque == pytest.approx(rms, rel=1e-15)


# -- properties ---------------------------------------------------------------------------

# Subnormal numbers (below 2.2e-308) carry fewer digits than any tolerance here assumes:
# no torque or speed a motor sees is one.
SAMPLES = arrays(float, (8, 2, 3), elements=st.floats(-200.0, 200.0, allow_subnormal=False))
SPEEDS = arrays(float, (8, 2, 3), elements=st.floats(-5.0, 5.0, allow_subnormal=False))
RESISTANCE = st.floats(0.0, 20.0)
RATIO = st.floats(0.0, 1.0)


def energy(torques, speeds, regeneration=0.0, **motor) -> float:
    battery = Battery(capacity=100.0, specific_energy=100.0, regeneration=regeneration)
    return analyze_electrical(
        torques, speeds, 1.5, 0.2, 30.0, 9.81, same(**motor), battery, ["a", "b"]
    ).energy_per_period


@settings(max_examples=60, deadline=None)
@given(SAMPLES, SPEEDS, RESISTANCE, RESISTANCE, RATIO, st.floats(0.01, 1.0))
def test_energy_never_falls_as_the_resistance_grows(tau, omega, r1, r2, regen, eta):
    low, high = sorted((r1, r2))
    first = energy(tau, omega, regen, resistance=low, gearbox_efficiency=eta)
    assert first <= energy(tau, omega, regen, resistance=high, gearbox_efficiency=eta)


@settings(max_examples=60, deadline=None)
@given(SAMPLES, SPEEDS, RATIO, RATIO, RESISTANCE, st.floats(0.01, 1.0))
def test_regeneration_never_increases_the_energy(tau, omega, r1, r2, resistance, eta):
    low, high = sorted((r1, r2))
    taken = energy(tau, omega, high, resistance=resistance, gearbox_efficiency=eta)
    assert taken <= energy(tau, omega, low, resistance=resistance, gearbox_efficiency=eta)


@settings(max_examples=60, deadline=None)
@given(SAMPLES, SPEEDS, st.floats(1.0, 500.0))
def test_lossless_motors_with_full_regeneration_take_the_net_mechanical_work(tau, omega, ratio):
    net = float((tau * omega).sum() * 1.5 / len(tau))  # Σ τ·ω·T/N_s
    scale = float(np.abs(tau * omega).sum() * 1.5 / len(tau))
    got = energy(tau, omega, 1.0, resistance=0.0, gearbox_efficiency=1.0, gear_ratio=ratio)
    assert got == pytest.approx(net, rel=1e-12, abs=1e-12 * scale)
