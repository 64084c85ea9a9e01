"""The motors in studies, decisions and the report: metrics, requirements, a section."""

from __future__ import annotations

import math

import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.actuators import Actuator, Actuators
from hexaleg.battery import Battery
from hexaleg.evaluation.evaluate import evaluate
from hexaleg.evaluation.metrics import METRICS, objectives
from hexaleg.evaluation.requirements import Requirements, check
from hexaleg.gait import analyze_gait
from hexaleg.gait.analysis import STUDY_GAIT

KEYS = dict(torque_constant=0.12, resistance=0.3, gearbox_efficiency=0.85, voltage=48.0)


def motors(hip_continuous: float = 150.0) -> Actuators:
    """Three actuators written out, strong enough for the default gait."""
    return Actuators(
        Actuator(60.0, peak_torque=80.0, continuous_torque=50.0, mass=0.8, **KEYS),
        Actuator(100.0, peak_torque=250.0, continuous_torque=hip_continuous, mass=2.0, **KEYS),
        Actuator(80.0, peak_torque=150.0, continuous_torque=90.0, mass=1.2, **KEYS),
    )


DESIGN = HexapodDesign(actuators=motors(), battery=Battery(600.0, 180.0, regeneration=0.2))


ELECTRICAL = tuple(spec for spec in METRICS if spec.analysis == "motors")


def test_the_electrical_metrics_are_the_gait_periods():
    found = evaluate(DESIGN, (*ELECTRICAL, METRICS.robot_mass)).metrics
    walked = analyze_gait(DESIGN, STUDY_GAIT, limits=False)
    electrical = walked.electrical
    assert electrical is not None and electrical.battery is not None
    assert found.energy_per_km == pytest.approx(electrical.energy_per_km, rel=1e-12)
    assert found.battery_range == pytest.approx(electrical.battery.range, rel=1e-12)
    rms = (walked.joint_torques**2).mean(axis=0) ** 0.5  # (legs, 3)
    continuous = [a.continuous_torque for a in DESIGN.actuators.joints]
    assert found.continuous_load == pytest.approx((rms / continuous).max(), rel=1e-12)
    assert found.robot_mass == pytest.approx(HexapodDesign().total_mass + 24.0 + 600 / 180)


def test_a_design_without_motors_says_why_it_has_no_electrical_metrics():
    found = evaluate(HexapodDesign(), ELECTRICAL)
    for spec in ELECTRICAL:
        assert math.isnan(found.metrics.value(spec)) and "actuators" in str(found.unmeasured[spec])
    no_battery = evaluate(HexapodDesign(actuators=motors()), (METRICS.battery_range,))
    assert "battery" in str(no_battery.unmeasured.battery_range)


def test_range_and_continuous_margin_requirements_are_checked():
    found = evaluate(DESIGN, (METRICS.battery_range, METRICS.continuous_load))
    load = found.metrics.value(METRICS.continuous_load)
    distance = found.metrics.value(METRICS.battery_range)
    meets = Requirements.from_table({"range_km": distance * 0.9, "continuous_margin": 1.0})
    fails = Requirements.from_table({"range_km": distance * 1.1, "continuous_margin": load * 0.9})
    assert all(c.met for c in check(meets, found.metrics, found.causes))
    assert not any(c.met for c in check(fails, found.metrics, found.causes))


def test_decide_minimizes_energy_per_km_and_robot_mass():
    assert {"energy_per_km", "robot_mass"} <= set(objectives("minimize"))


def test_the_report_has_a_motors_and_battery_section(tmp_path):
    from hexaleg.output.report.motors import PART, MotorsRecord
    from hexaleg.output.report.options import ReportOptions
    from hexaleg.output.report.part import ReportData
    from hexaleg.output.report.yours import compute as measured_once

    data = ReportData(DESIGN, ReportOptions(), HexapodModel(DESIGN))
    data = data.with_record(measured_once(data))  # your design's one evaluation, read by it
    data = data.with_record(PART.compute(data))
    section = PART.section(data)
    text = "\n".join(b for b in section.blocks if isinstance(b, str))
    assert section.title == "Motors and battery"
    words = ("RMS torque / continuous", "voltage needed / bus", "Wh/km", "km.", "copper",
             "V bus, its windings at 25 °C")  # fmt: skip
    assert all(word in text for word in words), text
    PART.files(data, tmp_path)
    assert (tmp_path / "gait_power.png").is_file() and (tmp_path / "gait_envelope.png").is_file()
    assert PART.json(data[MotorsRecord])["motors"]["electrical"]["energy_per_km"] > 0
    bare = ReportData(HexapodDesign(), ReportOptions(), HexapodModel(HexapodDesign()))
    bare = bare.with_record(PART.compute(bare))
    assert "names no actuators" in PART.section(bare).blocks[0]
