"""A gait period through the design's motors: energy, ratings, max speed, outputs."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pandas as pd
import pytest
from conftest import run_cli

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.actuators import Actuator, Actuators
from hexaleg.battery import Battery
from hexaleg.gait import Gait, analyze_gait
from hexaleg.limits import LEG_JOINTS

IDEAL = dict(torque_constant=0.1, resistance=0.0, gearbox_efficiency=1.0, voltage=1e4, mass=0.0)
"""A lossless, massless actuator's keys (no rotor inertia)."""


def ideal(**changes: float) -> Actuators:
    """Actuators that lose nothing and weigh nothing, with generous ratings."""
    keys = {**IDEAL, **changes}
    return Actuators(
        *(Actuator(50.0, peak_torque=1e4, continuous_torque=1e4, **keys) for _ in LEG_JOINTS)
    )


def test_ideal_motors_draw_exactly_the_positive_mechanical_work():
    design = HexapodDesign(actuators=ideal())
    walked = analyze_gait(design, Gait(), limits=False)
    plain = analyze_gait(HexapodDesign(), Gait(), limits=False)
    assert walked.electrical is not None
    assert np.array_equal(walked.joint_torques, plain.joint_torques)  # massless, no armature
    by_hand = np.maximum(plain.joint_torques * plain.joint_velocities, 0.0).sum()
    by_hand *= Gait().period / Gait().samples
    assert walked.electrical.energy_per_period == pytest.approx(by_hand, rel=1e-12)
    assert walked.electrical.energy_per_period == pytest.approx(
        plain.metrics.positive_work, rel=1e-12
    )
    assert walked.electrical.copper_loss_per_period == 0.0


def test_motor_masses_and_armature_change_the_torques_the_motors_see():
    heavy = dataclasses.replace(ideal().hip, mass=3.0, rotor_inertia=1e-4)
    design = HexapodDesign(actuators=dataclasses.replace(ideal(), hip=heavy))
    walked, plain = (analyze_gait(d, Gait(), limits=False) for d in (design, HexapodDesign()))
    assert walked.mass == pytest.approx(plain.mass + 18.0, rel=1e-12)
    assert walked.mass == pytest.approx(design.total_mass, rel=1e-12)
    assert not np.allclose(walked.joint_torques, plain.joint_torques)


def test_an_rms_over_the_continuous_torque_is_named_and_binds_the_max_speed():
    motors = ideal(resistance=0.2)

    def hip_rms(continuous: float, gait: Gait) -> float:
        hip = dataclasses.replace(motors.hip, continuous_torque=continuous)
        design = HexapodDesign(actuators=dataclasses.replace(motors, hip=hip))
        walked = analyze_gait(design, gait, limits=False)
        return float(np.sqrt((walked.joint_torques[:, :, 1] ** 2).mean(axis=0)).max())

    slow, walking = hip_rms(1e4, Gait(period=1e3)), hip_rms(1e4, Gait())
    assert walking > slow  # the inertial torques add to the hip's RMS
    continuous = 0.5 * (slow + walking)
    hip = dataclasses.replace(motors.hip, continuous_torque=continuous)
    design = HexapodDesign(actuators=dataclasses.replace(motors, hip=hip))
    walked = analyze_gait(design, Gait(), limits=False, speed=True)
    assert walked.electrical is not None
    assert walked.electrical.per_joint["hip"].rms_torque == pytest.approx(walking, rel=1e-12)
    over = [o for o in walked.over_rating if o.quantity == "continuous_torque"]
    assert over and all(o.joint == "hip" for o in over)
    assert walked.walkable and not walked.feasible
    limit = walked.max_speed
    assert limit is not None and 0 < limit.value < Gait().speed
    assert limit.limited_by.kind == "continuous_torque" and limit.limited_by.joint == "hip"
    at_limit = analyze_gait(design, Gait().with_speed(limit.value), limits=False)
    assert at_limit.electrical is not None
    assert at_limit.electrical.per_joint["hip"].rms_torque == pytest.approx(continuous, rel=1e-4)


def test_a_supply_too_low_binds_the_max_speed_on_voltage():
    design = HexapodDesign(actuators=ideal(voltage=12.0, resistance=0.05))
    walked = analyze_gait(design, Gait(), limits=False, speed=True)
    limit = walked.max_speed
    assert limit is not None and limit.limited_by.kind == "voltage"
    at_limit = analyze_gait(design, Gait().with_speed(limit.value), limits=False)
    assert at_limit.electrical is not None
    assert at_limit.electrical.voltage.max() == pytest.approx(12.0, rel=1e-4)


def test_gait_json_text_csv_and_plots_show_the_motors(tmp_path, capsys):
    from hexaleg.design_text import design_toml

    design = HexapodDesign(
        actuators=ideal(resistance=0.3, gearbox_efficiency=0.9, mass=1.0),
        battery=Battery(500.0, 200.0, regeneration=0.5),
    )
    (tmp_path / "robot.toml").write_text(design_toml(design))
    argv = ["gait", "--design", str(tmp_path / "robot.toml")]
    assert run_cli([*argv, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["mass"] == pytest.approx(design.total_mass, rel=1e-12)
    electrical, battery = data["electrical"], data["battery"]
    for key in ("energy_per_period", "copper_loss_per_period", "average_power",
                "cost_of_transport", "energy_per_km"):  # fmt: skip
        assert electrical[key] > 0
    for joint in LEG_JOINTS:
        assert set(electrical["per_joint"][joint]) == {
            "rms_torque", "peak_current", "peak_voltage", "energy_per_period"
        }  # fmt: skip
    assert battery["mass"] == pytest.approx(2.5)
    usable = 500.0 * (1 - 0.2)  # the default reserve keeps a fifth
    assert battery["runtime"] == pytest.approx(usable / electrical["average_power"], rel=1e-12)
    assert battery["range"] == pytest.approx(battery["runtime"] * data["gait"]["speed"] * 3.6)
    assert "mechanical_cost_of_transport" in data and "cost_of_transport" not in data
    csv, plots = tmp_path / "period.csv", tmp_path / "plots"
    assert run_cli([*argv, "--csv", str(csv), "--plot", str(plots)]) == 0
    text = capsys.readouterr().out
    for words in ("electrical energy per period", "energy per km", "battery", "copper loss"):
        assert words in text
    table = pd.read_csv(csv)
    for column in ("lf_hip_current", "lf_hip_voltage", "lf_hip_power"):
        assert column in table
    assert (plots / "gait_power.png").is_file() and (plots / "gait_envelope.png").is_file()


def test_a_design_without_actuators_has_no_electrical_figures(capsys):
    assert run_cli(["gait", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["electrical"] is None and data["battery"] is None


def test_with_design_keeps_the_motors_when_the_lengths_change():
    design = HexapodDesign(actuators=ideal(mass=1.0, rotor_inertia=1e-4))
    other = design.with_ratios(0.15, 0.45)
    fast = HexapodModel(design).with_design(other)
    slow = HexapodModel(other)
    assert np.array_equal(fast.model.armature, slow.model.armature)
    for mine, theirs in zip(fast.model.inertias, slow.model.inertias, strict=True):
        assert np.allclose(mine.toDynamicParameters(), theirs.toDynamicParameters(), atol=1e-12)
