"""What the robot must do: the requirements a decision meets, and how each is checked.

Each requirement (:mod:`~hexaleg.evaluation.requirement_specs`: what it bounds, its range,
option and key) is optional and has the same name in a design file's ``[requirements]``
table, on the command line (``--payload``, ``--slope``, ...) and in JSON. A
:class:`Requirements` holds the values given, each checked against its declaration.

A requirement's *margin* is how far its value is on the good side of the required one,
in its own unit (negative: not met); it *binds* a design that meets it within
:data:`~.requirement_specs.BINDING_SHARE` of the required value. Every check says what
limits its value: the constraint an analysis stops at (a :class:`~hexaleg.cause.Cause`:
a joint at its rated torque, tipping, ...), or, for a value that is the design's own
geometry, :attr:`~.requirement_specs.RequirementSpec.reason`.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from hexaleg._checks import require_finite, require_in_range
from hexaleg.cause import Cause
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.metrics import Causes, Metrics
from hexaleg.evaluation.requirement_specs import (
    CONDITIONS,
    LEG_LENGTH,
    MOTOR_SAFETY_FACTOR,
    PAYLOAD,
    PAYLOAD_AT,
    REQUIREMENTS,
    SLOPE,
    SPEED,
    STEP_HEIGHT,
    STRUCTURE,
    WALKING_SLOPE,
    ConditionSpec,
    RequirementSpec,
    condition_keys,
    degree_keys,
    table_keys,
)
from hexaleg.exceptions import ParameterError
from hexaleg.gait.spec import Gait

Position = tuple[float, float, float]
"""A point in the body frame [m]."""


@dataclass(frozen=True, init=False)
class Requirements:
    """What the robot must do: each requirement optional, each checked by its declaration.

    ``Requirements(payload=30, slope=0.2, payload_at=(0.1, 0, 0.05))``: a keyword per
    requirement or condition given, by its declared name
    (:data:`~.requirement_specs.REQUIREMENTS`, :data:`~.requirement_specs.CONDITIONS`;
    ``None``: not required); read back with :meth:`required` and :meth:`condition`.

    Attributes:
        values: Each requirement and condition given, by name, in the table's order [its
            unit; a position as three coordinates].
        walked: The gait walked before the speed and step height apply: the design file's
            ``[gait]`` table, else the default gait (not a requirement: what it is
            measured walking).

    """

    values: tuple[tuple[str, float | Position], ...]
    walked: Gait

    def __init__(self, walked: Gait | None = None, **given: Any) -> None:
        keys = {key.name: key for key in table_keys() if key.name not in degree_keys()}
        keys |= {spec.name: spec for spec in REQUIREMENTS.values() if spec.implied}
        unknown = [name for name in given if name not in keys]
        if unknown:
            raise ParameterError(unknown[0], given[unknown[0]], "no requirement of that name")
        checked: dict[str, float | Position] = {
            name: _checked(REQUIREMENTS[name], value)
            for name, value in given.items()
            if name in REQUIREMENTS and value is not None
        }
        for name, value in given.items():
            if name in CONDITIONS and value is not None:
                checked[name] = _condition(CONDITIONS[name], value, checked)
        ordered = [(name, checked[name]) for name in keys if name in checked]
        object.__setattr__(self, "values", tuple(ordered))
        object.__setattr__(self, "walked", Gait() if walked is None else walked)
        if self.required(SPEED) is not None:
            _ = self.gait  # its period must lie in the gait's range (ParameterError "speed")

    # -- construction -------------------------------------------------------------------

    @classmethod
    def from_table(cls, table: Mapping[str, Any], source: str = "requirements") -> Requirements:
        """The requirements of a design file's ``[requirements]`` table.

        Args:
            table: Keys as the requirements' and conditions' names (``slope_deg`` [°] for
                ``slope``).
            source: Where the table comes from, for error messages.

        Raises:
            ParameterError: an unknown key, or a value of the wrong type or out of its range,
                its field named ``<source>.<key>``.

        """
        if not isinstance(table, Mapping):
            raise ParameterError(source, table, "must be a table of requirement keys")
        known = tuple(spec.name for spec in table_keys())
        degrees, conditions = degree_keys(), condition_keys()
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
                name = degrees[key].name
                if name in table:
                    raise ParameterError(
                        field, raw, f"give the {name} in radians or degrees, not both"
                    )
                values[name] = math.radians(condition_value(conditions[key], raw, field))
            elif key in conditions:
                values[key] = condition_value(conditions[key], raw, field)
            else:
                values[key] = require_finite(field, raw)
        try:
            return cls(**values)
        except ParameterError as err:
            raise ParameterError(f"{source}.{err.field}", err.value, err.allowed) from None

    def replace(self, **changes: Any) -> Requirements:
        """Copy with some requirements or conditions changed (``None`` drops one), checked again."""
        return Requirements(self.walked, **(dict(self.values) | changes))

    def walking(self, gait: Gait) -> Requirements:
        """The same requirements, walking ``gait`` (:attr:`walked`)."""
        return Requirements(gait, **dict(self.values))

    def resolved(self, design: HexapodDesign) -> Requirements:
        """These requirements with what ``design`` sets filled in.

        The leg length, if not given: the design's. The legs' tubes hold
        (:data:`~.requirement_specs.STRUCTURE`), if the design's ``[structure]`` sizes them
        or gives every one.
        """
        changes: dict[str, float] = {}
        if self.required(LEG_LENGTH) is None:
            changes[LEG_LENGTH.name] = design.leg_length
        structure = design.structure
        if structure is not None and (structure.size or None not in structure.tubes):
            changes[STRUCTURE.name] = STRUCTURE.bounds[1]
        return self.replace(**changes) if changes else self

    # -- queries ------------------------------------------------------------------------

    def required(self, spec: RequirementSpec) -> float | None:
        """The required value of ``spec`` [its unit]; ``None``: not required."""
        value = dict(self.values).get(spec.name)
        return None if value is None else float(value)  # type: ignore[arg-type]

    def condition(self, spec: ConditionSpec) -> float | Position | None:
        """The value of condition ``spec``; ``None``: not given (its default applies)."""
        return dict(self.values).get(spec.name)

    @property
    def given(self) -> tuple[str, ...]:
        """Names of the requirements set, in :data:`~.requirement_specs.REQUIREMENTS` order."""
        return tuple(name for name, _ in self.values if name in REQUIREMENTS)

    @property
    def payload_mass(self) -> float:
        """The payload to carry [kg] (0 when none is required)."""
        return self.required(PAYLOAD) or 0.0

    @property
    def payload_at(self) -> Position | None:
        """Where the payload sits, body frame [m]; ``None``: the centre of the top face."""
        value = self.condition(PAYLOAD_AT)
        return value if isinstance(value, tuple) else None

    @property
    def walking_slope(self) -> float:
        """The slope walked uphill, downhill and across [rad] (0: level ground)."""
        value = self.condition(WALKING_SLOPE)
        return float(value) if isinstance(value, float) else 0.0

    @property
    def motor_safety_factor(self) -> float:
        """The motors' safety factor F [-] (1 unless given)."""
        value = self.condition(MOTOR_SAFETY_FACTOR)
        return float(value) if isinstance(value, float) else 1.0

    @property
    def needs_gait(self) -> bool:
        """Whether a walking requirement is set."""
        return self.required(SPEED) is not None

    @property
    def gait(self) -> Gait:
        """The gait every design walks: :attr:`walked` (the design file's ``[gait]``).

        It lifts the required step height and walks at the required speed where they are
        given (the ``[gait]`` table's, else the default gait's, without them).
        """
        gait, step, speed = self.walked, self.condition(STEP_HEIGHT), self.required(SPEED)
        gait = gait if not isinstance(step, float) else gait.replace(step_height=step)
        return gait if speed is None else gait.with_speed(speed)

    def walking_conditions(self) -> str:
        """The gait's conditions in words: ``tripod, stride 0.3 m, step height 0.1 m, …``.

        With the slope walked (up, down and across it) and the motors' safety factor, if
        given.
        """
        gait = self.gait
        carrying = f"carrying {self.payload_mass:g} kg" if self.payload_mass else "no payload"
        text = (
            f"{gait.pattern}, stride {gait.stride:g} m, step height {gait.step_height:g} m, "
            f"{carrying}"
        )
        if self.walking_slope:
            text += f", up, down and across a {math.degrees(self.walking_slope):.3g}° slope"
        if self.motor_safety_factor != 1:
            text += f", within ratings / {self.motor_safety_factor:g}"
        return text

    def to_dict(self) -> dict[str, Any]:
        """The requirements and conditions set, JSON-ready (SI units, radians)."""
        return {
            name: list(value) if isinstance(value, tuple) else value for name, value in self.values
        }

    def describe(self, name: str) -> str:
        """``name``'s requirement in words, with its condition: ``payload ≥ 30 kg (on 15°)``."""
        spec = REQUIREMENTS[name]
        sign = "≥" if spec.sense == "at least" else "≤"
        text = f"{name} {sign} {format_value(name, float(self.required(spec) or 0.0))}"
        slope = self.required(SLOPE)
        if spec is PAYLOAD and slope is not None:
            text += f" (on every slope up to {math.degrees(slope):.3g}°)"
        elif spec is SLOPE and self.required(PAYLOAD) is not None:
            text += f" (carrying {self.payload_mass:g} kg)"
        elif spec is SPEED:
            text += f" ({self.walking_conditions()})"
        return text


