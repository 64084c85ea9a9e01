"""Actuators and the battery: their keys, the design file's tables and every refusal."""

from __future__ import annotations

import math

import pytest

from hexaleg.actuator_catalog import (
    Catalog,
    actuators_from_table,
    catalog_from_data,
    shipped_catalog,
)
from hexaleg.actuators import ACTUATOR_FIELDS, ACTUATOR_NUMBERS, Actuator
from hexaleg.battery import BATTERY_FIELDS, Battery
from hexaleg.exceptions import ParameterError

HIP = {
    "gear_ratio": 100,
    "torque_constant": 0.05,
    "resistance": 0.5,
    "gearbox_efficiency": 0.8,
    "peak_torque": 30.0,
    "continuous_torque": 10.0,
    "mass": 1.2,
    "voltage": 48.0,
}
"""An actuator's required keys, in a design file's units (SI)."""


def tables(**hip):
    """An ``[actuators]`` table: the hip's keys changed by ``hip`` (None: left out)."""
    changed = {k: v for k, v in {**HIP, **hip}.items() if v is not None}
    return {"root": dict(HIP), "hip": changed, "knee": dict(HIP)}


def refusal(table, catalog=None) -> str:
    with pytest.raises(ParameterError) as info:
        actuators_from_table(table, catalog)
    message = str(info.value)
    assert "\n" not in message
    return message


def test_an_actuator_and_what_it_implies():
    actuator = Actuator(**HIP, rotor_inertia=2e-5)
    assert actuator.gear_ratio == 100.0 and isinstance(actuator.gear_ratio, float)
    assert actuator.no_load_speed == pytest.approx(48.0 / (0.05 * 100))  # 9.6 rad/s
    assert actuator.rated_speed == actuator.no_load_speed  # no max_speed: the no-load speed
    assert Actuator(**HIP, max_speed=2.5).rated_speed == 2.5
    assert actuator.armature == pytest.approx(100**2 * 2e-5)  # 0.2 kg·m²
    assert Actuator(**HIP).armature == 0.0  # rotor inertia defaults to 0


def test_the_three_joint_types_give_the_ratings_triples():
    actuators = actuators_from_table(
        {
            "root": {**HIP, "peak_torque": 20.0, "max_speed": 3.0},
            "hip": HIP,
            "knee": {**HIP, "continuous_torque": 5.0, "rotor_inertia": 1e-5},
        }
    )
    assert actuators.rated_torques == (20.0, 30.0, 30.0)
    assert actuators.continuous_torques == (10.0, 10.0, 5.0)
    assert actuators.rated_speeds == pytest.approx((3.0, 9.6, 9.6))
    assert actuators.armatures == pytest.approx((0.0, 0.0, 0.1))
    assert actuators.masses == (1.2, 1.2, 1.2)
    assert actuators.as_dict()["root"]["max_speed"] == 3.0


def test_every_key_is_declared_once_with_unit_and_range():
    numbers = {spec.name for spec in ACTUATOR_NUMBERS}
    assert numbers == {*HIP, "rotor_inertia", "max_speed"}
    for spec in ACTUATOR_NUMBERS:
        assert spec.unit and spec.help and spec.bounds is not None, spec.name
        assert spec.name in Actuator.__doc__  # the docstring lists every key
    assert "catalog" in {spec.name for spec in ACTUATOR_FIELDS}


@pytest.mark.parametrize("spec", ACTUATOR_NUMBERS, ids=lambda s: s.name)
@pytest.mark.parametrize("side", ["below", "above", "text", "nan"])
def test_each_key_out_of_its_range_is_refused_naming_it_and_its_range(spec, side):
    low, high = spec.bounds
    value = {
        "below": low - 1.0 if low <= 0 else low / 2,
        "above": high * 2,
        "text": "ten",
        "nan": math.nan,
    }[side]
    message = refusal(tables(**{spec.name: value}))
    assert message.startswith(f"actuators.hip.{spec.name} = ")
    assert f"[{low:g}, {high:g}] [{spec.unit}]" in message


