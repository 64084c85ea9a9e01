"""Margins and one bus: the safety factor, the battery's reserve, the bus voltage, hot windings.

- A safety factor F is the same as ratings divided by F: every result of a design with F
  equals that of the same design whose peak torque and speed ratings are divided by F.
- The bus voltage flag and the winding temperature against the motor equations worked in
  the test from the gait's own torques and speeds: ω_m = N·ω, τ_m = τ/(N·η) motoring or
  τ·η/N braking, i = τ_m/k_t, voltage |k_t·ω_m| + |i|·R, R·(1 + 0.00393·(T − 25)).
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from conftest import run_cli

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.actuators import Actuator, Actuators
from hexaleg.battery import Battery
from hexaleg.exceptions import ParameterError
from hexaleg.gait import Gait, analyze_gait
from hexaleg.gait.capacity import walking_payload_capacity
from hexaleg.limits import LEG_JOINTS
from hexaleg.statics import analyze_loads
from hexaleg.statics.ground import Ground

F = 1.4
"""The safety factor of the tests."""

GAIT = Gait(samples=60)

DESIGN = HexapodDesign(l1=0.15, l2=0.35, l3=0.45, nominal_angles=(0.0, -0.25, -1.7))


def derated(design: HexapodDesign, factor: float) -> HexapodDesign:
    """The oracle: the same design with every peak torque and speed rating divided by F."""
    if design.actuators is None:
        torques = tuple(r / factor for r in design.rated_torques)
        speeds = tuple(r / factor for r in design.rated_speeds)
        return design.replace(rated_torques=torques, rated_speeds=speeds)
    lowered = {
        joint: dataclasses.replace(
            actuator,
            peak_torque=actuator.peak_torque / factor,
            max_speed=actuator.rated_speed / factor,
        )
        for joint, actuator in zip(LEG_JOINTS, design.actuators.joints, strict=True)
    }
    return design.replace(actuators=dataclasses.replace(design.actuators, **lowered))


def _flags(flags) -> set[tuple[str, str, str, str, float]]:
    return {(o.leg, o.joint, o.quantity, o.at, round(o.rated, 9)) for o in flags}


@pytest.mark.slow  # two flexibility searches, 2 s
def test_the_safety_factor_standing_is_the_derated_design():
    mine = analyze_loads(DESIGN, safety_factor=F)
    oracle = analyze_loads(derated(DESIGN, F))
    assert mine.capacity == oracle.capacity and mine.capacity.mass > 0
    assert _flags(mine.over_rating) == _flags(oracle.over_rating)
    assert mine.to_dict()["safety_factor"] == F
    plain = analyze_loads(DESIGN)
    assert mine.capacity.mass < plain.capacity.mass


def test_the_safety_factor_walking_is_the_derated_design():
    model, oracle_model = HexapodModel(DESIGN), HexapodModel(derated(DESIGN, F))
    mine = walking_payload_capacity(model, GAIT, safety_factor=F)
    assert mine == walking_payload_capacity(oracle_model, GAIT)
    walked = analyze_gait(DESIGN, GAIT, model=model, safety_factor=F)
    other = analyze_gait(oracle_model.design, GAIT, model=oracle_model)
    assert walked.max_speed == other.max_speed and walked.max_stride == other.max_stride
    assert walked.feasible == other.feasible
    assert _flags(walked.over_rating) == _flags(other.over_rating)


MOTOR = Actuator(
    gear_ratio=100.0, torque_constant=0.08, resistance=0.6, gearbox_efficiency=0.85,
    peak_torque=250.0, continuous_torque=120.0, mass=1.0, voltage=48.0, max_speed=6.0,
)  # fmt: skip
"""A hand-made geared motor generous enough for the default gait."""


def test_the_safety_factor_with_actuators_is_the_derated_design():
    design = DESIGN.replace(actuators=Actuators(MOTOR, MOTOR, MOTOR))
    model, oracle_model = HexapodModel(design), HexapodModel(derated(design, F))
    assert walking_payload_capacity(model, GAIT, safety_factor=F) == walking_payload_capacity(
        oracle_model, GAIT
    )
    walked = analyze_gait(design, GAIT, model=model, limits=False, speed=True, safety_factor=F)
    other = analyze_gait(oracle_model.design, GAIT, model=oracle_model, limits=False, speed=True)
    assert walked.max_speed == other.max_speed
    np.testing.assert_array_equal(
        walked.electrical.ratings.ratings, other.electrical.ratings.ratings
    )


def needed_voltages(walked, motor: Actuator, temperature: float = 25.0) -> np.ndarray:
    """The voltage each joint's motor needs at each sample (N, 6, 3) [V], by hand."""
    tau, omega = walked.joint_torques, walked.joint_velocities
    n, eta, kt = motor.gear_ratio, motor.gearbox_efficiency, motor.torque_constant
    resistance = motor.resistance * (1 + 0.00393 * (temperature - 25.0))
    motor_speed = n * omega
    motor_torque = np.where(tau * omega >= 0, tau / (n * eta), tau * eta / n)
    return np.abs(kt * motor_speed) + np.abs(motor_torque / kt) * resistance


