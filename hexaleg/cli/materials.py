"""``hexaleg materials``: the structural materials a design file's ``[structure]`` draws on."""

from __future__ import annotations

import argparse
from typing import Any

from hexaleg.cli import catalog_listing
from hexaleg.cli.catalog_listing import catalog_lines, print_catalog
from hexaleg.materials import (
    MATERIAL_FIELDS,
    MaterialCatalog,
    shipped_materials,
    shipped_materials_path,
)

DESCRIPTION = (
    "List the materials catalog: each entry's density, Young's modulus, yield (or design) "
    "strength and, for a composite, shear strength, in SI units, and the document its "
    'numbers come from. A design file\'s [structure] material = "NAME" takes an entry; a '
    "[structure.material] table gives a material's own numbers instead."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    catalog_listing.add_arguments(parser)


def run(args: argparse.Namespace) -> int:
    """Print the catalog as a table (or JSON)."""
    catalog = shipped_materials()
    return print_catalog(args, lambda: catalog_json(catalog), lambda: catalog_text(catalog))


def catalog_json(catalog: MaterialCatalog) -> dict[str, Any]:
    """Every entry's numbers (SI), source and notes, with the keys' units."""
    return {
        "catalog": str(shipped_materials_path()),
        "materials": [entry.as_dict() for entry in catalog],
        "units": {spec.name: spec.unit for spec in MATERIAL_FIELDS},
    }


def catalog_text(catalog: MaterialCatalog) -> list[str]:
    """The catalog as lines: a table (one entry a row), what each key is, each source."""
    rows = [(entry, [getattr(entry, spec.name) for spec in MATERIAL_FIELDS]) for entry in catalog]
    return catalog_lines("Materials catalog", shipped_materials_path(), MATERIAL_FIELDS, rows)