@pytest.mark.parametrize("spec", ACTUATOR_FIELDS, ids=lambda s: s.name)
def test_a_misspelt_key_is_refused_with_the_nearest_and_its_range(spec):
    typo = spec.name[:-1] + ("x" if spec.name[-1] != "x" else "y")
    message = refusal(tables(**{typo: 1.0}))
    assert message.startswith(f"unknown key 'actuators.hip.{typo}': did you mean '{spec.name}'")
    if spec.bounds is not None:
        assert f"[{spec.bounds[0]:g}, {spec.bounds[1]:g}]" in message


@pytest.mark.parametrize("key", sorted(HIP))
def test_a_missing_required_key_is_named_with_its_range(key):
    message = refusal(tables(**{key: None}))
    assert message.startswith(f"actuators.hip.{key} is missing: ")
    assert 'or catalog = "NAME"' in message


def test_how_the_keys_fit_together_is_checked_too():
    message = refusal(tables(continuous_torque=31.0))  # above the peak of 30 N·m
    assert message == (
        "actuators.hip.continuous_torque = 31 is not valid: must be at most peak_torque = 30 [N·m]"
    )


@pytest.mark.parametrize(
    ("table", "expected"),
    [
        ({"root": HIP, "hips": HIP, "knee": HIP}, "actuators.hips = "),
        ({"root": HIP, "knee": HIP}, "actuators.hip = None is not valid: is missing"),
        ({"root": HIP, "hip": 3, "knee": HIP}, "actuators.hip = 3 is not valid: must be a table"),
        ([HIP, HIP, HIP], "actuators = "),
    ],
)
def test_the_joint_tables_themselves(table, expected):
    message = refusal(table)
    assert message.startswith(expected)
    if "hips" in expected:
        assert "did you mean 'hip'?" in message


# -- the catalog --------------------------------------------------------------------------

TINY = {
    "actuator": [
        {"name": "small_servo", "source": "Maker A, Servo datasheet, rev 2 (2020)", **HIP},
        {
            "name": "big_drive",
            "source": "Maker B, Drive manual, 1/2019",
            **HIP,
            "gear_ratio": 50,
            "gear_ratio_range": [30, 160],
            "rotor_inertia": 4e-4,
            "max_speed": 6.0,
        },
    ]
}
"""A two-entry catalog written here, independent of the shipped one."""


@pytest.fixture
def tiny() -> Catalog:
    return catalog_from_data(TINY)


def test_a_catalog_entry_supplies_the_keys_and_given_keys_override_it(tiny):
    table = {
        "root": {"catalog": "big_drive"},
        "hip": {"catalog": "big_drive", "gear_ratio": 100, "voltage": 24.0},
        "knee": {**HIP, "peak_torque": 40.0},
    }
    actuators = actuators_from_table(table, tiny)
    assert actuators.root.gear_ratio == 50 and actuators.root.max_speed == 6.0
    assert actuators.root.catalog == "big_drive" and actuators.knee.catalog is None
    assert actuators.hip.gear_ratio == 100 and actuators.hip.voltage == 24.0
    assert actuators.hip.rotor_inertia == 4e-4  # the rest from the entry
    assert actuators.armatures == pytest.approx((50**2 * 4e-4, 100**2 * 4e-4, 0.0))


def test_an_unknown_catalog_name_suggests_the_nearest(tiny):
    message = refusal(tables(catalog="big_driv"), tiny)
    assert message.startswith("actuators.hip.catalog = 'big_driv' is not valid: no such actuator")
    assert "did you mean 'big_drive'?" in message
    assert "is not valid: must be the name" in refusal(tables(catalog=3), tiny)


def test_a_gear_ratio_the_entry_does_not_come_in_is_refused(tiny):
    table = {"root": HIP, "hip": {"catalog": "big_drive", "gear_ratio": 200}, "knee": HIP}
    message = refusal(table, tiny)
    assert message == (
        "actuators.hip.gear_ratio = 200 is not valid: big_drive comes with ratios in [30, 160] [-]"
    )


def test_catalog_override_values_are_checked_like_any_key(tiny):
    table = {"root": HIP, "hip": {"catalog": "small_servo", "mass": -1}, "knee": HIP}
    assert refusal(table, tiny).startswith("actuators.hip.mass = -1 is not valid: must be a number")


