"""The materials catalog: every entry sourced and plausible, read raw; ``hexaleg materials``."""

from __future__ import annotations

import json
import math
import re
import sys

import pytest

from hexaleg.cli.main import main
from hexaleg.exceptions import ParameterError
from hexaleg.materials import (
    Material,
    MaterialCatalogError,
    catalog_from_data,
    load_materials,
    shipped_materials,
    shipped_materials_path,
)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

RAW = tomllib.loads(shipped_materials_path().read_text(encoding="utf-8"))["material"]
NUMBERS = ("density", "youngs_modulus", "yield_strength", "shear_strength")

# What a structural material's numbers can be at all (SI): densities between a foam's and
# osmium's, moduli between a soft plastic's and diamond's, strengths below their modulus.
PLAUSIBLE = {"density": (500.0, 23_000.0), "youngs_modulus": (1e8, 1.2e12)}


def names(entry):
    return entry["name"]


def test_at_least_five_entries_the_brief_names_and_unique_names():
    listed = [entry["name"] for entry in RAW]
    assert len(listed) >= 5 and len(set(listed)) == len(listed)
    assert "aluminium_6061_t6" in listed
    assert all(re.fullmatch(r"[a-z0-9][a-z0-9_]*", name) for name in listed)
    kinds = " ".join(listed)
    for kind in ("aluminium_7075", "steel", "carbon", "pla"):
        assert kind in kinds


@pytest.mark.parametrize("entry", RAW, ids=names)
def test_each_entry_cites_a_source_and_only_known_keys(entry):
    assert set(entry) <= {*NUMBERS, "name", "source", "notes"}
    assert isinstance(entry["source"], str) and len(entry["source"]) > 40
    # the source names the numbers it gives: each printed number appears in it
    assert re.search(r"\d", entry["source"])


@pytest.mark.parametrize("entry", RAW, ids=names)
def test_each_number_is_physically_plausible(entry):
    for key in NUMBERS[:3]:
        value = entry[key]
        assert isinstance(value, int | float) and math.isfinite(value), key
    for key, (low, high) in PLAUSIBLE.items():
        assert low <= entry[key] <= high, key
    assert 0 < entry["yield_strength"] < entry["youngs_modulus"] / 10
    if "shear_strength" in entry:
        assert 0 < entry["shear_strength"] < entry["yield_strength"]


def test_the_loader_reads_every_entry_as_given():
    catalog = shipped_materials()
    assert catalog.names == tuple(entry["name"] for entry in RAW)
    for material, raw in zip(catalog, RAW, strict=True):
        for key in NUMBERS:
            assert getattr(material, key) == raw.get(key)
        assert material.source == raw["source"]


def test_an_unknown_name_suggests_the_nearest():
    with pytest.raises(ParameterError, match=r"did you mean 'aluminium_6061_t6'"):
        shipped_materials().material("aluminum_6061", "structure.material")


@pytest.mark.parametrize(
    ("change", "match"),
    [
        ({"yield_strength": -5.0}, r"material\.x\.yield_strength = -5 .* \[Pa\]"),
        ({"density": 0.0}, r"material\.x\.density = 0 .* \[kg/m³\]"),
        ({"yeld_strength": 1e8}, r"did you mean 'yield_strength'"),
        ({"source": ""}, r"material\.x\.source"),
    ],
)
def test_a_bad_entry_names_its_key_and_range(change, match):
    entry = {"name": "x", "density": 2700, "youngs_modulus": 7e10, "yield_strength": 2e8}
    entry["source"] = "a handbook, table 1"
    with pytest.raises(ParameterError, match=match):
        catalog_from_data({"material": [entry | change]})


def test_a_catalog_without_sources_or_with_twins_is_refused(tmp_path):
    entry = {"name": "x", "density": 2700, "youngs_modulus": 7e10, "yield_strength": 2e8}
    with pytest.raises(ParameterError, match="source"):
        catalog_from_data({"material": [entry]})
    sourced = entry | {"source": "somewhere, table 2"}
    with pytest.raises(ParameterError, match="given twice"):
        catalog_from_data({"material": [sourced, sourced]})
    bad = tmp_path / "bad.toml"
    bad.write_text("[[material]\n", encoding="utf-8")
    with pytest.raises(MaterialCatalogError, match="not valid TOML"):
        load_materials(bad)


def test_a_material_s_own_table_reads_back_from_its_table():
    own = Material.from_table(
        {"density": 1200.0, "youngs_modulus": 3e9, "yield_strength": 5e7}, "structure.material"
    )
    assert own.name == "own" and own.shear_strength is None
    assert Material.from_table(own.to_table()) == own


def test_the_cli_lists_every_entry_with_its_source(capsys):
    assert main(["materials"]) == 0
    text = capsys.readouterr().out
    for raw in RAW:
        assert f"  {raw['name']}: {raw['source']}" in text
        row = next(line for line in text.splitlines() if line.startswith(raw["name"] + " "))
        assert float(row.split()[1]) == pytest.approx(raw["density"], rel=1e-3)


def test_the_cli_json_gives_si_numbers_and_units(capsys):
    assert main(["materials", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["units"] == {
        "density": "kg/m³",
        "youngs_modulus": "Pa",
        "yield_strength": "Pa",
        "shear_strength": "Pa",
    }
    for listed, raw in zip(data["materials"], RAW, strict=True):
        assert listed["name"] == raw["name"] and listed["source"] == raw["source"]
        for key in NUMBERS:
            assert listed[key] == raw.get(key)
