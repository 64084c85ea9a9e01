"""``hexaleg actuators``: the catalog as a table and as JSON, run in-process."""

from __future__ import annotations

import json
import sys

import pytest

from hexaleg.actuator_catalog import shipped_catalog_path
from hexaleg.cli.main import main

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

RAW = tomllib.loads(shipped_catalog_path().read_text(encoding="utf-8"))["actuator"]
NUMBERS = (
    "gear_ratio",
    "torque_constant",
    "resistance",
    "gearbox_efficiency",
    "peak_torque",
    "continuous_torque",
    "mass",
    "rotor_inertia",
    "voltage",
    "max_speed",
)


def test_the_json_gives_every_number_of_every_entry_and_its_source(capsys):
    assert main(["actuators", "--json"]) == 0
    listed = json.loads(capsys.readouterr().out)["actuators"]
    assert [entry["name"] for entry in listed] == [raw["name"] for raw in RAW]
    for entry, raw in zip(listed, RAW, strict=True):
        for key in NUMBERS:
            expected = raw.get(key, 0.0 if key == "rotor_inertia" else None)
            if expected is None:  # max_speed not given: the no-load speed V/(k_t·N)
                expected = raw["voltage"] / (raw["torque_constant"] * raw["gear_ratio"])
            assert entry[key] == pytest.approx(expected, rel=1e-15), (raw["name"], key)
        assert entry["source"] == raw["source"]


def test_the_table_lists_every_entry_its_keys_and_its_source(capsys):
    assert main(["actuators"]) == 0
    text = capsys.readouterr().out
    for raw in RAW:
        assert f"  {raw['name']}: {raw['source']}" in text
        row = next(line for line in text.splitlines() if line.startswith(raw["name"] + " "))
        assert float(row.split()[1]) == pytest.approx(raw["gear_ratio"], rel=1e-3)
    for key in NUMBERS:
        assert f"  {key}: " in text  # what each key is, its unit and range


def test_an_unknown_option_is_one_line(capsys):
    with pytest.raises(SystemExit) as info:
        main(["actuators", "--jsn"])
    assert info.value.code == 2
    assert capsys.readouterr().err.count("\n") == 1
