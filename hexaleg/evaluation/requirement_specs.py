"""Every requirement and condition of a decision, declared once.

A requirement bounds one metric (:data:`~hexaleg.evaluation.metrics.METRICS`); a condition says
under what it is measured (where the payload sits, how high the gait steps). Each is one
record here, and every reader derives what it needs from that record: the fields and
validation of :class:`~hexaleg.evaluation.requirements.Requirements`, the keys of a design
file's ``[requirements]`` table and the commented example ``hexaleg design init`` writes,
the command-line options of ``decide`` and ``report`` with their metavars and help, the
evaluation (which metric to measure), the checks (which way is met, what binds) and the
conflict messages. Adding a requirement is adding its record to :data:`REQUIREMENTS`
(and a :class:`~hexaleg.evaluation.metrics.MetricSpec` with its measuring step if the metric
is new).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

from hexaleg.design import SEGMENT_RANGE
from hexaleg.evaluation.metrics import METRICS, MetricSpec
from hexaleg.gait.spec import Gait
from hexaleg.statics.forces import PAYLOAD_REACH, PAYLOAD_SEARCH_LIMIT

Sense = Literal["at least", "at most"]
"""Which side of the required value meets a requirement."""

BINDING_SHARE = 0.01
"""A met requirement binds when its margin is within this share of the required value."""


@dataclass(frozen=True)
class RequirementSpec:
    """One requirement: what it bounds, how, and how it is written.

    Attributes:
        name: Its key in files and JSON, its field, and (with dashes) its option.
        metric: The metric it bounds.
        sense: ``"at least"`` or ``"at most"``.
        bounds: The plausible required values, inclusive [the metric's unit].
        help: What it asks, with its unit in brackets (the option's help, the file's comment).
        metavar: The option's metavar.
        example: A plausible value, for the commented example table of a new design file.
        reason: What sets its value when no analysis stops at a constraint (the design's
            own geometry).
        zero: Whether zero is a valid requirement (else it must be positive).

    """

    name: str
    metric: MetricSpec
    sense: Sense
    bounds: tuple[float, float]
    help: str
    metavar: str
    example: float
    reason: str
    zero: bool = False

    @property
    def unit(self) -> str:
        """Its unit: its metric's."""
        return self.metric.unit

    @property
    def option(self) -> str:
        """Its command-line option, ``--ground-clearance``."""
        return "--" + self.name.replace("_", "-")

    def margin(self, required: float, value: float) -> float:
        """How far ``value`` is on the good side of ``required`` [unit] (< 0: not met)."""
        return value - required if self.sense == "at least" else required - value

    def binds(self, required: float, margin: float) -> bool:
        """Whether a design meeting it with ``margin`` sits on it."""
        return 0 <= margin <= BINDING_SHARE * max(abs(required), 1e-12)


ConditionKind = Literal["position", "number", "degrees"]
"""A condition's value: body-frame coordinates, a number, or another key's value in degrees."""


@dataclass(frozen=True)
class ConditionSpec:
    """One condition of a requirement: a key of the table that is no requirement itself.

    Attributes:
        name: Its key in files and JSON, and (with dashes) its option.
        of: The requirement it belongs to (its option follows that one's).
        kind: What its value is.
        help: What it is, with its unit in brackets.
        metavar: The option's metavar (three, for a position).
        example: A plausible value (three numbers for a position).
        unit: Its unit (of each coordinate, for a position).
        bounds: Its plausible values, inclusive (of each coordinate, for a position).
        needs: Why it is refused without its requirement (empty: a degrees key, which
            gives the requirement itself).
        also: Other requirements it is a condition of too.

    """

    name: str
    of: str
    kind: ConditionKind
    help: str
    metavar: tuple[str, ...]
    example: float | tuple[float, float, float]
    unit: str
    bounds: tuple[float, float]
    needs: str = ""
    also: tuple[str, ...] = ()

    @property
    def option(self) -> str:
        """Its command-line option, ``--payload-at``."""
        return "--" + self.name.replace("_", "-")


REQUIREMENTS: Mapping[str, RequirementSpec] = {
    spec.name: spec
    for spec in (
        RequirementSpec(
            "payload",
            METRICS.payload_capacity,
            "at least",
            (0.0, PAYLOAD_SEARCH_LIMIT),
            "payload the robot must carry [kg]",
            "KG",
            30.0,
            "the statics",
            zero=True,
        ),
        RequirementSpec(
            "slope",
            METRICS.max_slope,
            "at least",
            (0.0, math.pi / 2),
            "slope it must stand on, uphill in every heading, with the payload [rad]",
            "RAD",
            math.radians(15.0),
            "the statics",
            zero=True,
        ),
        RequirementSpec(
            "ground_clearance",
            METRICS.ground_clearance,
            "at least",
            (0.0, 100.0),
            "body underside above the ground at the nominal stance [m]",
            "M",
            0.25,
            "geometry: the tibia, femur and nominal posture",
        ),
        RequirementSpec(
            "min_fb",
            METRICS.fb,
            "at least",
            (0.0, 10.0),
            "least axis-locked body flexibility FB (eq 29) [-]",
            "F",
            0.2,
            "geometry: twelve extremes, each stopped by its own constraint",
        ),
        RequirementSpec(
            "leg_length",
            METRICS.leg_length,
            "at most",
            (3 * SEGMENT_RANGE[0], SEGMENT_RANGE[1]),
            "largest total leg length l1+l2+l3 [m] (default: the design's)",
            "M",
            1.0,
            "geometry: the design's l1 + l2 + l3",
        ),
        RequirementSpec(
            "min_coxa",
            METRICS.coxa_length,
            "at least",
            SEGMENT_RANGE,
            "least coxa length l1, for the root actuator's packaging [m]",
            "M",
            0.08,
            "geometry: the design's coxa length l1",
        ),
        RequirementSpec(
            "speed",
            METRICS.max_speed,
            "at least",
            (0.0, 100.0),
            f"tripod gait speed ({Gait.stride:g} m stride) carrying the payload "
            "within the rated torques and speeds; with [actuators], within their "
            "electrical ratings: peak and continuous (RMS) torque, the supply "
            "voltage, max speed [m/s]",
            "M/S",
            0.3,
            "the gait",
        ),
        RequirementSpec(
            "walking_payload",
            METRICS.walking_payload_capacity,
            "at least",
            (0.0, PAYLOAD_SEARCH_LIMIT),
            "payload the robot must carry at payload_at walking that gait within "
            "every rating, the ZMP inside the standing feet [kg]",
            "KG",
            10.0,
            "the gait",
            zero=True,
        ),
        RequirementSpec(
            "range_km",
            METRICS.battery_range,
            "at least",
            (0.0, 1e5),
            "distance it must walk that gait on one charge of its battery [km]",
            "KM",
            5.0,
            "the gait and the battery",
        ),
        RequirementSpec(
            "continuous_margin",
            METRICS.continuous_load,
            "at most",
            (0.01, 1.0),
            "largest share of its continuous torque any joint's RMS torque may be "
            "walking that gait [-]",
            "SHARE",
            0.8,
            "the gait and the actuators",
        ),
    )
}
"""Every requirement, in the order answers list them."""

CONDITIONS: Mapping[str, ConditionSpec] = {
    spec.name: spec
    for spec in (
        ConditionSpec(
            "payload_at",
            "payload",
            "position",
            f"where the payload sits, body frame x, y, z, each in [-{PAYLOAD_REACH:g}, "
            f"{PAYLOAD_REACH:g}] [m] (default: the centre of the body's top face)",
            ("X", "Y", "Z"),
            (0.0, 0.0, 0.05),
            "m",
            (-PAYLOAD_REACH, PAYLOAD_REACH),
            "needs a payload [kg] to place",
            also=("walking_payload",),
        ),
        ConditionSpec(
            "slope_deg",
            "slope",
            "degrees",
            "the same slope in degrees [°]",
            ("DEG",),
            15.0,
            "°",
            (0.0, 90.0),
        ),
        ConditionSpec(
            "step_height",
            "speed",
            "number",
            f"step height of that gait [m] (default {Gait.step_height:g})",
            ("M",),
            0.1,
            "m",
            (0.0, 10.0),
            "needs a speed [m/s] to walk at; > 0 [m]",
        ),
    )
}
"""Every condition, each after the requirement it belongs to in the table and the options."""


def table_keys() -> tuple[RequirementSpec | ConditionSpec, ...]:
    """Every key of the ``[requirements]`` table, each condition after its requirement."""
    keys: list[RequirementSpec | ConditionSpec] = []
    for requirement in REQUIREMENTS.values():
        keys.append(requirement)
        keys += [c for c in CONDITIONS.values() if c.of == requirement.name]
    return tuple(keys)


def degree_keys() -> dict[str, str]:
    """Keys giving another key's value in degrees: ``{"slope_deg": "slope"}``."""
    return {c.name: c.of for c in CONDITIONS.values() if c.kind == "degrees"}
