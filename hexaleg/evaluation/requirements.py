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
  (:mod:`hexaleg.statics.standing_limits`);
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
  gait at the required speed;
- ``walking_payload`` [kg]: the largest payload at ``payload_at`` carried walking that gait
  with every joint within its ratings and the ZMP inside the standing feet
  (:mod:`hexaleg.gait.capacity`) — at least this;
- ``range_km`` [km]: the distance that gait walks on one charge of the design's
  ``[battery]``, through its ``[actuators]`` (:mod:`hexaleg.electrical`) — at least this;
- ``continuous_margin`` [-]: every joint's RMS torque over that gait period as a share of
  its actuator's continuous torque — at most this.

The ratings are the design's ``rated_torques`` and ``rated_speeds``. A requirement's
*margin* is how far its value is on the good side of the required one, in its own unit
(negative: not met); it *binds* a design that meets it within :data:`BINDING_SHARE` of
the required value. Every check says what limits its value: the constraint an analysis
stops at (a :class:`~hexaleg.cause.Cause`: a joint at its rated torque, tipping, ...),
or, for a value that is the design's own geometry,
:attr:`~.requirement_specs.RequirementSpec.reason`.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from dataclasses import field as dataclass_field
from typing import Any

from hexaleg._checks import require_finite, require_in_range
from hexaleg.cause import Cause
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.metrics import Causes, Metrics
from hexaleg.evaluation.requirement_specs import CONDITIONS, REQUIREMENTS, degree_keys, table_keys
from hexaleg.exceptions import ParameterError
from hexaleg.gait.spec import Gait


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
        walking_payload: Payload carried at ``payload_at`` walking that gait within every
            rating [kg].
        range_km: Distance walked on one charge of the design's battery [km].
        continuous_margin: Largest share of its continuous torque any joint's RMS torque
            may be walking the gait [-].
        walked: The gait walked before ``speed`` and ``step_height`` apply: the design
            file's ``[gait]`` table, else the default gait (not a requirement: what it
            is measured walking).

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
    walking_payload: float | None = None
    range_km: float | None = None
    continuous_margin: float | None = None
    walked: Gait = dataclass_field(default_factory=Gait)

    def __post_init__(self) -> None:
        for name, spec in REQUIREMENTS.items():
            value = getattr(self, name)
            if value is not None:
                checked = require_in_range(name, value, *spec.bounds, spec.unit)
                if checked <= 0 and not spec.zero:
                    raise ParameterError(name, value, f"must be positive [{spec.unit}]")
                object.__setattr__(self, name, checked)
        if self.slope is not None and self.slope >= math.pi / 2:
            raise ParameterError("slope", self.slope, "must be less than π/2 [rad]")
        for condition in CONDITIONS.values():
            value = getattr(self, condition.name, None)
            if value is None or not condition.needs:
                continue
            value = condition_value(condition.name, value)
            owners = (condition.of, *condition.also)
            if all(getattr(self, name) is None for name in owners) or (
                condition.kind == "number" and value <= 0
            ):
                raise ParameterError(condition.name, value, condition.needs)
            object.__setattr__(self, condition.name, value)
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
        known = tuple(spec.name for spec in table_keys())
        degrees = degree_keys()
        values: dict[str, Any] = {}
        for key, raw in table.items():
            field = f"{source}.{key}"
            if not isinstance(key, str):
                raise ParameterError(field, raw, "keys must be requirement names (text)")
            if key not in known:
                close = difflib.get_close_matches(str(key), known, n=1)
                hint = f"did you mean {close[0]!r}?" if close else "known: " + ", ".join(known)
                raise ParameterError(field, raw, f"unknown requirement; {hint}")
            if key in degrees:
                if degrees[key] in table:
                    raise ParameterError(
                        field, raw, f"give the {degrees[key]} in radians or degrees, not both"
                    )
                values[degrees[key]] = math.radians(condition_value(key, raw, field))
            elif key in CONDITIONS:
                values[key] = condition_value(key, raw, field)
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
        """Names of the requirements set, in :data:`REQUIREMENTS` order."""
        return tuple(name for name in REQUIREMENTS if getattr(self, name) is not None)

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
        """The gait every design walks: :attr:`walked` (the design file's ``[gait]``).

        It lifts ``step_height`` and walks at the required ``speed`` where they are given
        (the ``[gait]`` table's, else the default gait's, without them).
        """
        gait = self.walked
        gait = gait if self.step_height is None else gait.replace(step_height=self.step_height)
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
        for name in CONDITIONS:
            value = getattr(self, name, None)
            if value is not None:
                out[name] = list(value) if isinstance(value, tuple) else value
        return out

    def describe(self, name: str) -> str:
        """``name``'s requirement in words, with its condition: ``payload ≥ 30 kg (on 15°)``."""
        sign = "≥" if REQUIREMENTS[name].sense == "at least" else "≤"
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
    return REQUIREMENTS[name].metric.format(value)


def format_margin(check: RequirementCheck) -> str:
    """A check's margin, signed, with its unit; below 10⁻⁴ of the required value, ``±0``."""
    unit = REQUIREMENTS[check.name].unit
    tiny = abs(check.margin) < 1e-4 * max(abs(check.required), 1e-9)
    text = ("−0" if check.margin < 0 else "+0") if tiny else f"{check.margin:+.4g}"
    return text if unit == "1" else f"{text} {unit}"


@dataclass(frozen=True)
class RequirementCheck:
    """One requirement checked on one design.

    Attributes:
        name: The requirement.
        required: The required value [its unit].
        value: The design's value [its unit].
        margin: How far the value is on the good side [its unit] (< 0: not met).
        limited_by: What limits the value: the constraint an analysis stopped at, or
            the requirement's :attr:`~.requirement_specs.RequirementSpec.reason`.

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
        return REQUIREMENTS[self.name].binds(self.required, self.margin)

    def to_dict(self, binding: bool) -> dict[str, Any]:
        """JSON-ready: ``binds`` for the best design, ``met`` for the user's."""
        out: dict[str, Any] = {
            "required": self.required,
            "value": self.value,
            "margin": self.margin,
        }
        out |= {"binds": self.binds} if binding else {"met": self.met}
        return out | {"limited_by": limited_by_dict(self.limited_by)}


def limited_by_dict(limited_by: Cause | str) -> dict[str, Any]:
    """What limits a value, JSON-ready: a cause's fields, or a reason; ``description`` always."""
    if isinstance(limited_by, Cause):
        return limited_by.to_dict()
    return {"kind": "design", "description": limited_by}


def check(
    requirements: Requirements, metrics: Metrics, causes: Causes
) -> tuple[RequirementCheck, ...]:
    """Each given requirement against a design's ``metrics`` (and what limits them)."""
    checks = []
    for name in requirements.given:
        spec, required = REQUIREMENTS[name], float(getattr(requirements, name))
        value = metrics.value(spec.metric)
        limited_by = causes[spec.metric] or spec.reason
        checks.append(
            RequirementCheck(name, required, value, spec.margin(required, value), limited_by)
        )
    return tuple(checks)


def condition_value(name: str, value: Any, field: str | None = None) -> Any:
    """A condition's value checked against its declaration (a tuple for a position)."""
    spec, field = CONDITIONS[name], field or name
    if spec.kind != "position":
        return require_in_range(field, value, *spec.bounds, spec.unit)
    if isinstance(value, str) or not hasattr(value, "__len__") or len(value) != 3:
        raise ParameterError(field, value, "must be three coordinates x, y, z, body frame [m]")
    x, y, z = (require_in_range(field, v, *spec.bounds, spec.unit) for v in value)
    return (x, y, z)
