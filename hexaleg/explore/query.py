"""What one explorer request asks for: a design and the conditions it is measured under.

A query names any design field by its key in a design file (``l1=0.25``,
``body_width=0.7``, a triple as three comma-separated numbers:
``nominal_angles=0,0.1,-1.5``) and the conditions the sliders set: the payload
(``payload`` [kg], ``payload_at`` = x,y,z in the body frame [m]) and the gait's
``speed`` [m/s], ``stride`` [m] and ``step_height`` [m]. ``actuators.root``, ``actuators.hip`` and
``actuators.knee`` choose each joint type's motor by its catalog name (``hexaleg
actuators``), as ``catalog = "NAME"`` does in a design file; empty values take the
motors away (the ratings they gave kept, no motor model); a joint type not named keeps
the loaded design's motor. Every value is checked by its declaration; a bad one is a
:class:`~hexaleg.exceptions.ParameterError` naming the key and its range.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from hexaleg.actuator_catalog import shipped_catalog
from hexaleg.actuators import REFERENCE_TEMPERATURE, TABLE, Actuator, Actuators
from hexaleg.design import DESIGN_FIELDS, HexapodDesign
from hexaleg.evaluation.evaluate import Conditions
from hexaleg.exceptions import ParameterError
from hexaleg.limits import LEG_JOINTS
from hexaleg.statics.forces import PAYLOAD_REACH, Payload

__all__ = ["ACTUATOR_KEYS", "CONDITION_KEYS", "DESIGN_KEYS", "Query", "parse_query"]

DESIGN_KEYS: dict[str, Any] = {
    spec.key: spec for spec in DESIGN_FIELDS if spec.kind in ("number", "triple", "choice")
}
"""Design fields a query may set, by their design-file key."""

CONDITION_KEYS: dict[str, str] = {
    "payload": "payload mass [kg]",
    "payload_at": f"payload position x,y,z in the body frame, each in ±{PAYLOAD_REACH:g} [m]",
    "speed": "gait speed [m/s] (the stride kept, the period set)",
    "stride": "gait stride [m] (the period kept; with speed, the speed kept)",
    "step_height": "gait step height [m]",
}
"""The conditions a query may set, with what each is."""

ACTUATOR_KEYS: dict[str, str] = {f"{TABLE}.{joint}": joint for joint in LEG_JOINTS}
"""The keys choosing each joint type's motor from the catalog, with their joint type."""


@dataclass(frozen=True)
class Query:
    """One explorer request, checked.

    Attributes:
        design: The design asked about.
        conditions: What it is measured under.

    """

    design: HexapodDesign
    conditions: Conditions


def parse_query(params: Mapping[str, str], base: HexapodDesign, conditions: Conditions) -> Query:
    """The design and conditions of ``params`` (one text value per key) on top of ``base``.

    Args:
        params: Query keys and their values as text.
        base: The design the keys change (the loaded one).
        conditions: The conditions the keys change (the loaded ones).

    Raises:
        ParameterError: An unknown key, or a value out of its field's range.

    """
    known = (*DESIGN_KEYS, *CONDITION_KEYS, *ACTUATOR_KEYS)
    unknown = [key for key in params if key not in known]
    if unknown:
        raise ParameterError(
            unknown[0], params[unknown[0]], f"unknown key: known are {', '.join(known)}"
        )
    changes = {key: _field(key, text) for key, text in params.items() if key in DESIGN_KEYS}
    if any(key in params for key in ACTUATOR_KEYS):
        changes["actuators"] = _actuators(params, base.actuators)
    design = base.replace(**changes) if changes else base
    return Query(design, _conditions(params, conditions))


def _field(key: str, text: str) -> Any:
    """A design field's value from text, checked by its declaration."""
    spec = DESIGN_KEYS[key]
    if spec.kind == "choice":
        return text
    if spec.kind == "triple":
        return spec.check(tuple(_number(f"{key}.{item}", part, spec.unit)
                                for item, part in _three(key, text, spec.items)))  # fmt: skip
    return spec.check(_number(key, text, spec.unit, spec.bounds))


def _actuators(params: Mapping[str, str], loaded: Actuators | None) -> Actuators | None:
    """The motors a query chooses: catalog names, empty for none, the loaded ones kept."""
    chosen: dict[str, Actuator | None] = {}
    for key, joint in ACTUATOR_KEYS.items():
        if key not in params:
            chosen[joint] = None if loaded is None else getattr(loaded, joint)
        elif params[key].strip():
            chosen[joint] = shipped_catalog().entry(params[key].strip(), key).actuator
        else:
            chosen[joint] = None
    if all(actuator is None for actuator in chosen.values()):
        return None
    given = {joint: actuator for joint, actuator in chosen.items() if actuator is not None}
    missing = [joint for joint in LEG_JOINTS if joint not in given]
    if missing:
        key = f"{TABLE}.{missing[0]}"
        raise ParameterError(
            key, params.get(key, ""), "choose a motor for every joint type, or none"
        )
    temperature = REFERENCE_TEMPERATURE if loaded is None else loaded.winding_temperature
    return Actuators(given["root"], given["hip"], given["knee"], temperature)


def _conditions(params: Mapping[str, str], base: Conditions) -> Conditions:
    """The loaded conditions with the payload and gait the query sets."""
    payload = base.payload
    if "payload" in params or "payload_at" in params:
        mass = _number("payload", params["payload"], "kg") if "payload" in params else payload.mass
        position = payload.position
        if "payload_at" in params:
            given = _three("payload_at", params["payload_at"], ("x", "y", "z"))
            x, y, z = (_number(f"payload_at.{axis}", part, "m") for axis, part in given)
            position = (x, y, z)
        payload = _checked_payload(mass, position)
    gait = base.gait
    if "stride" in params:
        gait = gait.replace(stride=_number("stride", params["stride"], "m"))
    if "step_height" in params:
        gait = gait.replace(step_height=_number("step_height", params["step_height"], "m"))
    if "speed" in params:
        gait = gait.with_speed(_number("speed", params["speed"], "m/s"))
    return Conditions(payload, base.slope, gait, base.stance, base.mode, base.collisions)


def _checked_payload(mass: float, position: tuple[float, float, float] | None) -> Payload:
    """The payload, its errors named by the query's keys."""
    try:
        return Payload(mass, position)
    except ParameterError as err:
        key = err.field.replace("payload mass", "payload").replace("payload position", "payload_at")
        raise ParameterError(key, err.value, err.allowed) from None


def _three(key: str, text: str, items: tuple[str, ...]) -> list[tuple[str, str]]:
    """A triple's three comma-separated parts, paired with their names."""
    parts = text.split(",")
    if len(parts) != 3:
        raise ParameterError(key, text, f"must be three comma-separated numbers {','.join(items)}")
    return list(zip(items, parts, strict=True))


def _number(key: str, text: str, unit: str, bounds: tuple[float, float] | None = None) -> float:
    """A finite number from text; its range is checked where it is declared."""
    try:
        value = float(text)
    except ValueError:
        within = "" if bounds is None else " in [{:g}, {:g}]".format(*bounds)
        raise ParameterError(key, text, f"must be a number{within} [{unit}]") from None
    return value
