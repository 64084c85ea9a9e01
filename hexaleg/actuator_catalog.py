"""The actuator catalog: real actuators' datasheet numbers, each entry with its source.

The catalog ships with hexaleg as ``hexaleg/data/actuators.toml``: one ``[[actuator]]``
table per entry, holding

- ``name``: how a design file's ``catalog = "NAME"`` refers to it (lower case, digits, ``_``);
- the :class:`~hexaleg.actuators.Actuator` keys, in SI units (the required ones all given);
- ``source``: the document the numbers come from (manufacturer, title, version or date);
- optionally ``gear_ratio_range``: the lowest and highest ratio the product comes in;
- optionally ``manufacturer``, ``model`` and ``notes`` (text: how a number was derived).

``hexaleg actuators`` lists it. Every entry is checked as an actuator is, and the
catalog as a whole refuses a name given twice. A design file's ``[actuators]`` table, whose
joints may name an entry (``catalog = "NAME"``), is read here
(:func:`actuators_from_table`), where the entries are.
"""

from __future__ import annotations

import difflib
import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hexaleg.actuators import (
    ACTUATOR_FIELDS,
    GEAR_RATIO_RANGE,
    REFERENCE_TEMPERATURE,
    TABLE,
    TEMPERATURE_KEY,
    Actuator,
    Actuators,
)
from hexaleg.catalog_file import (
    NamedCatalog,
    entry_tables,
    load_catalog_file,
    named_table,
    shipped_file,
)
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.limits import LEG_JOINTS
from hexaleg.table_records import record_from_table, require_table

ENTRY_TABLE = "actuator"
"""The catalog file's array of tables: ``[[actuator]]``."""

TEXT_KEYS: dict[str, str] = {
    "name": "how a design file's catalog = NAME refers to the entry",
    "source": "the document the numbers come from: manufacturer, title, version or date",
    "manufacturer": "who makes it",
    "model": "the product's designation",
    "notes": "how derived numbers were derived, and caveats",
}
"""The catalog's text keys beside the actuator's (``name`` and ``source`` required)."""


class CatalogError(HexalegError):
    """An actuator catalog file that cannot be read or holds an invalid entry."""


@dataclass(frozen=True)
class CatalogEntry:
    """One actuator of the catalog.

    Attributes:
        name: How ``catalog = "NAME"`` refers to it.
        values: Its :class:`~hexaleg.actuators.Actuator` keys as the catalog gives them
            (SI units).
        source: The document its numbers come from.
        gear_ratio_range: The lowest and highest gear ratio the product comes in [-], if
            the catalog says.
        manufacturer: Who makes it.
        model: The product's designation.
        notes: How derived numbers were derived, and caveats.

    """

    name: str
    values: Mapping[str, Any] = field(compare=False)
    source: str
    gear_ratio_range: tuple[float, float] | None = None
    manufacturer: str = ""
    model: str = ""
    notes: str = ""

    @functools.cached_property
    def actuator(self) -> Actuator:
        """The entry as an actuator (checked when the catalog is read)."""
        return Actuator(**self.values, catalog=self.name)

    def require_gear_ratio(self, ratio: float, name: str) -> None:
        """Refuse a gear ratio [-] outside :attr:`gear_ratio_range`, naming ``name``."""
        if self.gear_ratio_range is None:
            return
        low, high = self.gear_ratio_range
        if not low <= ratio <= high:
            raise ParameterError(
                name, ratio, f"{self.name} comes with ratios in [{low:g}, {high:g}] [-]"
            )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: every actuator number (``max_speed`` resolved) and the source."""
        actuator = self.actuator
        numbers = {s.name: getattr(actuator, s.name) for s in ACTUATOR_FIELDS if s.kind == "number"}
        return {
            "name": self.name,
            "manufacturer": self.manufacturer,
            "model": self.model,
            **numbers,
            "max_speed": actuator.rated_speed,
            "max_speed_derived": actuator.max_speed is None,
            "armature": actuator.armature,
            "gear_ratio_range": None if self.gear_ratio_range is None else [*self.gear_ratio_range],
            "source": self.source,
            "notes": self.notes,
        }


@dataclass(frozen=True)
class Catalog(NamedCatalog[CatalogEntry]):
    """Actuator catalog entries by name.

    Attributes:
        entries: The entries, in the catalog's order (each name once).

    """

    ENTRY_TABLE = ENTRY_TABLE
    KIND = "actuator"
    LISTED_BY = "hexaleg actuators"

    def entry(self, name: Any, field: str = "catalog") -> CatalogEntry:
        """The entry called ``name``; else a ParameterError naming ``field`` and the nearest."""
        return self.find(name, field)


def catalog_from_data(data: Mapping[str, Any]) -> Catalog:
    """The catalog a parsed catalog file holds (``{"actuator": [{...}, ...]}``).

    Raises:
        ParameterError: One line naming ``actuator.<name>.<key>`` and what is allowed.

    """
    tables = entry_tables(data, ENTRY_TABLE)
    return Catalog(tuple(_entry(raw, index) for index, raw in enumerate(tables)))


def _entry(raw: Any, index: int) -> CatalogEntry:
    table, name, where = named_table(raw, index, ENTRY_TABLE, "actuator keys", TEXT_KEYS["source"])
    texts = {key: table[key] for key in TEXT_KEYS if key in table}
    for key, value in texts.items():
        if not isinstance(value, str) or not value.strip():
            raise ParameterError(f"{where}.{key}", value, f"must be text: {TEXT_KEYS[key]}")
    values = {k: v for k, v in table.items() if k not in TEXT_KEYS and k != "gear_ratio_range"}
    if "catalog" in values:
        raise ParameterError(f"{where}.catalog", values["catalog"], "an entry names no catalog")
    actuator = record_from_table(Actuator, ACTUATOR_FIELDS, values, where)
    entry = CatalogEntry(
        name=name,
        values=values,
        source=texts["source"],
        gear_ratio_range=_ratio_range(f"{where}.gear_ratio_range", table.get("gear_ratio_range")),
        manufacturer=texts.get("manufacturer", ""),
        model=texts.get("model", ""),
        notes=texts.get("notes", ""),
    )
    entry.require_gear_ratio(actuator.gear_ratio, f"{where}.gear_ratio")
    return entry


def _ratio_range(name: str, value: Any) -> tuple[float, float] | None:
    if value is None:
        return None
    low, high = GEAR_RATIO_RANGE
    allowed = f"must be [lowest, highest] gear ratio, each in [{low:g}, {high:g}] [-]"
    if not isinstance(value, list) or len(value) != 2:
        raise ParameterError(name, value, allowed)
    for number in value:
        if isinstance(number, bool) or not isinstance(number, int | float):
            raise ParameterError(name, value, allowed)
        if not (math.isfinite(number) and low <= number <= high):
            raise ParameterError(name, value, allowed)
    if value[0] > value[1]:
        raise ParameterError(name, value, allowed + ", lowest first")
    return (float(value[0]), float(value[1]))


def load_catalog(path: str | Path) -> Catalog:
    """The catalog a TOML catalog file holds.

    Raises:
        CatalogError: The file cannot be read, is not TOML, or holds an invalid entry;
            one line naming the file and the key.

    """
    return load_catalog_file(path, catalog_from_data, CatalogError)


def shipped_catalog_path() -> Path:
    """Where hexaleg's own catalog file is installed."""
    return shipped_file("actuators.toml")


