"""``hexaleg actuators``: the actuator catalog a design file's ``catalog = "NAME"`` draws on."""

from __future__ import annotations

import argparse
from typing import Any

from hexaleg.actuator_catalog import Catalog, CatalogEntry, shipped_catalog, shipped_catalog_path
from hexaleg.actuators import ACTUATOR_NUMBERS
from hexaleg.cli.output import columns, print_json, require_stdout
from hexaleg.table_records import key_line

DESCRIPTION = (
    "List the actuator catalog: each entry's gear ratio, motor constants (at the motor), "
    "output ratings, mass, rotor inertia, supply and speed rating in SI units, and the "
    'document its numbers come from. A design file\'s [actuators.hip] catalog = "NAME" '
    "takes an entry's keys; keys given beside it override them."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    parser.add_argument(
        "--json", action="store_true", help="print JSON: every number of every entry, its source"
    )


def run(args: argparse.Namespace) -> int:
    """Print the catalog as a table (or JSON)."""
    catalog = shipped_catalog()
    if args.json:
        print_json(catalog_json(catalog))
        return 0
    require_stdout()
    print("\n".join(catalog_text(catalog)))
    return 0


def catalog_json(catalog: Catalog) -> dict[str, Any]:
    """Every entry's numbers (``max_speed`` resolved) and source, with the keys' units."""
    units = {spec.name: spec.unit for spec in ACTUATOR_NUMBERS}
    return {
        "catalog": str(shipped_catalog_path()),
        "actuators": [entry.to_dict() for entry in catalog],
        "units": units | {"armature": "kg·m²", "gear_ratio_range": "-"},
    }


def _cells(entry: CatalogEntry) -> list[str]:
    actuator = entry.actuator
    numbers = {spec.name: getattr(actuator, spec.name) for spec in ACTUATOR_NUMBERS}
    numbers["max_speed"] = actuator.rated_speed
    return [entry.name] + [f"{numbers[spec.name]:.4g}" for spec in ACTUATOR_NUMBERS]


def catalog_text(catalog: Catalog) -> list[str]:
    """The catalog as lines: a table (one entry a row), what each key is, each source."""
    header = ["name"] + [spec.name for spec in ACTUATOR_NUMBERS]
    units = [""] + [f"[{spec.unit}]" for spec in ACTUATOR_NUMBERS]
    rows = [_cells(entry) for entry in catalog]
    lines = [f"Actuator catalog ({len(catalog)} entries, {shipped_catalog_path()})", ""]
    lines += [*columns([header, units, *rows]), "", "Keys:"]
    lines += [f"  {spec.name}: {key_line(spec)}" for spec in ACTUATOR_NUMBERS]
    lines += ["  (max_speed listed: the given one, or the no-load speed when not given)", ""]
    lines.append("Sources:")
    for entry in catalog:
        lines.append(f"  {entry.name}: {entry.source}")
    return lines