@pytest.mark.parametrize("temperature", [25.0, 110.0])
def test_the_bus_voltage_flag_by_hand(temperature):
    motors = Actuators(MOTOR, MOTOR, MOTOR, winding_temperature=temperature)
    design = DESIGN.replace(actuators=motors)
    walked = analyze_gait(design, GAIT, limits=False)
    peaks = needed_voltages(walked, MOTOR, temperature).max(axis=0)  # (6, 3)
    np.testing.assert_allclose(walked.electrical.ratings.values[2], peaks, rtol=1e-12)
    assert not any(o.quantity == "voltage" for o in walked.over_rating)  # within 48 V
    bus = float(np.quantile(peaks, 0.6))  # some joints need more than the bus gives
    battery = Battery(capacity=300.0, specific_energy=150.0, voltage=bus)
    on_bus = analyze_gait(design.replace(battery=battery), GAIT, limits=False)
    by_hand = needed_voltages(on_bus, MOTOR, temperature).max(axis=0)
    expected = {
        (leg, joint): by_hand[i, j]
        for i, leg in enumerate(on_bus.legs)
        for j, joint in enumerate(LEG_JOINTS)
        if by_hand[i, j] > bus
    }
    flagged = {(o.leg, o.joint): o for o in on_bus.over_rating if o.quantity == "voltage"}
    assert set(flagged) == set(expected) and expected
    for key, flag in flagged.items():
        assert flag.peak == pytest.approx(expected[key], rel=1e-12) and flag.rated == bus
    assert not on_bus.feasible and "voltage needed" in on_bus.infeasible_because
    assert on_bus.electrical.supply == bus
    assert on_bus.to_dict()["electrical"]["winding_temperature"] == temperature


def test_hot_windings_need_more_voltage_and_lose_more_in_copper():
    cold, hot = (
        analyze_gait(DESIGN.replace(actuators=Actuators(MOTOR, MOTOR, MOTOR, t)), GAIT,
                     limits=False).electrical
        for t in (25.0, 125.0)
    )  # fmt: skip
    scale = 1 + 0.00393 * 100.0
    assert hot.copper_loss_per_period == pytest.approx(cold.copper_loss_per_period * scale)
    hotter, colder = hot.ratings.values[2], cold.ratings.values[2]
    assert (hotter >= colder).all() and (hotter > colder).any()


def test_motors_of_different_voltages_need_a_bus_voltage():
    other = dataclasses.replace(MOTOR, voltage=24.0)
    with pytest.raises(ParameterError, match=r"battery\.voltage.*root 48 V, hip 24 V, knee 48 V"):
        DESIGN.replace(actuators=Actuators(MOTOR, other, MOTOR))
    battery = Battery(capacity=300.0, specific_energy=150.0, voltage=36.0)
    design = DESIGN.replace(actuators=Actuators(MOTOR, other, MOTOR), battery=battery)
    assert design.bus_voltage == 36.0
    assert DESIGN.replace(actuators=Actuators(MOTOR, MOTOR, MOTOR)).bus_voltage == 48.0
    assert DESIGN.bus_voltage is None


