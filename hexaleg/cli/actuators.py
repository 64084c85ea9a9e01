"""``hexaleg actuators``: the actuator catalog a design file's ``catalog = "NAME"`` draws on."""

from __future__ import annotations

import argparse
from typing import Any

from hexaleg.actuator_catalog import Catalog, CatalogEntry, shipped_catalog, shipped_catalog_path
from hexaleg.actuators import ACTUATOR_NUMBERS
from hexaleg.cli import catalog_listing
from hexaleg.cli.catalog_listing import catalog_lines, print_catalog

DESCRIPTION = (
    "List the actuator catalog: each entry's gear ratio, motor constants (at the motor), "
    "output ratings, mass, rotor inertia, supply and speed rating in SI units, and the "
    'document its numbers come from. A design file\'s [actuators.hip] catalog = "NAME" '
    "takes an entry's keys; keys given beside it override them."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    catalog_listing.add_arguments(parser)


def run(args: argparse.Namespace) -> int:
    """Print the catalog as a table (or JSON)."""
    catalog = shipped_catalog()
    return print_catalog(args, lambda: catalog_json(catalog), lambda: catalog_text(catalog))


def catalog_json(catalog: Catalog) -> dict[str, Any]:
    """Every entry's numbers (``max_speed`` resolved) and source, with the keys' units."""
    units = {spec.name: spec.unit for spec in ACTUATOR_NUMBERS}
    return {
        "catalog": str(shipped_catalog_path()),
        "actuators": [entry.to_dict() for entry in catalog],
        "units": units | {"armature": "kg·m²", "gear_ratio_range": "-"},
    }


def _numbers(entry: CatalogEntry) -> list[float]:
    actuator = entry.actuator
    numbers = {spec.name: getattr(actuator, spec.name) for spec in ACTUATOR_NUMBERS}
    numbers["max_speed"] = actuator.rated_speed
    return [numbers[spec.name] for spec in ACTUATOR_NUMBERS]


def catalog_text(catalog: Catalog) -> list[str]:
    """The catalog as lines: a table (one entry a row), what each key is, each source."""
    rows = [(entry, _numbers(entry)) for entry in catalog]
    note = "(max_speed listed: the given one, or the no-load speed when not given)"
    return catalog_lines(
        "Actuator catalog", shipped_catalog_path(), ACTUATOR_NUMBERS, rows, key_notes=[note]
    )
