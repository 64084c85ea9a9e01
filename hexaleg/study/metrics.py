"""Every metric a design has, declared once: its name, unit, label and which way is better.

A metric is one number measured on one design (its FB, its payload capacity, its max
speed). Each is a :class:`MetricSpec` in :data:`METRICS`, and that one declaration is what
every reader takes its name, unit and words from: the evaluation that measures it
(:mod:`hexaleg.study.evaluation`), the study's ranking rule, ``decide``'s objectives and
requirements, the conflict messages, the report's decision and the study's columns.
Adding a metric is adding its declaration here and its measuring step in the evaluation.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

from hexaleg.design import HexapodDesign
from hexaleg.exceptions import ParameterError
from hexaleg.limits import LEG_JOINTS

Better = Literal["maximize", "minimize"]
"""Which way a metric is better."""

Analysis = Literal[
    "geometry", "workspace", "manipulability", "flexibility", "clearance", "standing", "walking"
]
"""The analysis that measures a metric (the evaluation runs each one at most once)."""


@dataclass(frozen=True)
class MetricSpec:
    """Everything said about one metric, once.

    Attributes:
        name: Its key in every record, table column, JSON object and option.
        unit: Its SI unit as written in brackets (``"1"`` for a pure number).
        label: Its name in a sentence or a table cell: ``"FB"``, ``"improved area"``.
        text: What it is, with its source: ``"body flexibility FB (eq 29, axis-locked)"``.
        better: Whether larger or smaller is better.
        analysis: What measures it.
        objective: Whether ``decide`` offers it as an objective (in its better direction).

    """

    name: str
    unit: str
    label: str
    text: str
    better: Better
    analysis: Analysis
    objective: bool = False

    @property
    def described(self) -> str:
        """What it is with its unit: ``"body flexibility FB [-] (eq 29, axis-locked)"``."""
        unit = "-" if self.unit == "1" else self.unit
        head, _, source = self.text.partition(" (")
        return f"{head} [{unit}]" + (f" ({source}" if source else "")

    def format(self, value: float) -> str:
        """The value with its unit, four significant digits; angles also in degrees."""
        if self.unit == "rad":
            return f"{significant(value, 4)} rad ({significant(math.degrees(value))}°)"
        text = significant(value, 4)
        return text if self.unit == "1" else f"{text} {self.unit}"

    def cell(self, value: float) -> str:
        """The value in a table cell whose header gives the unit: four significant digits."""
        return significant(value, 4)

    def short(self, value: float) -> str:
        """The value in a sentence, as an engineer writes it: ``2000 kg``, ``0.0123 m``, ``17°``.

        Three significant digits, never an exponent; angles in degrees.
        """
        if self.unit == "rad":
            return f"{significant(math.degrees(value))}°"
        text = significant(value)
        return text if self.unit == "1" else f"{text} {self.unit}"


def significant(value: float, digits: int = 3) -> str:
    """``value`` rounded to ``digits`` significant digits, written without an exponent."""
    if not math.isfinite(value) or value == 0:
        return f"{value:g}"
    rounded = float(f"{value:.{digits}g}")
    decimals = max(0, digits - 1 - math.floor(math.log10(abs(rounded))))
    text = f"{rounded:.{decimals}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


METRICS: Mapping[str, MetricSpec] = {
    spec.name: spec
    for spec in (
        MetricSpec("improved_area", "m²", "improved area", "improved workspace area (eq 16)",
                   "maximize", "workspace", objective=True),
        MetricSpec("average_manipulability", "m³", "w_A",
                   "average manipulability w_A (eq 27, improved domain)", "maximize",
                   "manipulability", objective=True),
        MetricSpec("fb", "1", "FB", "body flexibility FB (eq 29, axis-locked)", "maximize",
                   "flexibility", objective=True),
        MetricSpec("payload_capacity", "kg", "payload",
                   "payload capacity (nominal stance, on the required slope if one is)",
                   "maximize", "standing", objective=True),
        MetricSpec("walking_payload_capacity", "kg", "walking payload",
                   "walking payload capacity (the gait within every rating, the ZMP inside)",
                   "maximize", "walking", objective=True),
        MetricSpec("max_slope", "rad", "slope",
                   "steepest slope stood on in every heading, with the payload", "maximize",
                   "standing"),
        MetricSpec("ground_clearance", "m", "ground clearance",
                   "body underside above the ground (nominal stance)", "maximize", "clearance"),
        MetricSpec("leg_length", "m", "leg length", "total leg length l1 + l2 + l3",
                   "minimize", "geometry", objective=True),
        MetricSpec("coxa_length", "m", "coxa", "coxa length l1", "maximize", "geometry"),
        MetricSpec("robot_mass", "kg", "robot mass", "the whole robot's mass", "minimize",
                   "geometry", objective=True),
        MetricSpec("max_speed", "m/s", "speed",
                   "fastest walk of the gait's stride within the ratings", "maximize", "walking",
                   objective=True),
        MetricSpec("gait_peak_torque", "N·m", "peak torque",
                   "largest joint torque over a gait period", "minimize", "walking",
                   objective=True),
        MetricSpec("mechanical_cost_of_transport", "1", "mechanical cost of transport",
                   "positive mechanical work per weight and distance walked", "minimize",
                   "walking", objective=True),
        MetricSpec("mechanical_energy_per_km", "Wh/km", "mechanical energy",
                   "positive mechanical work per kilometre walked", "minimize", "walking"),
        MetricSpec("energy_per_km", "Wh/km", "energy per km",
                   "electrical energy per kilometre walked, through the motors", "minimize",
                   "walking", objective=True),
        MetricSpec("electrical_cost_of_transport", "1", "electrical cost of transport",
                   "electrical energy per weight and distance walked", "minimize", "walking"),
        MetricSpec("continuous_load", "1", "continuous load",
                   "largest RMS torque over its actuator's continuous torque, any joint",
                   "minimize", "walking"),
        MetricSpec("battery_range", "km", "range",
                   "distance walked on one charge of the battery", "maximize", "walking",
                   objective=True),
        MetricSpec("min_zmp_margin", "m", "ZMP margin",
                   "the gait's least ZMP distance inside the standing feet", "maximize",
                   "walking"),
        *(
            MetricSpec(f"gait_{kind}_{joint}_torque", "N·m", f"{joint} {kind} torque",
                       f"{kind.upper() if kind == 'rms' else kind} {joint} torque over a gait "
                       "period (the worst leg)", "minimize", "walking")
            for joint in LEG_JOINTS for kind in ("peak", "rms")
        ),
        MetricSpec("nominal_height", "m", "body height",
                   "body frame's height above the ground at the nominal stance", "maximize",
                   "geometry"),
        MetricSpec("stability_margin", "m", "stability margin",
                   "centre of mass's footprint inside the support polygon (nominal stance)",
                   "maximize", "standing"),
    )
}  # fmt: skip
"""Every metric, in the order answers list them."""


def metric(name: str) -> MetricSpec:
    """The declaration of metric ``name``; a ParameterError naming the known ones otherwise."""
    try:
        return METRICS[name]
    except KeyError:
        raise ParameterError("metric", name, "one of " + ", ".join(METRICS)) from None


def objectives(better: Better) -> tuple[str, ...]:
    """The metrics ``decide`` offers to make best in direction ``better``."""
    return tuple(m.name for m in METRICS.values() if m.objective and m.better == better)


NEEDS: Mapping[str, tuple[str, ...]] = {
    "energy_per_km": ("actuators",),
    "electrical_cost_of_transport": ("actuators",),
    "continuous_load": ("actuators",),
    "battery_range": ("actuators", "battery"),
}
"""The design-file tables a metric is measured through: without them it has no value."""


def missing_tables(name: str, design: HexapodDesign, actuators: bool = False) -> tuple[str, ...]:
    """The tables (``"actuators"``, ``"battery"``) metric ``name`` needs that ``design`` lacks.

    ``actuators``: motors are being chosen for it (``decide --choose-actuators``).
    """
    has = {"actuators": actuators or design.actuators is not None,
           "battery": design.battery is not None}  # fmt: skip
    return tuple(table for table in NEEDS.get(name, ()) if not has[table])