@pytest.mark.parametrize(
    ("table", "fragment"),
    [
        ("reserve = 1", "battery.reserve = 1 is not valid: must be a number in [0, 0.99]"),
        ("reserve = -0.1", "battery.reserve = -0.1 is not valid: must be a number in [0, 0.99]"),
        ("voltage = -48", "battery.voltage"),
    ],
)
def test_bad_battery_keys_are_one_line_and_exit_2(tmp_path, capsys, table, fragment):
    path = tmp_path / "robot.toml"
    path.write_text(f"[battery]\ncapacity = 100\nspecific_energy = 150\n{table}\n")
    assert run_cli(["loads", "--design", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err and fragment in err


def test_loads_prints_the_safety_factor_and_flags_against_rating_over_f(capsys):
    argv = ["loads", "--payload", "30", "--motor-safety-factor", "2.5"]
    assert run_cli([*argv, "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["safety_factor"] == 2.5
    assert all(flag["rated"] * 2.5 in (60.0, 150.0, 120.0) for flag in printed["over_rating"])
    assert printed["over_rating"]  # 150 N·m / 2.5 = 60 N·m at the hips holds no 30 kg
    assert run_cli(argv) == 0
    assert "(rated 150 / 2.5 = 60 N·m)" in capsys.readouterr().out


def test_the_bus_temperature_and_reserve_read_back_from_toml_and_json(tmp_path):
    from hexaleg.design_file import load_design
    from hexaleg.design_text import design_toml

    battery = Battery(capacity=300.0, specific_energy=150.0, voltage=36.0, reserve=0.1)
    motors = Actuators(MOTOR, dataclasses.replace(MOTOR, voltage=24.0), MOTOR, 70.0)
    design = DESIGN.replace(actuators=motors, battery=battery)
    (tmp_path / "robot.toml").write_text(design_toml(design))
    (tmp_path / "robot.json").write_text(json.dumps({"design": design.as_dict()}))
    for name in ("robot.toml", "robot.json"):
        again = load_design(tmp_path / name)
        assert again == design and again.bus_voltage == 36.0
        assert again.actuators.winding_temperature == 70.0 and again.battery.reserve == 0.1


def _walks(seed: int):
    rng = np.random.default_rng(seed)
    for _ in range(12):
        angles = (0.0, rng.uniform(-0.4, 0.2), rng.uniform(-2.0, -1.2))
        design = HexapodDesign.from_ratios(
            rng.uniform(0.05, 0.3), rng.uniform(0.3, 0.6), nominal_angles=angles
        )
        gait = Gait(pattern=str(rng.choice(["tripod", "tetrapod", "wave"])), samples=60,
                    period=rng.uniform(1.2, 3.0), stride=rng.uniform(0.1, 0.3))  # fmt: skip
        ground = Ground(np.radians(rng.uniform(-12, 12)), rng.uniform(-3, 3))
        yield design, gait, ground, rng.uniform(1.0, 1.3)


@pytest.mark.parametrize(("design", "gait", "ground", "factor"), list(_walks(5)))
def test_feasible_means_within_every_rating_so_the_max_speed_reaches_the_speed(
    design, gait, ground, factor
):
    """Never "feasible yes" beside a joint over its rating or a max speed below the speed
    walked: a walkable period is feasible exactly when its max speed (at its own stride)
    reaches the speed it walks, and then no joint is over any rating."""
    walked = analyze_gait(design, gait, ground=ground, limits=False, speed=True,
                          safety_factor=factor)  # fmt: skip
    if not walked.walkable:  # a joint limit or a foot's reach breaks: named first
        assert not walked.feasible and walked.infeasible_because == str(walked.violations[0])
        return
    reaches = walked.max_speed.value >= gait.speed * (1 - 1e-9)
    assert walked.feasible == reaches
    assert walked.feasible == (not walked.over_rating and not walked.slips and not walked.tipping)


def test_the_default_wave_gait_over_its_speed_rating_is_not_feasible():
    walked = analyze_gait(HexapodDesign(), Gait(pattern="wave"), limits=False, speed=True)
    assert walked.over_rating and not walked.feasible
    assert walked.max_speed.value < walked.gait.speed
    assert walked.infeasible_because.startswith("over its ratings: ")