def _checked(spec: RequirementSpec, value: Any) -> float:
    """A required value within its declaration's bounds (positive unless zero may be)."""
    checked = require_in_range(spec.name, value, *spec.bounds, spec.unit)
    if checked <= 0 and not spec.zero:
        raise ParameterError(spec.name, value, f"must be positive [{spec.unit}]")
    if spec.below and checked >= spec.bounds[1]:
        raise ParameterError(
            spec.name, value, f"must be less than {spec.metric.format(spec.bounds[1])}"
        )
    return checked


def _condition(
    spec: ConditionSpec, value: Any, required: Mapping[str, float | Position]
) -> float | Position:
    """A condition's value checked, refused when none of its requirements is given.

    A condition of every requirement (``of`` ``None``) is never alone.
    """
    checked = condition_value(spec, value)
    owners = () if spec.of is None else (spec.of, *spec.also)
    lonely = bool(owners) and all(owner.name not in required for owner in owners)
    zero = spec.kind == "number" and isinstance(checked, float) and checked <= 0
    if lonely or (zero and not spec.zero):
        raise ParameterError(spec.name, value, spec.needs)
    return checked


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
        """Whether the design meets it (to :data:`~.requirement_specs.ROUNDOFF`)."""
        return REQUIREMENTS[self.name].met(self.required, self.margin)

    @property
    def binds(self) -> bool:
        """Whether the design meets it with almost no margin to spare."""
        return REQUIREMENTS[self.name].binds(self.required, self.margin)

    @property
    def at_limit(self) -> bool:
        """Whether it binds with no margin left to speak of (within 0.5 % of the limit)."""
        return REQUIREMENTS[self.name].at_limit(self.required, self.margin)

    def to_dict(self, binding: bool) -> dict[str, Any]:
        """JSON-ready: ``binds`` and ``at_limit`` for the best design, ``met`` for the user's."""
        out: dict[str, Any] = {
            "required": self.required,
            "value": self.value,
            "margin": self.margin,
        }
        out |= {"binds": self.binds, "at_limit": self.at_limit} if binding else {"met": self.met}
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
        spec = REQUIREMENTS[name]
        required, value = float(requirements.required(spec) or 0.0), metrics.value(spec.metric)
        limited_by = causes[spec.metric] or spec.reason
        checks.append(
            RequirementCheck(name, required, value, spec.margin(required, value), limited_by)
        )
    return tuple(checks)


def condition_value(spec: ConditionSpec, value: Any, field: str | None = None) -> Any:
    """A condition's value checked against its declaration (a tuple for a position)."""
    field = field or spec.name
    if spec.kind != "position":
        return require_in_range(field, value, *spec.bounds, spec.unit)
    if isinstance(value, str) or not hasattr(value, "__len__") or len(value) != 3:
        raise ParameterError(field, value, "must be three coordinates x, y, z, body frame [m]")
    x, y, z = (require_in_range(field, v, *spec.bounds, spec.unit) for v in value)
    return (x, y, z)