@functools.cache
def shipped_catalog() -> Catalog:
    """The catalog hexaleg ships (``hexaleg/data/actuators.toml``), read once."""
    return load_catalog(shipped_catalog_path())


def actuators_from_table(table: Any, catalog: Catalog | None = None) -> Actuators:
    """The actuators a design file's ``[actuators]`` table describes.

    Args:
        table: ``{"root": {...}, "hip": {...}, "knee": {...}}``, each a table of
            :class:`~hexaleg.actuators.Actuator` keys, or a ``catalog`` key and the keys it
            overrides.
        catalog: The catalog ``catalog = "NAME"`` refers to; hexaleg's own
            (:func:`shipped_catalog`) if omitted.

    Raises:
        ParameterError: One line naming ``actuators.<joint>.<key>`` and its range, an
            unknown key with the nearest known one, or an unknown catalog name with the
            nearest entry.

    """
    table = require_table(TABLE, table, "root, hip and knee actuators")
    keys = (*LEG_JOINTS, TEMPERATURE_KEY)
    for joint in table:
        if joint not in keys:
            close = difflib.get_close_matches(joint, keys, n=1)
            hint = (
                f"did you mean {close[0]!r}?"
                if close
                else f"use root, hip and knee (and {TEMPERATURE_KEY})"
            )
            raise ParameterError(f"{TABLE}.{joint}", table[joint], f"no such joint: {hint}")
    joints = {joint: _actuator(table, joint, catalog) for joint in LEG_JOINTS}
    temperature = table.get(TEMPERATURE_KEY, REFERENCE_TEMPERATURE)
    return Actuators(**joints, winding_temperature=temperature)


def _actuator(table: Mapping[str, Any], joint: str, catalog: Catalog | None) -> Actuator:
    """``[actuators.<joint>]``: its own keys over its catalog entry's."""
    name = f"{TABLE}.{joint}"
    if joint not in table:
        raise ParameterError(name, None, "is missing: give each of root, hip and knee a table")
    given = require_table(name, table[joint], ", ".join(s.name for s in ACTUATOR_FIELDS))
    if "catalog" not in given:
        hint = ', or catalog = "NAME" (hexaleg actuators lists them)'
        return record_from_table(Actuator, ACTUATOR_FIELDS, given, name, hint=hint)
    found = shipped_catalog() if catalog is None else catalog  # an empty catalog is falsy
    entry = found.entry(given["catalog"], f"{name}.catalog")
    actuator = record_from_table(Actuator, ACTUATOR_FIELDS, given, name, entry.values)
    entry.require_gear_ratio(actuator.gear_ratio, f"{name}.gear_ratio")
    return actuator
