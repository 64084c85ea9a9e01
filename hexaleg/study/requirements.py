"""What the robot must do: the requirements a decision meets, and how each is checked.

Each requirement is optional and has the same name in a design file's ``[requirements]``
table, on the command line (``--payload``, ``--slope``, ...) and in JSON:

- ``payload`` [kg] carried at ``payload_at`` (body frame [m]; default the centre of the
  body's top face): the largest payload the nominal stance holds with every joint
  torque within its rating and the centre of mass over the support polygon — on level
  ground, and on every slope up to ``slope`` in every heading when a slope is required;
- ``slope`` [rad] (``slope_deg`` [°] in files and ``--slope-deg``): the steepest slope the
  robot stands on, uphill in every heading, carrying ``payload`` — the first slope where
  it tips, slides (tan α > μ) or a joint torque reaches its rating
  (:mod:`hexaleg.study.standing`);
- ``ground_clearance`` [m]: the body's underside above the ground at the nominal stance;
- ``min_fb`` [-]: the axis-locked body flexibility FB (eq 29) at least this;
- ``leg_length`` [m]: l1 + l2 + l3 at most this (default: the design's own);
- ``min_coxa`` [m]: l1 at least this (what the root actuator's packaging needs);
- ``speed`` [m/s]: the fastest a tripod gait of the default stride
  (:class:`~hexaleg.gait.spec.Gait`), lifting its feet ``step_height`` [m] (a condition of
  it, like ``payload_at`` of the payload) and carrying the payload when one is required,
  walks with every peak joint torque and joint speed within its rating and every
  constraint of the period kept (:func:`~hexaleg.gait.limits.max_speed`; zero if that
  stride cannot be walked at all) — at least this. :attr:`Requirements.gait` is that
  gait at the required speed.

The ratings are the design's ``rated_torques`` and ``rated_speeds``. A requirement's
*margin* is how far its value is on the good side of the required one, in its own unit
(negative: not met); it *binds* a design that meets it within :data:`BINDING_SHARE` of
the required value. Every check says what limits its value: the constraint an analysis
stops at (a :class:`~hexaleg.cause.Cause`: a joint at its rated torque, tipping, ...),
or, for a value that is the design's own geometry, :attr:`RequirementKind.reason`.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any, Literal

from hexaleg._checks import require_finite, require_in_range
from hexaleg.cause import Cause
from hexaleg.design import SEGMENT_RANGE, HexapodDesign
from hexaleg.exceptions import ParameterError
from hexaleg.gait.spec import Gait
from hexaleg.statics.forces import PAYLOAD_REACH, PAYLOAD_SEARCH_LIMIT

Sense = Literal["at least", "at most"]
"""Which side of the required value meets a requirement."""

BINDING_SHARE = 0.01
"""A met requirement binds when its margin is within this share of the required value."""


@dataclass(frozen=True)
class RequirementKind:
    """One kind of requirement: what it limits and how.

    Attributes:
        name: Its key in files, JSON and (with dashes) on the command line.
        metric: The design metric it limits (:mod:`hexaleg.study.evaluation`).
        sense: ``"at least"`` or ``"at most"``.
        unit: Its unit.
        bounds: The plausible required values, inclusive [unit].
        text: What it asks, in a few words.
        reason: What sets its value when no analysis stops at a constraint (the
            design's own geometry).

    """

    name: str
    metric: str
    sense: Sense
    unit: str
    bounds: tuple[float, float]
    text: str
    reason: str

    def margin(self, required: float, value: float) -> float:
        """How far ``value`` is on the good side of ``required`` [unit] (< 0: not met)."""
        return value - required if self.sense == "at least" else required - value

    def binds(self, required: float, margin: float) -> bool:
        """Whether a design meeting it with ``margin`` sits on it."""
        return 0 <= margin <= BINDING_SHARE * max(abs(required), 1e-12)


KINDS: dict[str, RequirementKind] = {
    kind.name: kind
    for kind in (
        RequirementKind("payload", "payload", "at least", "kg", (0.0, PAYLOAD_SEARCH_LIMIT),
                        "payload carried at payload_at", "the statics"),
        RequirementKind("slope", "slope", "at least", "rad", (0.0, math.pi / 2),
                        "slope stood on in every heading, with the payload", "the statics"),
        RequirementKind("ground_clearance", "ground_clearance", "at least", "m", (0.0, 100.0),
                        "body underside above the ground at the nominal stance",
                        "geometry: the tibia, femur and nominal posture"),
        RequirementKind("min_fb", "fb", "at least", "1", (0.0, 10.0),
                        "axis-locked body flexibility FB (eq 29)",
                        "geometry: twelve extremes, each stopped by its own constraint"),
        RequirementKind("leg_length", "leg_length", "at most", "m",
                        (3 * SEGMENT_RANGE[0], SEGMENT_RANGE[1]), "l1 + l2 + l3",
                        "geometry: the design's l1 + l2 + l3"),
        RequirementKind("min_coxa", "coxa", "at least", "m", SEGMENT_RANGE, "coxa length l1",
                        "geometry: the design's coxa length l1"),
        RequirementKind("speed", "speed", "at least", "m/s", (0.0, 100.0),
                        "tripod gait speed within the ratings", "the gait"),
    )
}  # fmt: skip
"""Every requirement, in the order the answer lists them."""

DEGREE_KEYS = {"slope_deg": "slope"}
"""Keys that give a requirement in degrees instead of radians."""

POSITION_KEY = "payload_at"
"""Where the payload sits, body frame (x, y, z) [m]: a condition, not a requirement."""

STEP_KEY = "step_height"
"""How high the gait of the ``speed`` requirement lifts its feet [m]: a condition of it."""

STEP_BOUNDS = (0.0, 10.0)
"""Plausible step heights [m]."""


@dataclass(frozen=True)
class Requirements:
    """What the robot must do; every requirement is optional (``None``: not required).

    Attributes:
        payload: Payload carried [kg].
        payload_at: Where it sits, body frame [m]; ``None``: the centre of the top face.
        slope: Slope stood on in every heading, carrying the payload [rad].
        ground_clearance: Body underside above the ground at the nominal stance [m].
        min_fb: Least axis-locked FB [-].
        leg_length: Largest l1 + l2 + l3 [m]; ``None``: the design's own (:meth:`resolved`).
        min_coxa: Least coxa length l1 [m].
        speed: Tripod gait speed within the ratings [m/s].
        step_height: Step height of that gait [m] (the gait's default if omitted).

    """

    payload: float | None = None
    payload_at: tuple[float, float, float] | None = None
    slope: float | None = None
    ground_clearance: float | None = None
    min_fb: float | None = None
    leg_length: float | None = None
    min_coxa: float | None = None
    speed: float | None = None
    step_height: float | None = None

    def __post_init__(self) -> None:
        for name, kind in KINDS.items():
            value = getattr(self, name)
            if value is not None:
                checked = require_in_range(name, value, *kind.bounds, kind.unit)
                if checked <= 0 and name not in ("payload", "slope"):
                    raise ParameterError(name, value, f"must be positive [{kind.unit}]")
                object.__setattr__(self, name, checked)
        if self.slope is not None and self.slope >= math.pi / 2:
            raise ParameterError("slope", self.slope, "must be less than π/2 [rad]")
        if self.payload_at is not None:
            object.__setattr__(self, "payload_at", _position(self.payload_at))
        if self.payload_at is not None and self.payload is None:
            raise ParameterError(POSITION_KEY, self.payload_at, "needs a payload [kg] to place")
        if self.step_height is not None:
            height = require_in_range(STEP_KEY, self.step_height, *STEP_BOUNDS, "m")
            if height <= 0 or self.speed is None:
                raise ParameterError(STEP_KEY, height, "needs a speed [m/s] to walk at; > 0 [m]")
            object.__setattr__(self, STEP_KEY, height)
        if self.speed is not None:
            _ = self.gait  # its period must lie in the gait's range (ParameterError "speed")

    # -- construction -------------------------------------------------------------------

    @classmethod
    def from_table(cls, table: Mapping[str, Any], source: str = "requirements") -> Requirements:
        """The requirements of a design file's ``[requirements]`` table.

        Args:
            table: Keys as the fields' names (``slope_deg`` [°] for ``slope``).
            source: Where the table comes from, for error messages.

        Raises:
            ParameterError: an unknown key, or a value of the wrong type or out of its range,
                its field named ``<source>.<key>``.

        """
        if not isinstance(table, Mapping):
            raise ParameterError(source, table, "must be a table of requirement keys")
        known = (*KINDS, POSITION_KEY, STEP_KEY, *DEGREE_KEYS)
        values: dict[str, Any] = {}
        for key, raw in table.items():
            field = f"{source}.{key}"
            if not isinstance(key, str):
                raise ParameterError(field, raw, "keys must be requirement names (text)")
            if key not in known:
                close = difflib.get_close_matches(key, known, n=1)
                hint = f"did you mean {close[0]!r}?" if close else "known: " + ", ".join(known)
                raise ParameterError(field, raw, f"unknown requirement; {hint}")
            if key == POSITION_KEY:
                values[key] = _position(raw, field)
            elif key in DEGREE_KEYS:
                if DEGREE_KEYS[key] in table:
                    raise ParameterError(
                        field, raw, "give the slope in radians or degrees, not both"
                    )
                values[DEGREE_KEYS[key]] = math.radians(require_in_range(field, raw, 0, 90, "°"))
            else:
                values[key] = require_finite(field, raw)
        try:
            return cls(**values)
        except ParameterError as err:
            raise ParameterError(f"{source}.{err.field}", err.value, err.allowed) from None

    def replace(self, **changes: Any) -> Requirements:
        """Copy with some requirements changed (validated again)."""
        return replace(self, **changes)

    def resolved(self, design: HexapodDesign) -> Requirements:
        """These requirements with the defaults filled in from ``design`` (its leg length)."""
        if self.leg_length is not None:
            return self
        return self.replace(leg_length=design.leg_length)

    # -- queries ------------------------------------------------------------------------

    @property
    def given(self) -> tuple[str, ...]:
        """Names of the requirements set, in :data:`KINDS` order."""
        return tuple(name for name in KINDS if getattr(self, name) is not None)

    @property
    def payload_mass(self) -> float:
        """The payload to carry [kg] (0 when none is required)."""
        return self.payload or 0.0

    @property
    def needs_gait(self) -> bool:
        """Whether a walking requirement is set."""
        return self.speed is not None

    @property
    def gait(self) -> Gait:
        """The gait every design walks: :class:`~hexaleg.gait.spec.Gait`'s tripod and stride.

        It lifts ``step_height`` and walks at the required ``speed`` (the gait's own
        speed without one).
        """
        gait = Gait() if self.step_height is None else Gait(step_height=self.step_height)
        return gait if self.speed is None else gait.with_speed(self.speed)

    def walking_conditions(self) -> str:
        """The gait's conditions in words: ``tripod, stride 0.3 m, step height 0.1 m, …``."""
        gait = self.gait
        carrying = f"carrying {self.payload:g} kg" if self.payload else "no payload"
        return (
            f"{gait.pattern}, stride {gait.stride:g} m, step height {gait.step_height:g} m, "
            f"{carrying}"
        )

    def to_dict(self) -> dict[str, Any]:
        """The requirements set, JSON-ready (SI units, radians)."""
        out = {name: getattr(self, name) for name in self.given}
        if self.payload_at is not None:
            out[POSITION_KEY] = list(self.payload_at)
        if self.step_height is not None:
            out[STEP_KEY] = self.step_height
        return out

    def describe(self, name: str) -> str:
        """``name``'s requirement in words, with its condition: ``payload ≥ 30 kg (on 15°)``."""
        sign = "≥" if KINDS[name].sense == "at least" else "≤"
        text = f"{name} {sign} {format_value(name, getattr(self, name))}"
        if name == "payload" and self.slope is not None:
            text += f" (on every slope up to {math.degrees(self.slope):.3g}°)"
        elif name == "slope" and self.payload is not None:
            text += f" (carrying {self.payload:g} kg)"
        elif name == "speed":
            text += f" ({self.walking_conditions()})"
        return text


def format_value(name: str, value: float) -> str:
    """A requirement's value with its unit; slopes also in degrees."""
    kind = KINDS[name]
    if kind.unit == "rad":
        return f"{value:.4g} rad ({math.degrees(value):.3g}°)"
    if kind.unit == "1":
        return f"{value:.4g}"
    return f"{value:.4g} {kind.unit}"


def format_margin(check: RequirementCheck) -> str:
    """A check's margin, signed, with its unit; below 10⁻⁴ of the required value, ``±0``."""
    kind = KINDS[check.name]
    tiny = abs(check.margin) < 1e-4 * max(abs(check.required), 1e-9)
    text = ("−0" if check.margin < 0 else "+0") if tiny else f"{check.margin:+.4g}"
    return text if kind.unit == "1" else f"{text} {kind.unit}"


@dataclass(frozen=True)
class RequirementCheck:
    """One requirement checked on one design.

    Attributes:
        name: The requirement.
        required: The required value [its unit].
        value: The design's value [its unit].
        margin: How far the value is on the good side [its unit] (< 0: not met).
        limited_by: What limits the value: the constraint an analysis stopped at, or
            the requirement's :attr:`~RequirementKind.reason`.

    """

    name: str
    required: float
    value: float
    margin: float
    limited_by: Cause | str

    @property
    def met(self) -> bool:
        """Whether the design meets it."""
        return self.margin >= 0

    @property
    def binds(self) -> bool:
        """Whether the design meets it with almost no margin to spare."""
        return KINDS[self.name].binds(self.required, self.margin)

    def to_dict(self, binding: bool) -> dict[str, Any]:
        """JSON-ready: ``binds`` for the best design, ``met`` for the user's."""
        out: dict[str, Any] = {"required": self.required, "value": self.value,
                               "margin": self.margin}  # fmt: skip
        out |= {"binds": self.binds} if binding else {"met": self.met}
        return out | {"limited_by": limited_by_dict(self.limited_by)}


def limited_by_dict(limited_by: Cause | str) -> dict[str, Any]:
    """What limits a value, JSON-ready: a cause's fields, or a reason; ``description`` always."""
    if isinstance(limited_by, Cause):
        return limited_by.to_dict()
    return {"kind": "design", "description": limited_by}


def check(requirements: Requirements, values: Mapping[str, float],
          causes: Mapping[str, Cause]) -> tuple[RequirementCheck, ...]:  # fmt: skip
    """Each given requirement against a design's metric ``values`` (and what limits them)."""
    checks = []
    for name in requirements.given:
        kind, required = KINDS[name], float(getattr(requirements, name))
        value = float(values[kind.metric])
        checks.append(RequirementCheck(name, required, value, kind.margin(required, value),
                                       causes.get(kind.metric, kind.reason)))  # fmt: skip
    return tuple(checks)


def _position(value: Any, field: str = POSITION_KEY) -> tuple[float, float, float]:
    if isinstance(value, str) or not hasattr(value, "__len__") or len(value) != 3:
        raise ParameterError(field, value, "must be three coordinates x, y, z, body frame [m]")
    x, y, z = (require_in_range(field, v, -PAYLOAD_REACH, PAYLOAD_REACH, "m") for v in value)
    return (x, y, z)
