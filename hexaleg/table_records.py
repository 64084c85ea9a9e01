"""Records declared key by key and read from a table of a design file.

A record such as :class:`~hexaleg.actuators.Actuator` or :class:`~hexaleg.battery.Battery`
declares each of its keys once, as a dataclass field holding a
:class:`~hexaleg.field_spec.FieldSpec` (what it is, its unit, its range, its default; a
field declared without a default is required). This module is the one place that checks
such a record's values, reads it from a TOML table and says what went wrong in one line
naming the key with its table (``actuators.hip.gear_ratio``) and its valid range.
"""

from __future__ import annotations

import dataclasses
import difflib
import re
from collections.abc import Mapping, Sequence
from typing import Any, TypeVar

from hexaleg.exceptions import ParameterError
from hexaleg.field_spec import FieldSpec

T = TypeVar("T")

ENTRY_NAME = re.compile(r"[a-z0-9][a-z0-9_]*")
"""A catalog entry's name: lower-case letters, digits and underscores."""

REQUIRED = dataclasses.MISSING
"""The default of a declared key that has none: the key is required."""


class TableKeyError(ParameterError):
    """A key of a table that is unknown (a typo, most often) or missing.

    Attributes:
        field: The key with its table, e.g. ``"actuators.hip.gear_ratoi"``.
        allowed: What would be right (the nearest key and its range, or the keys).

    """

    def __init__(self, field: str, allowed: str, message: str) -> None:
        super().__init__(field, None, allowed)
        self.args = (message,)

    def __str__(self) -> str:
        return str(self.args[0])

    def __reduce__(self) -> tuple[Any, ...]:
        return (type(self), (self.field, self.allowed, self.args[0]))


def range_text(spec: FieldSpec) -> str:
    """A key's range in words: ``"a number in [1, 10000] [-]"`` (or its kind)."""
    if spec.kind == "number" and spec.bounds is not None:
        return f"a number in [{spec.bounds[0]:g}, {spec.bounds[1]:g}] [{spec.unit}]"
    if spec.kind == "triple" and spec.bounds is not None:
        return (
            f"{len(spec.items)} numbers ({', '.join(spec.items)}), each in "
            f"[{spec.bounds[0]:g}, {spec.bounds[1]:g}] [{spec.unit}]"
        )
    return "a name" if spec.kind == "choice" else spec.kind


def key_line(spec: FieldSpec) -> str:
    """One line on a key: what it is, its unit and range, and its default if it has one."""
    default = "required" if spec.default is REQUIRED else f"default {spec.default!r}"
    return f"{spec.help}; {range_text(spec)}; {default}"


def checked(spec: FieldSpec, value: Any, name: str | None = None) -> Any:
    """``value`` of the key ``spec`` checked and normalized, or a one-line ParameterError.

    Args:
        spec: The key's declaration.
        value: What was given; ``None`` is kept for a key whose default is ``None``.
        name: The key's full name in messages (``"actuators.hip.gear_ratio"``); the
            field's own name if omitted.

    """
    name = spec.name if name is None else name
    if value is None and spec.default is None:
        return None
    try:
        return dataclasses.replace(spec, name=name).check(value)
    except ParameterError as err:
        if spec.bounds is None or spec.kind not in ("number", "triple"):
            raise
        raise ParameterError(err.field, err.value, f"must be {range_text(spec)}") from None


def check_record(record: object, specs: tuple[FieldSpec, ...]) -> None:
    """Check and normalize every declared key of a frozen dataclass in place."""
    for spec in specs:
        object.__setattr__(record, spec.name, checked(spec, getattr(record, spec.name)))


def unknown_key(table: str, key: str, specs: tuple[FieldSpec, ...]) -> TableKeyError:
    """The error for ``key``, which table ``table`` does not have: the nearest one named."""
    names = [spec.name for spec in specs]
    field = f"{table}.{key}" if table else key
    close = difflib.get_close_matches(key, names, n=1, cutoff=0.5)
    if close:
        spec = specs[names.index(close[0])]
        allowed = f"did you mean {close[0]!r} ({spec.help}, {range_text(spec)})?"
    else:
        allowed = "known keys: " + ", ".join(names)
    return TableKeyError(field, allowed, f"unknown key {field!r}: {allowed}")


def unknown_name(
    field: str, name: Any, names: Sequence[str], what: str, listed: str
) -> ParameterError:
    """The error for ``name``, which no entry of a catalog has: the nearest entry named.

    Args:
        field: The key that gave the name (``"structure.material"``).
        name: What was given.
        names: The catalog's names.
        what: What an entry is (``"actuator"``, ``"material"``).
        listed: Where the user finds them (``"hexaleg materials lists them"``).

    """
    if not isinstance(name, str):
        return ParameterError(field, name, f"must be the name of a catalog {what}")
    close = difflib.get_close_matches(name, names, n=1, cutoff=0.4)
    hint = f"did you mean {close[0]!r}?" if close else "none is called so"
    return ParameterError(field, name, f"no such {what}: {hint} ({listed})")


def missing_key(table: str, spec: FieldSpec, hint: str = "") -> TableKeyError:
    """The error for a required key that is not given."""
    field = f"{table}.{spec.name}"
    allowed = f"{spec.help}, {range_text(spec)}"
    return TableKeyError(field, allowed, f"{field} is missing: {allowed}; give it{hint}")


def require_table(name: str, value: Any, what: str) -> Mapping[str, Any]:
    """``value`` if it is a table (a mapping with string keys); else a ParameterError."""
    if not isinstance(value, Mapping) or not all(isinstance(k, str) for k in value):
        raise ParameterError(name, value, f"must be a table of {what}")
    return value


def record_from_table(
    cls: type[T],
    specs: tuple[FieldSpec, ...],
    table: Any,
    name: str,
    base: Mapping[str, Any] | None = None,
    hint: str = "",
) -> T:
    """The record of class ``cls`` that a table describes, every key checked.

    Args:
        cls: A frozen dataclass whose declared keys are ``specs``.
        specs: Its keys' declarations (:func:`~hexaleg.field_spec.field_specs`).
        table: The table as parsed: key → value.
        name: The table's name in messages (``"actuators.hip"``, ``"battery"``).
        base: Values the table's own keys override (a catalog entry's).
        hint: Said after a missing key's range (``', or catalog = "NAME"'``).

    Raises:
        ParameterError: One line naming ``<name>.<key>`` and what is allowed.

    """
    table = require_table(name, table, ", ".join(spec.name for spec in specs))
    known = {spec.name: spec for spec in specs}
    for key, value in table.items():
        if key not in known:
            raise unknown_key(name, key, specs)
        checked(known[key], value, f"{name}.{key}")
    values = {**(base or {}), **table}
    for spec in specs:
        if spec.default is REQUIRED and spec.name not in values:
            raise missing_key(name, spec, hint)
    try:
        return cls(**values)
    except ParameterError as err:  # how the keys fit together: name the table too
        raise ParameterError(f"{name}.{err.field}", err.value, err.allowed) from None
