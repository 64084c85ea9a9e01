"""Every requirement and condition of a decision, declared once.

A requirement bounds one metric (:data:`~hexaleg.evaluation.metrics.METRICS`); a condition says
under what it is measured (where the payload sits, how high the gait steps). Each is one
record here, and every reader derives what it needs from that record: the validation and
storage of :class:`~hexaleg.evaluation.requirements.Requirements`, the keys of a design
file's ``[requirements]`` table and the commented example ``hexaleg design init`` writes,
the command-line options of ``decide`` and ``report`` with their metavars and help, the
evaluation (the metric to measure), the checks (which way is met, what binds) and the
conflict messages. Adding a requirement is adding its record to :data:`REQUIREMENTS` (and
a metric with its measuring step, :mod:`hexaleg.evaluation.metrics`, if the metric is
new); code that reads one requirement reads it by its record (``requirements.required(SLOPE)``).

The ratings the requirements are measured against are the design's ``rated_torques`` and
``rated_speeds``. Payload and slope are one condition seen two ways: the payload is held
on the required slope, the slope stood on with the required payload.
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
from hexaleg.statics.ground import MAX_SLOPE
from hexaleg.statics.ratings import SAFETY_FACTOR_RANGE

Sense = Literal["at least", "at most"]
"""Which side of the required value meets a requirement."""

BINDING_SHARE = 0.01
"""A met requirement binds when its margin is within this share of the required value."""

AT_LIMIT_SHARE = 0.005
"""A met requirement is *at the limit* when its margin is within this share of the required
value: no margin a workshop's tolerances or a motor's spread could eat into is left."""

ROUNDOFF = 1e-12
"""A value within this share of the required one meets it [-]: the floating-point sum of
lengths a workshop gives in millimetres (0.02 + 0.569 + 0.411 m) is their decimal sum only
to this, and a value equal to its limit to twelve digits is at it, not past it."""

DEGREES = "_deg"
"""The suffix of a key giving a requirement in degrees (``slope_deg``)."""


@dataclass(frozen=True)
class RequirementSpec:
    """One requirement: what it bounds, how, and how it is written.

    Attributes:
        metric: The metric it bounds (what measures it).
        sense: ``"at least"`` or ``"at most"``.
        bounds: The plausible required values, inclusive [the metric's unit].
        help: What it asks, with its unit in brackets (the option's help, the file's comment).
        metavar: The option's metavar.
        example: A plausible value, for the commented example table of a new design file.
        reason: What sets its value when no analysis stops at a constraint (the design's
            own geometry).
        name: Its key in files and JSON, and (with dashes) its option; its metric's name
            if omitted.
        zero: Whether zero is a valid requirement (else it must be positive).
        below: Whether it must be below its upper bound, not at it.
        degrees: Whether it is an angle also given in degrees, as ``<name>_deg``.
        implied: Whether the design asks it rather than the user: never a key or an option
            (:meth:`~.requirements.Requirements.resolved` sets it), never relaxed.

    """

    metric: MetricSpec
    sense: Sense
    bounds: tuple[float, float]
    help: str
    metavar: str
    example: float
    reason: str
    name: str = ""
    zero: bool = False
    below: bool = False
    degrees: bool = False
    implied: bool = False

    def __post_init__(self) -> None:
        if not self.name:
            object.__setattr__(self, "name", self.metric.name)

    @property
    def unit(self) -> str:
        """Its unit: its metric's."""
        return self.metric.unit

    @property
    def option(self) -> str:
        """Its command-line option, ``--ground-clearance``."""
        return "--" + self.name.replace("_", "-")

    @property
    def in_degrees(self) -> ConditionSpec | None:
        """The key giving it in degrees (``slope_deg``), if it is an angle."""
        if not self.degrees:
            return None
        return _in_degrees(self, self, self.metric.label, self.example, self.bounds)

    def margin(self, required: float, value: float) -> float:
        """How far ``value`` is on the good side of ``required`` [unit] (< 0: not met)."""
        return value - required if self.sense == "at least" else required - value

    def met(self, required: float, margin: float) -> bool:
        """Whether a value ``margin`` from ``required`` meets it (within :data:`ROUNDOFF`)."""
        return margin >= -ROUNDOFF * max(abs(required), 1e-12)

    def binds(self, required: float, margin: float) -> bool:
        """Whether a design meeting it with ``margin`` sits on it."""
        return self.met(required, margin) and margin <= BINDING_SHARE * max(abs(required), 1e-12)

    def at_limit(self, required: float, margin: float) -> bool:
        """Whether a design meeting it with ``margin`` has no margin left to speak of."""
        return self.met(required, margin) and margin <= AT_LIMIT_SHARE * max(abs(required), 1e-12)


ConditionKind = Literal["position", "number", "degrees"]
"""A condition's value: body-frame coordinates, a number, or its requirement in degrees."""


@dataclass(frozen=True)
class ConditionSpec:
    """One condition: a key of the table that is no requirement itself.

    A condition of one requirement (where the payload sits, how high the gait steps), or of
    every requirement and metric measured (the slope walked, the motors' safety factor).

    Attributes:
        name: Its key in files and JSON, and (with dashes) its option.
        of: The requirement it belongs to (its option follows that one's); ``None``: every
            requirement's and metric's (its option follows the requirements').
        kind: What its value is.
        help: What it is, with its unit in brackets.
        metavar: The option's metavar (three, for a position).
        example: A plausible value (three numbers for a position).
        unit: Its unit (of each coordinate, for a position).
        bounds: Its plausible values, inclusive (of each coordinate, for a position).
        needs: Why it is refused without its requirement (empty: a degrees key, which
            gives the requirement itself, or a condition of every requirement).
        also: Other requirements it is a condition of too.
        zero: Whether a number may be zero (else it must be positive).
        degrees: Whether it is an angle also given in degrees, as ``<name>_deg``.
        gives: For a key in degrees, the requirement or condition it gives in radians.

    """

    name: str
    of: RequirementSpec | None
    kind: ConditionKind
    help: str
    metavar: tuple[str, ...]
    example: float | tuple[float, float, float]
    unit: str
    bounds: tuple[float, float]
    needs: str = ""
    also: tuple[RequirementSpec, ...] = ()
    zero: bool = False
    degrees: bool = False
    gives: RequirementSpec | ConditionSpec | None = None

    @property
    def option(self) -> str:
        """Its command-line option, ``--payload-at``."""
        return "--" + self.name.replace("_", "-")

    @property
    def in_degrees(self) -> ConditionSpec | None:
        """The key giving it in degrees (``walking_slope_deg``), if it is an angle."""
        if not self.degrees or not isinstance(self.example, float):
            return None
        return _in_degrees(self, self.of, self.name.replace("_", " "), self.example, self.bounds)


def _in_degrees(
    spec: RequirementSpec | ConditionSpec,
    of: RequirementSpec | None,
    label: str,
    example: float,
    bounds: tuple[float, float],
) -> ConditionSpec:
    """The key giving ``spec`` (an angle [rad]) in degrees: ``<name>_deg`` [°]."""
    low, high = bounds
    return ConditionSpec(
        spec.name + DEGREES,
        of,
        "degrees",
        f"the same {label} in degrees [°]",
        ("DEG",),
        round(math.degrees(example), 9),
        "°",
        (round(math.degrees(low), 9), round(math.degrees(high), 9)),
        zero=True,
        gives=spec,
    )


PAYLOAD = RequirementSpec(
    METRICS.payload_capacity,
    "at least",
    (0.0, PAYLOAD_SEARCH_LIMIT),
    "payload the robot must carry [kg]",
    "KG",
    30.0,
    "the statics",
    name="payload",
    zero=True,
)
"""The payload [kg] carried at :data:`PAYLOAD_AT`: the largest payload the nominal stance
holds with every joint torque within its rating and the centre of mass over the support
polygon — on level ground, and on every slope up to :data:`SLOPE` in every heading when a
slope is required."""

SLOPE = RequirementSpec(
    METRICS.max_slope,
    "at least",
    (0.0, math.pi / 2),
    "slope it must stand on, uphill in every heading, with the payload [rad]",
    "RAD",
    math.radians(15.0),
    "the statics",
    name="slope",
    zero=True,
    below=True,
    degrees=True,
)
"""The steepest slope [rad] (``slope_deg`` [°]) the robot stands on, uphill in every
heading, carrying :data:`PAYLOAD`: the first slope where it tips, slides (tan α > μ) or a
joint torque reaches its rating (:mod:`hexaleg.statics.standing_limits`)."""

GROUND_CLEARANCE = RequirementSpec(
    METRICS.ground_clearance,
    "at least",
    (0.0, 100.0),
    "body underside above the ground at the nominal stance [m]",
    "M",
    0.25,
    "geometry: the tibia, femur and nominal posture",
)
"""The body's underside above the ground at the nominal stance [m]."""

MIN_FB = RequirementSpec(
    METRICS.fb,
    "at least",
    (0.0, 10.0),
    "least axis-locked body flexibility FB (eq 29) [-]",
    "F",
    0.2,
    "geometry: twelve extremes, each stopped by its own constraint",
    name="min_fb",
)
"""The axis-locked body flexibility FB (eq 29) at least this [-]."""

LEG_LENGTH = RequirementSpec(
    METRICS.leg_length,
    "at most",
    (3 * SEGMENT_RANGE[0], SEGMENT_RANGE[1]),
    "largest total leg length l1+l2+l3 [m] (default: the design's)",
    "M",
    1.0,
    "geometry: the design's l1 + l2 + l3",
)
"""l1 + l2 + l3 at most this [m] (default: the design's own, :meth:`.Requirements.resolved`)."""

MIN_COXA = RequirementSpec(
    METRICS.coxa_length,
    "at least",
    SEGMENT_RANGE,
    "least coxa length l1, for the root actuator's packaging [m]",
    "M",
    0.08,
    "geometry: the design's coxa length l1",
    name="min_coxa",
)
"""l1 at least this [m] (what the root actuator's packaging needs)."""

SPEED = RequirementSpec(
    METRICS.max_speed,
    "at least",
    (0.0, 100.0),
    f"tripod gait speed ({Gait.stride:g} m stride) carrying the payload within the rated "
    "torques and speeds; with [actuators], within their electrical ratings: peak and "
    "continuous (RMS) torque, the supply voltage, max speed [m/s]",
    "M/S",
    0.3,
    "the gait",
    name="speed",
)
"""The fastest [m/s] a tripod gait of the default stride (:class:`~hexaleg.gait.spec.Gait`),
lifting its feet :data:`STEP_HEIGHT` and carrying the payload when one is required, walks
with every peak joint torque and joint speed within its rating and every constraint of the
period kept (:func:`~hexaleg.gait.limits.max_speed`; zero if that stride cannot be walked
at all) — at least this. :attr:`.Requirements.gait` is that gait at the required speed."""

WALKING_PAYLOAD = RequirementSpec(
    METRICS.walking_payload_capacity,
    "at least",
    (0.0, PAYLOAD_SEARCH_LIMIT),
    "payload the robot must carry at payload_at walking that gait within every rating, the "
    "ZMP inside the standing feet [kg]",
    "KG",
    10.0,
    "the gait",
    name="walking_payload",
    zero=True,
)
"""The largest payload [kg] at :data:`PAYLOAD_AT` carried walking that gait with every joint
within its ratings and the ZMP inside the standing feet (:mod:`hexaleg.gait.capacity`) — at
least this."""

RANGE_KM = RequirementSpec(
    METRICS.battery_range,
    "at least",
    (0.0, 1e5),
    "distance it must walk that gait on one charge of its battery [km]",
    "KM",
    5.0,
    "the gait and the battery",
    name="range_km",
)
"""The distance [km] that gait walks on one charge of the design's ``[battery]``, through its
``[actuators]`` (:mod:`hexaleg.electrical`) — at least this."""

CONTINUOUS_MARGIN = RequirementSpec(
    METRICS.continuous_load,
    "at most",
    (0.01, 1.0),
    "largest share of its continuous torque any joint's RMS torque may be walking that gait [-]",
    "SHARE",
    0.8,
    "the gait and the actuators",
    name="continuous_margin",
)
"""Every joint's RMS torque over that gait period as a share of its actuator's continuous
torque — at most this [-]."""

STRUCTURE = RequirementSpec(
    METRICS.structure_load,
    "at most",
    (1.0, 1.0),
    "every leg tube within its strength / safety factor and the foot's deflection within its "
    "limit [-] (the design's [structure] asks it)",
    "1",
    1.0,
    "the legs' tubes and their loads",
    name="structure",
    implied=True,
)
"""The legs' tubes hold, a requirement whenever the design's ``[structure]`` gives every
tube or sizes them: the largest von Mises stress over strength / safety factor and the foot's
deflection over its limit at most 1 — standing with the payload at the nominal stance, the
twelve extremes and every heading of the required slope, and walking the gait when a walking
metric is measured (:data:`~hexaleg.evaluation.metrics.METRICS` ``structure_load``)."""

REQUIREMENTS: Mapping[str, RequirementSpec] = {
    spec.name: spec
    for spec in (
        PAYLOAD,
        SLOPE,
        GROUND_CLEARANCE,
        MIN_FB,
        LEG_LENGTH,
        MIN_COXA,
        SPEED,
        WALKING_PAYLOAD,
        RANGE_KM,
        CONTINUOUS_MARGIN,
        STRUCTURE,
    )
}
"""Every requirement by name, in the order answers list them."""

PAYLOAD_AT = ConditionSpec(
    "payload_at",
    PAYLOAD,
    "position",
    f"where the payload sits, body frame x, y, z, each in [-{PAYLOAD_REACH:g}, "
    f"{PAYLOAD_REACH:g}] [m] (default: the centre of the body's top face)",
    ("X", "Y", "Z"),
    (0.0, 0.0, 0.05),
    "m",
    (-PAYLOAD_REACH, PAYLOAD_REACH),
    "needs a payload [kg] to place",
    also=(WALKING_PAYLOAD,),
)
"""Where the payload sits, body frame [m] (default: the centre of the body's top face)."""

STEP_HEIGHT = ConditionSpec(
    "step_height",
    SPEED,
    "number",
    f"step height of that gait [m] (default {Gait.step_height:g})",
    ("M",),
    0.1,
    "m",
    (0.0, 10.0),
    "needs a speed [m/s] to walk at; > 0 [m]",
)
"""How high the gait of :data:`SPEED` lifts its feet [m] (the gait's own if omitted)."""

WALKING_SLOPE = ConditionSpec(
    "walking_slope",
    None,
    "number",
    f"slope the robot must walk, uphill, downhill and across; every walking requirement and "
    f"metric is its worst of the three walks [rad], at most {math.degrees(MAX_SLOPE):g}° "
    "(default 0: level ground)",
    ("RAD",),
    math.radians(10.0),
    "rad",
    (0.0, MAX_SLOPE),
    zero=True,
    degrees=True,
)
"""The slope [rad] (``walking_slope_deg`` [°]) the robot walks its gait on: uphill (the
ground rising along the gait's heading), downhill and across
(:func:`~hexaleg.evaluation.walks.walking_grounds`); the speed, walking payload, range,
torques, cost of transport and every other walking metric are each the worst of the three
walks. The slope it must stand on is :data:`SLOPE`."""

MOTOR_SAFETY_FACTOR = ConditionSpec(
    "motor_safety_factor",
    None,
    "number",
    "the motors' safety factor F: every peak joint torque and speed within its rating / F, "
    "standing and walking [-] (default 1; the legs' tubes have [structure] safety_factor)",
    ("F",),
    1.5,
    "-",
    SAFETY_FACTOR_RANGE,
)
"""The motors' safety factor F ≥ 1 [-]: every rated torque and speed is divided by F wherever a
payload, a slope or a speed is measured within the ratings, standing and walking (the
``[structure]`` table's ``safety_factor`` is the legs' tubes')."""

CONDITIONS: Mapping[str, ConditionSpec] = {
    spec.name: spec for spec in (PAYLOAD_AT, STEP_HEIGHT, WALKING_SLOPE, MOTOR_SAFETY_FACTOR)
}
"""Every condition by name, each after the requirement it belongs to in the table and the
options (the keys in degrees are their requirements', :attr:`RequirementSpec.in_degrees`),
the conditions of every requirement last."""


def table_keys() -> tuple[RequirementSpec | ConditionSpec, ...]:
    """Every key of the ``[requirements]`` table, each condition after its requirement."""
    keys: list[RequirementSpec | ConditionSpec] = []
    for requirement in REQUIREMENTS.values():
        if requirement.implied:
            continue
        keys.append(requirement)
        keys += [] if requirement.in_degrees is None else [requirement.in_degrees]
        keys += [c for c in CONDITIONS.values() if c.of is requirement]
    for condition in CONDITIONS.values():
        if condition.of is None:
            keys += [condition] + ([] if condition.in_degrees is None else [condition.in_degrees])
    return tuple(keys)


def condition_keys() -> dict[str, ConditionSpec]:
    """Every key of the table that is no requirement: the conditions and the keys in degrees."""
    return {key.name: key for key in table_keys() if isinstance(key, ConditionSpec)}


def degree_keys() -> dict[str, RequirementSpec | ConditionSpec]:
    """Keys giving a key in degrees, and that key: ``{"slope_deg": SLOPE, ...}``."""
    return {
        key.name: key.gives
        for key in condition_keys().values()
        if key.kind == "degrees" and key.gives is not None
    }
