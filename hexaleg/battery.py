"""The battery: its capacity, its mass, where it sits, and what it takes back.

A design file's ``[battery]`` table holds the keys declared below (:class:`Battery`),
in SI units except the battery's own: capacity in watt-hours [Wh] and specific energy in
watt-hours per kilogram [Wh/kg], as datasheets give them. The battery's mass
capacity / specific energy is a point mass at ``battery_at`` in the body frame. The
share ``regeneration`` of the power the motors give back while braking returns to the
battery; the electronics draw ``electronics_power`` all the time
(:mod:`hexaleg.electrical` has the equations). Its ``voltage`` is the bus every motor is
fed from (unset: the actuators' own voltage, when they agree); the share ``reserve`` of
its capacity is never used, so the runtime and range count only the rest.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, cast

from hexaleg._checks import require_instance
from hexaleg.actuators import Actuators
from hexaleg.field_spec import FieldSpec, attributes_section, declare, field_specs
from hexaleg.table_records import REQUIRED, check_record, record_from_table

POSITION_RANGE = (-100.0, 100.0)
"""Plausible coordinate of the battery's position in the body frame [m] (as a payload's)."""

TABLE = "battery"
"""The design file's table of the battery."""

VOLTAGE_RANGE = (0.1, 1e4)
"""Plausible bus voltage [V] (an actuator's supply range): positive."""

DEFAULT_RESERVE = 0.2
"""Share of the capacity kept in reserve by default [-]: hexaleg's choice, not a datasheet's
(a pack left a fifth charged is spared deep discharge and keeps the robot able to walk
home); set ``reserve = 0`` to count the whole capacity."""
RESERVE_RANGE = (0.0, 0.99)
"""A reserve's range [-]: none kept, up to all but a hundredth (a whole capacity kept in
reserve leaves nothing to walk on)."""


@dataclass(frozen=True)
class Battery:
    """The robot's battery: capacity, specific energy, position, regeneration, electronics."""

    # a table, one field a row: its declaration's default, meaning, unit and range
    # fmt: off
    capacity: float = declare(REQUIRED, "energy stored when full", "Wh", (1e-3, 1e7))
    specific_energy: float = declare(
        REQUIRED, "energy stored per kilogram of battery (its mass: capacity / this)", "Wh/kg",
        (1.0, 1e4),
    )
    battery_at: tuple[float, float, float] = declare(
        (0.0, 0.0, 0.0), "where the battery's mass sits, body frame", "m", POSITION_RANGE,
        kind="triple", items=("x", "y", "z"),
    )
    regeneration: float = declare(
        0.0, "share r of the braking motors' electrical power that recharges it", "-",
        (0.0, 1.0),
    )
    electronics_power: float = declare(
        0.0, "power P₀ the electronics draw all the time", "W", (0.0, 1e6)
    )
    voltage: float | None = declare(
        None, "bus voltage V feeding every motor; unset: the actuators' own voltage, when "
        "all three agree", "V", VOLTAGE_RANGE,
    )
    reserve: float = declare(
        DEFAULT_RESERVE, "share of the capacity never used (runtime and range count the "
        "rest)", "-", RESERVE_RANGE,
    )
    # fmt: on

    def __post_init__(self) -> None:
        check_record(self, BATTERY_FIELDS)

    @property
    def usable(self) -> float:
        """The capacity a charge gives before the reserve: capacity·(1 − reserve) [Wh]."""
        return self.capacity * (1.0 - self.reserve)

    @classmethod
    def from_table(cls, table: Any) -> Battery:
        """The battery a design file's ``[battery]`` table describes.

        Raises:
            ParameterError: One line naming ``battery.<key>`` and its range, or an unknown
                key with the nearest known one.

        """
        return record_from_table(cls, BATTERY_FIELDS, table, TABLE)

    @property
    def mass(self) -> float:
        """The battery's mass: capacity / specific energy [kg]."""
        return self.capacity / self.specific_energy

    def as_dict(self) -> dict[str, Any]:
        """Every key (Wh, Wh/kg, m, W) and the mass [kg]."""
        return self.to_table() | {"mass": self.mass}

    def to_table(self) -> dict[str, Any]:
        """The design file's ``[battery]`` table: every key set (:meth:`from_table` reads it)."""
        out: dict[str, Any] = {spec.name: getattr(self, spec.name) for spec in BATTERY_FIELDS}
        out = {key: value for key, value in out.items() if value is not None}
        return out | {"battery_at": list(self.battery_at)}


BATTERY_FIELDS: tuple[FieldSpec, ...] = field_specs(Battery)
"""Every battery key's declaration, in order."""

Battery.__doc__ = cast(str, Battery.__doc__).rstrip() + "\n\n" + attributes_section(BATTERY_FIELDS)


def bus_voltage(battery: Battery | None, actuators: Actuators | None) -> float | None:
    """The voltage every motor is fed from [V] (``None`` without actuators).

    The battery's ``voltage``, else the actuators' own when all three agree.

    Raises:
        ParameterError: ``battery`` is no Battery, or ``battery.voltage`` is needed (the
            actuators' voltages differ: :meth:`~hexaleg.actuators.Actuators.supply_voltage`).

    """
    if battery is not None:
        require_instance("battery", battery, Battery, "a Battery or None")
    if actuators is None:
        return None
    if battery is not None and battery.voltage is not None:
        return battery.voltage
    return actuators.supply_voltage()
