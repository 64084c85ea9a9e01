"""``hexaleg materials``: the structural materials a design file's ``[structure]`` draws on."""

from __future__ import annotations

import argparse
from typing import Any

from hexaleg.cli.output import columns, print_json, require_stdout
from hexaleg.materials import (
    MATERIAL_FIELDS,
    Material,
    MaterialCatalog,
    shipped_materials,
    shipped_materials_path,
)
from hexaleg.table_records import key_line

DESCRIPTION = (
    "List the materials catalog: each entry's density, Young's modulus, yield (or design) "
    "strength and, for a composite, shear strength, in SI units, and the document its "
    'numbers come from. A design file\'s [structure] material = "NAME" takes an entry; a '
    "[structure.material] table gives a material's own numbers instead."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    parser.add_argument(
        "--json", action="store_true", help="print JSON: every number of every entry, its source"
    )


def run(args: argparse.Namespace) -> int:
    """Print the catalog as a table (or JSON)."""
    catalog = shipped_materials()
    if args.json:
        print_json(catalog_json(catalog))
        return 0
    require_stdout()
    print("\n".join(catalog_text(catalog)))
    return 0


def catalog_json(catalog: MaterialCatalog) -> dict[str, Any]:
    """Every entry's numbers (SI), source and notes, with the keys' units."""
    return {
        "catalog": str(shipped_materials_path()),
        "materials": [entry.as_dict() for entry in catalog],
        "units": {spec.name: spec.unit for spec in MATERIAL_FIELDS},
    }


def _cells(entry: Material) -> list[str]:
    numbers = (getattr(entry, spec.name) for spec in MATERIAL_FIELDS)
    return [entry.name] + ["-" if v is None else f"{v:.4g}" for v in numbers]


def catalog_text(catalog: MaterialCatalog) -> list[str]:
    """The catalog as lines: a table (one entry a row), what each key is, each source."""
    header = ["name"] + [spec.name for spec in MATERIAL_FIELDS]
    units = [""] + [f"[{spec.unit}]" for spec in MATERIAL_FIELDS]
    rows = [_cells(entry) for entry in catalog]
    lines = [f"Materials catalog ({len(catalog)} entries, {shipped_materials_path()})", ""]
    lines += [*columns([header, units, *rows]), "", "Keys:"]
    lines += [f"  {spec.name}: {key_line(spec)}" for spec in MATERIAL_FIELDS]
    lines += ["", "Sources:"]
    for entry in catalog:
        lines.append(f"  {entry.name}: {entry.source}")
        if entry.notes:
            lines.append(f"    ({entry.notes})")
    return lines