def entry(**changes):
    base = {"name": "one", "source": "Maker, Sheet, v1", **HIP}
    return {"actuator": [{k: v for k, v in {**base, **changes}.items() if v is not None}]}


@pytest.mark.parametrize(
    ("data", "expected"),
    [
        ({"actuator": [*TINY["actuator"], TINY["actuator"][0]]}, "actuator.name = 'small_servo'"),
        (entry(source=None), "actuator.one.source = None is not valid: is required"),
        (entry(source="  "), "actuator.one.source = ' ' is not valid: must be text"),
        (entry(name="Big Servo"), "actuator[0].name = 'Big Servo' is not valid"),
        (entry(voltage=None), "actuator.one.voltage is missing"),
        (entry(peak_torque=5.0), "actuator.one.continuous_torque = 10 is not valid"),
        (entry(gear_ratio_range=[120, 160]), "actuator.one.gear_ratio = 100 is not valid"),
        (entry(gear_ratio_range=[160, 30]), "actuator.one.gear_ratio_range = [160, 30]"),
        (entry(gear_ratio_range=[30]), "actuator.one.gear_ratio_range = [30]"),
        (entry(catalog="two"), "actuator.one.catalog = 'two' is not valid"),
        (entry(torque_konstant=1.0), "unknown key 'actuator.one.torque_konstant'"),
        ({"actuators": []}, "actuators = [] is not valid"),
    ],
)
def test_a_bad_catalog_entry_is_refused_in_one_line(data, expected):
    with pytest.raises(ParameterError) as info:
        catalog_from_data(data)
    assert str(info.value).startswith(expected)
    assert "\n" not in str(info.value)


def test_a_catalog_entry_lists_every_number_and_its_source(tiny):
    out = tiny.entry("small_servo").to_dict()
    assert out["max_speed"] == pytest.approx(48.0 / (0.05 * 100))  # derived: V/(k_t·N)
    assert out["max_speed_derived"] is True
    assert out["source"] == "Maker A, Servo datasheet, rev 2 (2020)"
    assert {spec.name for spec in ACTUATOR_NUMBERS} <= set(out)


def test_the_shipped_catalog_loads_and_every_entry_makes_an_actuator():
    catalog = shipped_catalog()
    assert len(catalog) >= 10
    for item in catalog:
        assert item.actuator.catalog == item.name


# -- the battery --------------------------------------------------------------------------


def test_the_battery_mass_and_defaults():
    battery = Battery.from_table({"capacity": 500, "specific_energy": 200})
    assert battery.mass == pytest.approx(2.5)  # 500 Wh / 200 Wh/kg
    assert battery.battery_at == (0.0, 0.0, 0.0)  # the body origin
    assert battery.regeneration == 0.0 and battery.electronics_power == 0.0
    placed = Battery.from_table(
        {"capacity": 500, "specific_energy": 200, "battery_at": [0.1, 0, -0.05]}
    )
    assert placed.battery_at == (0.1, 0.0, -0.05)


@pytest.mark.parametrize("spec", BATTERY_FIELDS, ids=lambda s: s.name)
def test_each_battery_key_out_of_range_or_misspelt_is_refused(spec):
    low, high = spec.bounds
    good = {"capacity": 500.0, "specific_energy": 200.0}
    bad = high * 2 if spec.kind == "number" else [0.0, 0.0, high * 2]
    with pytest.raises(ParameterError) as info:
        Battery.from_table({**good, spec.name: bad})
    assert str(info.value).startswith(f"battery.{spec.name}")
    assert f"[{low:g}, {high:g}] [{spec.unit}]" in str(info.value)
    with pytest.raises(ParameterError) as info:
        Battery.from_table({**good, spec.name + "s": 1.0})
    assert str(info.value).startswith(f"unknown key 'battery.{spec.name}s': did you mean")


def test_a_battery_without_its_capacity_is_refused():
    with pytest.raises(ParameterError, match=r"^battery.capacity is missing: "):
        Battery.from_table({"specific_energy": 200})
