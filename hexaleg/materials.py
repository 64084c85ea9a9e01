"""Structural materials of the legs' tubes, and the catalog hexaleg ships of them.

A :class:`Material` is what a tube's mass, stress and deflection need: its density ρ
[kg/m³], Young's modulus E [Pa] and the strength it is used to [Pa] — a metal's yield
strength, the design strength a composite or a printed polymer is used to — and, for a
material far weaker in shear than von Mises credits (a unidirectional composite), a
shear strength that bounds the torsion shear stress on its own.

The catalog ships as ``hexaleg/data/materials.toml``: one ``[[material]]`` table per
entry holding ``name`` (lower case, digits, ``_``), the numbers above in SI units,
``source`` (the document each number is copied from: publisher, title, table) and
optionally ``notes``. ``hexaleg materials`` lists it; a design file's ``[structure]``
names an entry (``material = "aluminium_6061_t6"``) or gives its own numbers in a
``[structure.material]`` table.
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, cast

from hexaleg.catalog_file import (
    NamedCatalog,
    entry_tables,
    load_catalog_file,
    named_table,
    shipped_file,
)
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.field_spec import FieldSpec, attributes_section, declare, field_specs
from hexaleg.table_records import REQUIRED, check_record, record_from_table, require_table

ENTRY_TABLE = "material"
"""The catalog file's array of tables: ``[[material]]``."""

OWN = "own"
"""The name of a material whose numbers a design file gives itself."""

TEXT_KEYS: dict[str, str] = {
    "name": "how a design file's [structure] material = NAME refers to the entry",
    "source": "the document the numbers come from: publisher, title, table or page",
    "notes": "what the numbers are (typical, minimum) and caveats",
}
"""A material's text keys beside its numbers (a catalog entry requires ``name`` and ``source``)."""

STRENGTH_RANGE = (1e3, 1e11)
"""Plausible strength [Pa]: a kilopascal (a foam) to a hundred gigapascals (beyond any fibre)."""


@dataclass(frozen=True)
class Material:
    """A structural material: density, stiffness, strength, and where the numbers come from.

    ``name``, ``source`` and ``notes`` are text: the entry's name (``"own"`` for numbers a
    design file gives), the document its numbers are copied from, and what they are.

    """

    # a table, one field a row: its declaration's default, meaning, unit and range
    # fmt: off
    density: float = declare(REQUIRED, "density ρ", "kg/m³", (1.0, 3e4))
    youngs_modulus: float = declare(REQUIRED, "Young's modulus E", "Pa", (1e6, 1e13))
    yield_strength: float = declare(
        REQUIRED, "yield strength, or the design strength a composite or print is used to",
        "Pa", STRENGTH_RANGE,
    )
    shear_strength: float | None = declare(
        None, "shear strength bounding the torsion shear stress on its own (a composite's); "
        "unset: von Mises alone", "Pa", STRENGTH_RANGE,
    )
    name: str = OWN
    source: str = "given in the design file"
    notes: str = ""
    # fmt: on

    def __post_init__(self) -> None:
        check_record(self, MATERIAL_FIELDS)
        for key in TEXT_KEYS:
            if not isinstance(getattr(self, key), str):
                raise ParameterError(key, getattr(self, key), f"must be text: {TEXT_KEYS[key]}")

    @classmethod
    def from_table(cls, table: Any, where: str = ENTRY_TABLE) -> Material:
        """The material a table of its keys describes (a catalog entry, ``[structure.material]``).

        Raises:
            ParameterError: One line naming ``<where>.<key>`` and its range.

        """
        table = require_table(where, table, ", ".join([*TEXT_KEYS, *NUMBER_KEYS]))
        texts = {key: table[key] for key in TEXT_KEYS if key in table}
        for key, value in texts.items():
            if not isinstance(value, str) or not value.strip():
                raise ParameterError(f"{where}.{key}", value, f"must be text: {TEXT_KEYS[key]}")
        numbers = {key: value for key, value in table.items() if key not in TEXT_KEYS}
        record = record_from_table(cls, MATERIAL_FIELDS, numbers, where)
        return dataclasses.replace(record, **texts)

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready: every number (SI) and text key."""
        numbers = {spec.name: getattr(self, spec.name) for spec in MATERIAL_FIELDS}
        return numbers | {key: getattr(self, key) for key in TEXT_KEYS}

    def to_table(self) -> dict[str, Any]:
        """The design file's ``[structure.material]`` table: every key that is set."""
        return {key: value for key, value in self.as_dict().items() if value not in (None, "")}


MATERIAL_FIELDS: tuple[FieldSpec, ...] = field_specs(Material)
"""Every number key of a material, declared once: validation, files, listing and docs read it."""

NUMBER_KEYS: tuple[str, ...] = tuple(spec.name for spec in MATERIAL_FIELDS)
"""The material's number keys, in order."""

Material.__doc__ = (
    cast(str, Material.__doc__).rstrip() + "\n\n" + attributes_section(MATERIAL_FIELDS)
)


class MaterialCatalogError(HexalegError):
    """A materials catalog file that cannot be read or holds an invalid entry."""


@dataclass(frozen=True)
class MaterialCatalog(NamedCatalog[Material]):
    """Materials by name, in the catalog's order (each name once).

    Attributes:
        entries: The materials.

    """

    ENTRY_TABLE = ENTRY_TABLE
    KIND = "material"
    LISTED_BY = "hexaleg materials"

    def material(self, name: Any, field: str = "material") -> Material:
        """The material called ``name``; else a ParameterError naming ``field`` and the nearest."""
        return self.find(name, field)


def catalog_from_data(data: Mapping[str, Any]) -> MaterialCatalog:
    """The catalog a parsed catalog file holds (``{"material": [{...}, ...]}``).

    Raises:
        ParameterError: One line naming ``material.<name>.<key>`` and what is allowed.

    """
    tables = entry_tables(data, ENTRY_TABLE)
    return MaterialCatalog(tuple(_entry(raw, index) for index, raw in enumerate(tables)))


def _entry(raw: Any, index: int) -> Material:
    table, _, where = named_table(raw, index, ENTRY_TABLE, "material keys", TEXT_KEYS["source"])
    return Material.from_table(table, where)


def load_materials(path: str | Path) -> MaterialCatalog:
    """The catalog a TOML materials file holds.

    Raises:
        MaterialCatalogError: The file cannot be read, is not TOML, or holds an invalid
            entry; one line naming the file and the key.

    """
    return load_catalog_file(path, catalog_from_data, MaterialCatalogError)


def shipped_materials_path() -> Path:
    """Where hexaleg's own materials catalog is installed."""
    return shipped_file("materials.toml")


@functools.cache
def shipped_materials() -> MaterialCatalog:
    """The materials catalog hexaleg ships (``hexaleg/data/materials.toml``), read once."""
    return load_materials(shipped_materials_path())
