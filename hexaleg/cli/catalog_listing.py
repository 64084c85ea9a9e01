"""What ``hexaleg actuators`` and ``hexaleg materials`` share: listing a shipped catalog.

Each prints its catalog as a table (one entry a row, a column per number with its unit),
what each key is and each entry's source; ``--json`` prints every number instead.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any, Protocol

from hexaleg.cli.output import columns, print_json, require_stdout
from hexaleg.field_spec import FieldSpec
from hexaleg.table_records import key_line


class Sourced(Protocol):
    """A catalog entry as listed: its name, its source and (maybe empty) notes."""

    @property
    def name(self) -> str: ...  # noqa: D102

    @property
    def source(self) -> str: ...  # noqa: D102


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add a listing command's options."""
    parser.add_argument(
        "--json", action="store_true", help="print JSON: every number of every entry, its source"
    )


def print_catalog(
    args: argparse.Namespace,
    as_json: Callable[[], dict[str, Any]],
    as_text: Callable[[], list[str]],
) -> int:
    """Print the catalog as JSON (``--json``) or as text lines."""
    if args.json:
        print_json(as_json())
        return 0
    require_stdout()
    print("\n".join(as_text()))
    return 0


def catalog_lines(
    title: str,
    path: Path,
    specs: Sequence[FieldSpec],
    rows: Iterable[tuple[Sourced, Sequence[Any]]],
    key_notes: Sequence[str] = (),
) -> list[str]:
    """The catalog as lines: a table, what each key is, each entry's source (and notes).

    Args:
        title: What the catalog is ("Actuator catalog").
        path: Where it is installed.
        specs: The numbers' declarations, one column each.
        rows: Each entry and its numbers in ``specs``' order (``None``: not given).
        key_notes: Lines after the keys' (how a listed number was resolved).

    """
    rows = list(rows)
    header = ["name"] + [spec.name for spec in specs]
    units = [""] + [f"[{spec.unit}]" for spec in specs]
    cells = [[entry.name] + ["-" if v is None else f"{v:.4g}" for v in row] for entry, row in rows]
    lines = [f"{title} ({len(rows)} entries, {path})", ""]
    lines += [*columns([header, units, *cells]), "", "Keys:"]
    lines += [f"  {spec.name}: {key_line(spec)}" for spec in specs]
    lines += [f"  {note}" for note in key_notes]
    lines += ["", "Sources:"]
    for entry, _ in rows:
        lines.append(f"  {entry.name}: {entry.source}")
        notes = getattr(entry, "notes", "")
        if notes:
            lines.append(f"    ({notes})")
    return lines
