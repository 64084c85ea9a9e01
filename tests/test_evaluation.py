"""One evaluation of a design against the single-design analyses it stands for."""

from __future__ import annotations

import dataclasses
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
from hexaleg.evaluation.metrics import METRICS, Metrics, PerMetric, objectives
from hexaleg.gait.capacity import walking_payload_capacity
from hexaleg.gait.spec import Gait
from hexaleg.ratings import NEEDS_RATING
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
        # no actuators: nothing through the motors (test_motors_study has a design with them);
        # no [structure]: no tubes to load
        **dict.fromkeys(
            (
                "energy_per_km",
                "electrical_cost_of_transport",
                "continuous_load",
                "battery_range",
                "structure_load",
            ),
            math.nan,
        ),
    }


@pytest.mark.parametrize("design", _designs(3, seed=11))
def test_every_metric_equals_its_single_design_analysis(design):
    found = evaluate(design, list(METRICS))
    assert not found.error and set(found.metrics.to_dict()) == {spec.name for spec in METRICS}
    expected = _oracle(design)
    assert set(expected) == {spec.name for spec in METRICS}
    assert found.metrics.to_dict() == pytest.approx(expected, rel=1e-9, abs=1e-12, nan_ok=True)


def test_the_fast_path_of_one_body_equals_each_design_on_its_own_urdf():
    base = HexapodDesign()
    model = HexapodModel(base)
    template = StanceGeometry.from_model(model)
    designs = _designs(4, seed=5)
    specs = (METRICS.fb, METRICS.payload_capacity, METRICS.ground_clearance, METRICS.max_speed)
    models = [model.with_design(design) for design in designs]
    batch = evaluate_many(designs, specs, Conditions(), models, template)
    for design, fast in zip(designs, batch, strict=True):
        exact = evaluate(design, specs)
        assert fast.metrics.to_dict() == pytest.approx(exact.metrics.to_dict(), rel=1e-9, abs=1e-12)


def test_only_what_is_asked_is_measured_and_kept():
    design = HexapodDesign()
    found = evaluate(design, [METRICS.improved_area])
    assert found.metrics == Metrics(improved_area=found.metrics.improved_area)
    assert found.metrics.improved_area is not None and found.flexibility is None
    kept = evaluate(design, [METRICS.fb, METRICS.payload_capacity], Conditions(keep=True))
    assert kept.flexibility is not None and kept.loads is not None and kept.gait is None
    assert kept.metrics.payload_capacity == kept.loads.capacity.mass


def test_the_conditions_reach_the_analyses():
    design = HexapodDesign()
    payload = Payload(20.0, (0.1, 0.0, 0.05))
    conditions = Conditions(payload=payload, slope=math.radians(10), gait=Gait().with_speed(0.2))
    specs = (METRICS.payload_capacity, METRICS.max_slope, METRICS.max_speed)
    found, level = evaluate(design, specs, conditions).metrics, evaluate(design, specs).metrics
    assert found.value(METRICS.payload_capacity) < level.value(METRICS.payload_capacity)  # 10°
    assert found.value(METRICS.max_slope) <= level.value(METRICS.max_slope)
    walked = analyze_gait(design, Gait().with_speed(0.2), payload, limits=False, speed=True)
    assert walked.max_speed is not None
    assert found.max_speed == pytest.approx(walked.max_speed.value, rel=1e-12)


def test_a_gait_that_cannot_be_walked_leaves_its_costs_unmeasured_and_says_why():
    design = HexapodDesign.from_ratios(0.2, 0.75)  # the tibia cannot reach the stride
    specs = (METRICS.max_speed, METRICS.gait_peak_torque, METRICS.mechanical_cost_of_transport)
    found = evaluate(design, specs)
    assert found.metrics.max_speed == 0.0
    assert found.metrics.gait_peak_torque is not None and math.isnan(found.metrics.gait_peak_torque)
    assert "cannot walk the gait" in (found.unmeasured.gait_peak_torque or "")
    assert found.unmeasured.max_speed is None  # the max speed is measured all the same


def test_a_design_without_ratings_leaves_what_needs_one_unmeasured_and_says_so():
    rated = HexapodDesign()
    unrated = rated.replace(rated_torques=None, rated_speeds=None)  # a robot file's effort="0"
    needs = (METRICS.payload_capacity, METRICS.max_slope, METRICS.walking_payload_capacity,
             METRICS.max_speed)  # fmt: skip
    free = (METRICS.stability_margin, METRICS.gait_peak_torque)  # no rating enters them
    found = evaluate(unrated, (*needs, *free))
    for spec in needs:
        assert math.isnan(found.metrics.value(spec)) and found.metrics[spec] is not None
        assert found.unmeasured[spec] == NEEDS_RATING and found.causes[spec] is None
    assert found.walks is None
    alike = evaluate(rated, free)  # what needs no rating: the rated design's own values
    for spec in free:
        assert found.metrics.value(spec) == pytest.approx(alike.metrics.value(spec), rel=1e-12)
        assert found.unmeasured[spec] is None


def test_every_metric_is_declared_once_and_measured_by_a_known_analysis():
    declared = [f.name for f in dataclasses.fields(PerMetric)]
    assert [spec.name for spec in METRICS] == declared  # each field is its declaration
    assert all(getattr(METRICS, name).name == name for name in declared)
    assert {spec.analysis for spec in METRICS} <= set(ANALYSES)
    units = {"m", "m²", "m³", "1", "kg", "rad", "m/s", "N·m", "Wh/km", "km"}
    assert {spec.unit for spec in METRICS} <= units
    assert set(objectives("maximize")) & set(objectives("minimize")) == set()
    assert METRICS.named("fb") is METRICS.fb and METRICS.fb.label == "FB"
    with pytest.raises(Exception, match="one of improved_area"):
        METRICS.named("flexibility")


def test_a_design_s_metrics_are_typed_fields_and_read_back_from_their_dict():
    metrics = Metrics(fb=0.3, walking_payload_capacity=12.0, gait_peak_hip_torque=math.nan)
    assert metrics.fb == 0.3 and metrics[METRICS.walking_payload_capacity] == 12.0
    assert math.isnan(metrics.value(METRICS.max_speed))  # not measured
    peaks = metrics.joint_torques("peak")
    assert peaks == {"root": None, "hip": metrics.gait_peak_hip_torque, "knee": None}
    back = Metrics.from_dict(metrics.to_dict())
    assert back.to_dict() == pytest.approx(metrics.to_dict(), nan_ok=True)
    with pytest.raises(ValueError, match="unknown metric"):
        Metrics.from_dict({"flexibility": 0.3})
    with pytest.raises(dataclasses.FrozenInstanceError):
        metrics.fb = 0.4  # type: ignore[misc]


@pytest.mark.parametrize(
    ("value", "text"),
    [
        (2000.0, "2000"),
        (1234.5, "1230"),
        (0.012345, "0.0123"),
        (0.5, "0.5"),
        (368.2, "368"),
        (1e6, "1000000"),
        (-0.000123, "-0.000123"),
        (0.0, "0"),
    ],
)
def test_numbers_in_sentences_read_as_an_engineer_writes_them(value, text):
    from hexaleg.evaluation.metrics import significant

    assert significant(value) == text
    assert METRICS.payload_capacity.short(value) == f"{text} kg"
