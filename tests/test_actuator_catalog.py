"""The shipped actuator catalog's schema, read as raw TOML, independently of the loader."""

from __future__ import annotations

import math
import re
import sys

import pytest

from hexaleg.actuator_catalog import shipped_catalog, shipped_catalog_path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

REQUIRED = (
    "gear_ratio",
    "torque_constant",
    "resistance",
    "gearbox_efficiency",
    "peak_torque",
    "continuous_torque",
    "mass",
    "voltage",
)
"""The keys every entry must give (the actuator's required keys)."""
OPTIONAL_NUMBERS = ("rotor_inertia", "max_speed")
TEXT = ("name", "source", "manufacturer", "model", "notes")

ENTRIES = tomllib.loads(shipped_catalog_path().read_text(encoding="utf-8"))["actuator"]


def names(entry):
    return entry["name"]


def test_the_catalog_file_has_entries_with_unique_names():
    listed = [entry["name"] for entry in ENTRIES]
    assert len(listed) >= 10
    assert len(set(listed)) == len(listed)
    assert all(re.fullmatch(r"[a-z0-9][a-z0-9_]*", name) for name in listed)


@pytest.mark.parametrize("entry", ENTRIES, ids=names)
def test_each_entry_has_every_required_key_and_only_known_ones(entry):
    assert set(REQUIRED) <= set(entry)
    assert set(entry) <= {*REQUIRED, *OPTIONAL_NUMBERS, *TEXT, "gear_ratio_range"}


@pytest.mark.parametrize("entry", ENTRIES, ids=names)
def test_each_number_is_physically_plausible(entry):
    numbers = {k: entry[k] for k in (*REQUIRED, *OPTIONAL_NUMBERS) if k in entry}
    for key, value in numbers.items():
        assert isinstance(value, int | float) and not isinstance(value, bool), key
        assert math.isfinite(value), key
    assert 1 <= entry["gear_ratio"] <= 1e4
    assert 0 < entry["gearbox_efficiency"] <= 1
    assert entry["torque_constant"] > 0 and entry["resistance"] >= 0
    assert entry["peak_torque"] >= entry["continuous_torque"] > 0
    assert entry["mass"] > 0 and entry["voltage"] > 0  # real products weigh something
    assert entry.get("rotor_inertia", 0.0) >= 0 and entry.get("max_speed", 1.0) > 0
    if "gear_ratio_range" in entry:
        low, high = entry["gear_ratio_range"]
        assert 1 <= low <= entry["gear_ratio"] <= high


@pytest.mark.parametrize("entry", ENTRIES, ids=names)
def test_each_source_names_a_document_by_maker_and_version_or_date(entry):
    source = entry["source"]
    assert isinstance(source, str) and len(source) >= 30
    assert entry["manufacturer"].split()[0].lower() in source.lower()
    assert re.search(r"\d", source)  # a version, date, page or commit


DC_SERVOS = [e for e in ENTRIES if e["name"].startswith("dynamixel_")]
"""Servos whose k_t·N and R the catalog derives from the stall and no-load points at V."""


@pytest.mark.parametrize("entry", DC_SERVOS, ids=names)
def test_derived_servo_constants_give_back_the_printed_stall_and_no_load_points(entry):
    """A DC motor at V: stall current V/R gives k_t·N·η·V/R at the output; no load, V/(k_t·N).

    The catalog's peak torque and max speed are the printed stall torque and no-load speed;
    k_t, R and η were derived from them, so the model must reproduce both to their
    rounding (three or four significant figures).
    """
    kt_n = entry["torque_constant"] * entry["gear_ratio"]
    stall = kt_n * entry["gearbox_efficiency"] * entry["voltage"] / entry["resistance"]
    assert stall == pytest.approx(entry["peak_torque"], rel=2e-3)
    assert entry["voltage"] / kt_n == pytest.approx(entry["max_speed"], rel=1e-3)


def test_the_loader_reads_the_same_entries():
    assert shipped_catalog().names == tuple(entry["name"] for entry in ENTRIES)
