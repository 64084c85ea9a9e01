"""One evaluation of a design against the single-design analyses it stands for."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg import (
    HexapodDesign,
    HexapodModel,
    StanceGeometry,
    analyze_gait,
    analyze_loads,
    analyze_manipulability,
    flexibility,
)
from hexaleg.evaluation.evaluate import ANALYSES, Conditions, evaluate, evaluate_many
from hexaleg.evaluation.metrics import METRICS, metric, objectives
from hexaleg.gait.capacity import walking_payload_capacity
from hexaleg.gait.spec import Gait
from hexaleg.statics.forces import Payload


def _designs(count: int, seed: int) -> list[HexapodDesign]:
    """Seeded designs of the default body: coxa ratio 0.06-0.22, tibia ratio 0.3-0.6."""
    rng = np.random.default_rng(seed)
    return [
        HexapodDesign.from_ratios(rng.uniform(0.06, 0.22), rng.uniform(0.3, 0.6))
        for _ in range(count)
    ]


def _oracle(design: HexapodDesign) -> dict[str, float]:
    """Every metric from the single-design analyses and closed forms, on the design's URDF."""
    loads = analyze_loads(design)
    walked = analyze_gait(design, Gait(), limits=False, speed=True)
    assert walked.max_speed is not None
    return {
        "improved_area": 2 * math.pi * design.l2 * design.l3 / 3,  # eq 16
        "average_manipulability": analyze_manipulability(design).average_improved,
        "fb": flexibility(design, "axis").fb,
        "payload_capacity": loads.capacity.mass,
        "max_slope": loads.worst_slope.max_slope,
        "ground_clearance": design.nominal_height - design.body_height / 2,
        "leg_length": design.l1 + design.l2 + design.l3,
        "coxa_length": design.l1,
        "robot_mass": design.total_mass,
        "max_speed": walked.max_speed.value,
        "gait_peak_torque": float(np.abs(walked.joint_torques).max()),
        "mechanical_cost_of_transport": walked.metrics.cost_of_transport,
        # its own module, held against a bisection on analyze_gait in test_gait_capacity
        "walking_payload_capacity": walking_payload_capacity(HexapodModel(design)).mass,
        # positive work per period over the distance walked in it, J/m to Wh/km
        "mechanical_energy_per_km": walked.metrics.positive_work
        / (walked.gait.speed * walked.gait.period)
        / 3.6,
        "min_zmp_margin": walked.min_zmp_margin,
        **{
            f"gait_peak_{j}_torque": float(np.abs(walked.joint_torques[..., k]).max())
            for k, j in enumerate(("root", "hip", "knee"))
        },
        **{
            f"gait_rms_{j}_torque": float(
                np.sqrt((walked.joint_torques[..., k] ** 2).mean(axis=0)).max()
            )
            for k, j in enumerate(("root", "hip", "knee"))
        },
        "nominal_height": float(HexapodModel(design).nominal_base_pose().translation[2]),
        "stability_margin": loads.nominal.stability_margin,
        # no actuators: nothing through the motors (test_motors_study has a design with them)
        **dict.fromkeys(
            ("energy_per_km", "electrical_cost_of_transport", "continuous_load", "battery_range"),
            math.nan,
        ),
    }


@pytest.mark.parametrize("design", _designs(3, seed=11))
def test_every_metric_equals_its_single_design_analysis(design):
    found = evaluate(design, list(METRICS))
    assert not found.error and set(found.values) == set(METRICS)
    assert found.values == pytest.approx(_oracle(design), rel=1e-9, abs=1e-12, nan_ok=True)


def test_the_fast_path_of_one_body_equals_each_design_on_its_own_urdf():
    base = HexapodDesign()
    model = HexapodModel(base)
    template = StanceGeometry.from_model(model)
    designs = _designs(4, seed=5)
    names = ("fb", "payload_capacity", "ground_clearance", "max_speed")
    batch = evaluate_many(designs, names, Conditions(), model, template)
    for design, fast in zip(designs, batch, strict=True):
        exact = evaluate(design, names)
        assert fast.values == pytest.approx(exact.values, rel=1e-9, abs=1e-12)


def test_only_what_is_asked_is_measured_and_kept():
    design = HexapodDesign()
    found = evaluate(design, ["improved_area"])
    assert list(found.values) == ["improved_area"] and found.flexibility is None
    kept = evaluate(design, ["fb", "payload_capacity"], Conditions(keep=True))
    assert kept.flexibility is not None and kept.loads is not None and kept.gait is None
    assert kept.values["payload_capacity"] == kept.loads.capacity.mass


def test_the_conditions_reach_the_analyses():
    design = HexapodDesign()
    payload = Payload(20.0, (0.1, 0.0, 0.05))
    conditions = Conditions(payload=payload, slope=math.radians(10), gait=Gait().with_speed(0.2))
    found = evaluate(design, ["payload_capacity", "max_slope", "max_speed"], conditions)
    level = evaluate(design, ["payload_capacity", "max_slope", "max_speed"])
    assert found.values["payload_capacity"] < level.values["payload_capacity"]  # on 10°
    assert found.values["max_slope"] <= level.values["max_slope"]
    walked = analyze_gait(design, Gait().with_speed(0.2), payload, limits=False, speed=True)
    assert walked.max_speed is not None
    assert found.values["max_speed"] == pytest.approx(walked.max_speed.value, rel=1e-12)


def test_a_gait_that_cannot_be_walked_leaves_its_costs_unmeasured_and_says_why():
    design = HexapodDesign.from_ratios(0.2, 0.75)  # the tibia cannot reach the stride
    found = evaluate(design, ["max_speed", "gait_peak_torque", "mechanical_cost_of_transport"])
    assert found.values["max_speed"] == 0.0
    assert math.isnan(found.values["gait_peak_torque"])
    assert "cannot walk the gait" in found.unmeasured["gait_peak_torque"]


def test_every_metric_is_declared_once_and_measured_by_a_known_analysis():
    assert all(spec.name == name for name, spec in METRICS.items())
    assert {spec.analysis for spec in METRICS.values()} <= set(ANALYSES)
    assert {spec.unit for spec in METRICS.values()} <= {"m", "m²", "m³", "1", "kg", "rad",
                                                       "m/s", "N·m", "Wh/km", "km"}  # fmt: skip
    assert set(objectives("maximize")) & set(objectives("minimize")) == set()
    assert metric("fb").label == "FB"
    with pytest.raises(Exception, match="one of improved_area"):
        metric("flexibility")


@pytest.mark.parametrize(
    ("value", "text"),
    [(2000.0, "2000"), (1234.5, "1230"), (0.012345, "0.0123"), (0.5, "0.5"), (368.2, "368"),
     (1e6, "1000000"), (-0.000123, "-0.000123"), (0.0, "0")],
)  # fmt: skip
def test_numbers_in_sentences_read_as_an_engineer_writes_them(value, text):
    from hexaleg.evaluation.metrics import significant

    assert significant(value) == text
    assert metric("payload_capacity").short(value) == f"{text} kg"
