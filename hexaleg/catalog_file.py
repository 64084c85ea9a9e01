"""A catalog file: named entries of datasheet or handbook numbers, each with its source.

hexaleg ships two catalogs (actuators, :mod:`hexaleg.actuator_catalog`; structural
materials, :mod:`hexaleg.materials`) and reads both the same way: a TOML file of
``[[ENTRY]]`` tables only, each with a ``name`` (lower-case letters, digits, ``_``) given
once in the file and a ``source`` (the document its numbers are copied from). A design
file refers to an entry by its name; an unknown name is refused naming the nearest.
Each catalog says what its entries are (:class:`NamedCatalog`' class attributes) and how
one table becomes an entry; the rest is here.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any, ClassVar, Generic, Protocol, TypeVar

from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.table_records import ENTRY_NAME, require_table, unknown_name

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib


class Named(Protocol):
    """An entry: anything with a name."""

    @property
    def name(self) -> str:
        """How a design file refers to the entry."""
        ...


Entry = TypeVar("Entry", bound=Named)
CatalogT = TypeVar("CatalogT")


@dataclass(frozen=True)
class NamedCatalog(Generic[Entry]):
    """Entries by name, in the catalog's order (each name once).

    A catalog subclasses it naming its file's array of tables (``ENTRY_TABLE``), what an
    entry is (``KIND``, in messages) and the command that lists them (``LISTED_BY``).

    Attributes:
        entries: The entries.

    """

    entries: tuple[Entry, ...]

    ENTRY_TABLE: ClassVar[str] = "entry"
    KIND: ClassVar[str] = "entry"
    LISTED_BY: ClassVar[str] = "hexaleg"

    def __post_init__(self) -> None:
        seen: set[str] = set()
        for entry in self.entries:
            if entry.name in seen:
                raise ParameterError(
                    f"{self.ENTRY_TABLE}.name", entry.name, "each name once (it is given twice)"
                )
            seen.add(entry.name)

    def __iter__(self) -> Iterator[Entry]:
        return iter(self.entries)

    def __len__(self) -> int:
        return len(self.entries)

    @property
    def names(self) -> tuple[str, ...]:
        """Every entry's name, in order."""
        return tuple(entry.name for entry in self.entries)

    def find(self, name: Any, field: str) -> Entry:
        """The entry called ``name``; else a ParameterError naming ``field`` and the nearest."""
        for entry in self.entries:
            if entry.name == name:
                return entry
        raise unknown_name(field, name, self.names, self.KIND, f"{self.LISTED_BY} lists them")


def entry_tables(data: Mapping[str, Any], entry_table: str) -> list[Any]:
    """The ``[[entry_table]]`` tables of a parsed catalog file, refusing anything else.

    Raises:
        ParameterError: A key other than ``entry_table``, or it not an array of tables.

    """
    unknown = [key for key in data if key != entry_table]
    if unknown:
        allowed = f"a catalog holds [[{entry_table}]] tables only"
        raise ParameterError(unknown[0], data[unknown[0]], allowed)
    tables = data.get(entry_table, [])
    if not isinstance(tables, list):
        raise ParameterError(entry_table, tables, f"must be [[{entry_table}]] tables")
    return tables


def named_table(
    raw: Any, index: int, entry_table: str, keys: str, source: str
) -> tuple[Mapping[str, Any], str, str]:
    """Entry ``index``'s table, its name and where it is (``ENTRY.NAME``) for messages.

    Args:
        raw: The entry as parsed.
        index: Its place in the file (named in a refusal before its name is known).
        entry_table: The file's array of tables.
        keys: What the entry's keys are (in a refusal of a table that is not one).
        source: What its ``source`` must say (in the refusal of an entry without one).

    Raises:
        ParameterError: Not a table, a name that is not lower-case letters, digits and
            ``_``, or no ``source``.

    """
    table = require_table(f"{entry_table}[{index}]", raw, keys)
    name = table.get("name")
    if not isinstance(name, str) or not ENTRY_NAME.fullmatch(name):
        raise ParameterError(
            f"{entry_table}[{index}].name", name, "lower-case letters, digits and '_'"
        )
    where = f"{entry_table}.{name}"
    if "source" not in table:
        raise ParameterError(f"{where}.source", None, f"is required: {source}")
    return table, name, where


def load_catalog_file(
    path: str | Path,
    from_data: Callable[[Mapping[str, Any]], CatalogT],
    error: type[HexalegError],
) -> CatalogT:
    """The catalog a TOML file holds, read by ``from_data``.

    Raises:
        HexalegError: ``error``: the file cannot be read, is not TOML, or holds an invalid
            entry; one line naming the file and the key.

    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as err:
        raise error(f"{path}: cannot read it ({err})") from None
    except tomllib.TOMLDecodeError as err:
        raise error(f"{path}: not valid TOML ({err})") from None
    try:
        return from_data(data)
    except ParameterError as err:
        raise error(f"{path}: {err}") from None


def shipped_file(name: str) -> Path:
    """Where a catalog hexaleg ships (``hexaleg/data/NAME``) is installed."""
    return Path(str(resources.files("hexaleg") / "data" / name))
