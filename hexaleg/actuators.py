"""The joints' actuators: a motor behind a gearbox, fed from a supply, one per joint type.

A design file holds one table per joint type, ``[actuators.root]``, ``[actuators.hip]``
and ``[actuators.knee]``; each key is declared once below (:class:`Actuator`), in SI
units. Every key without a default is required unless ``catalog = "NAME"`` names an
entry of the actuator catalog that supplies it (the catalog reads such a table:
:func:`hexaleg.actuator_catalog.actuators_from_table`, listed by ``hexaleg actuators``);
keys given beside ``catalog`` override the entry's, each on its own (an overridden
``gear_ratio`` keeps the entry's output-side ratings, so give those as well).

The model is a DC-equivalent motor: torque τ_m = k_t·i at the motor, terminal
resistance R in the same convention (copper loss i²R), a gearbox of ratio N and
efficiency η between motor and joint (:mod:`hexaleg.electrical` has the equations).

One bus feeds every motor: the ``[battery]``'s ``voltage``, else the actuators' own
``voltage`` when all three agree (:meth:`Actuators.supply_voltage`; the design refuses
actuators of different voltages without a bus voltage). An actuator's ``voltage`` is the
supply its datasheet quotes its figures at (its no-load speed among them).

The windings' resistance is the datasheet's at its reference temperature, 25 °C; the
``[actuators]`` table's ``winding_temperature`` T [°C] scales every R by
1 + α·(T − 25) with copper's temperature coefficient α = :data:`COPPER_ALPHA`
(:attr:`Actuators.resistances`). α is the International Annealed Copper Standard's at
20 °C; used from 25 °C it overstates the resistance by α·5/(1 + α·5) ≈ 2 % of the change.
Derived per joint: the no-load speed V/(k_t·N) [rad/s] (the speed rating when
``max_speed`` is not given) and the reflected rotor inertia N²·J [kg·m²], the joint's
armature.

Another gear ratio for the same motor (:meth:`Actuator.with_gear_ratio`, what
``decide --free-gear-ratio`` searches within a catalog entry's ``gear_ratio_range``):
N changes to N' = s·N and

- the motor's k_t, R, J, the supply V, the mass and η stay (η is held at the entry's: a
  datasheet gives one per ratio, within a few per cent of each other for the catalog's
  units);
- the speed rating scales as 1/s (a given ``max_speed``, the motor's top speed through
  the new ratio; the no-load speed V/(k_t·N') follows by itself), the armature as s²;
- the peak and continuous torques scale as min(s, 1): below the entry's ratio the motor
  binds (its torque limit times N'·η), above it the rule credits no more than the
  datasheet printed for the entry's ratio, since the gearbox it was rated with may
  bind there. Against Harmonic Drive's CHA tables, which print every ratio
  (``hexaleg/data/actuators_notes.md``), the rule is conservative except below the
  entry's ratio where a smaller gearbox is rated less than proportionally (CHA-32A at
  30: 100 N·m printed, 130 N·m by the rule; CHA-17A's continuous torque at 80: 27 N·m
  printed, 31 N·m by the rule); above it, scaling by s would overstate (CHA-20A at 160:
  92 N·m printed, 131 N·m by s). A product sells discrete ratios: the ratio found is a
  continuous optimum to round to the nearest one sold.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, cast

from hexaleg._checks import require_in_range
from hexaleg.exceptions import ParameterError
from hexaleg.field_spec import FieldSpec, attributes_section, declare, field_specs
from hexaleg.limits import LEG_JOINTS
from hexaleg.table_records import REQUIRED, check_record

GEAR_RATIO_RANGE = (1.0, 1e4)
"""Plausible gear ratio N [-]: direct drive to a harmonic drive's highest."""
TORQUE_RANGE = (1e-3, 1e6)
"""Plausible output torque rating [N·m] (the design's rated torques' range)."""
SPEED_RANGE = (1e-3, 1e4)
"""Plausible output speed rating [rad/s] (the design's rated speeds' range)."""

TABLE = "actuators"
"""The design file's table of actuators: one sub-table per joint type."""

COPPER_ALPHA = 0.00393
"""Temperature coefficient of resistance of copper [1/K]: the International Annealed Copper
Standard's at 20 °C (National Bureau of Standards, Handbook 100, *Copper Wire Tables*, 1966,
Part I §1.1(b) "Temperature coefficient of resistance of copper", p. 3; first measured by
J. H. Dellinger, Bulletin of the Bureau of Standards 7(1), 1911, pp. 71–101)."""

REFERENCE_TEMPERATURE = 25.0
"""The winding temperature datasheets quote the resistance at [°C]: R is used as given there."""

WINDING_TEMPERATURE_RANGE = (-50.0, 200.0)
"""Winding temperatures accepted [°C]: a cold start outdoors up to beyond the hottest
standard insulation class for motor windings, class 180 (H) of IEC 60085 (180 °C)."""

TEMPERATURE_KEY = "winding_temperature"
"""The ``[actuators]`` table's key of the windings' temperature, beside the joint tables."""
TEMPERATURE_TEXT = "the windings' temperature: every R scaled from the datasheets' 25 °C [°C]"
"""What ``winding_temperature`` is, as a design file's comment says it."""


@dataclass(frozen=True)
class Actuator:
    """One joint type's actuator: motor constants, gearbox, ratings, mass and supply.

    Torques and speeds are at the output (the joint) unless said "at the motor".

    """

    # a table, one field a row: its declaration's default, meaning, unit and range
    # fmt: off
    gear_ratio: float = declare(
        REQUIRED, "gear ratio N: motor turns per joint turn", "-", GEAR_RATIO_RANGE
    )
    torque_constant: float = declare(
        REQUIRED, "torque constant k_t at the motor", "N·m/A", (1e-5, 100.0)
    )
    resistance: float = declare(
        REQUIRED, "terminal resistance R, in k_t's convention (copper loss i²R)", "Ω",
        (0.0, 1e4),
    )
    gearbox_efficiency: float = declare(
        REQUIRED, "gearbox efficiency η, both directions", "-", (0.01, 1.0)
    )
    peak_torque: float = declare(REQUIRED, "peak torque at the output", "N·m", TORQUE_RANGE)
    continuous_torque: float = declare(
        REQUIRED, "continuous torque at the output, at most the peak (bounds the RMS)", "N·m",
        TORQUE_RANGE,
    )
    mass: float = declare(REQUIRED, "mass of motor and gearbox", "kg", (0.0, 1e4))
    voltage: float = declare(REQUIRED, "supply voltage V", "V", (0.1, 1e4))
    rotor_inertia: float = declare(
        0.0, "rotor inertia J at the motor (its armature at the joint: N²·J)", "kg·m²",
        (0.0, 10.0),
    )
    max_speed: float | None = declare(
        None, "largest speed at the output; unset: the no-load speed V/(k_t·N)", "rad/s",
        SPEED_RANGE,
    )
    catalog: str | None = declare(
        None, "the catalog entry supplying the keys not given", kind="choice"
    )
    # fmt: on

    def __post_init__(self) -> None:
        check_record(self, ACTUATOR_FIELDS)
        if self.catalog is not None and not isinstance(self.catalog, str):
            raise ParameterError("catalog", self.catalog, "must be an actuator's name")
        if self.continuous_torque > self.peak_torque:
            raise ParameterError(
                "continuous_torque",
                self.continuous_torque,
                f"must be at most peak_torque = {self.peak_torque:g} [N·m]",
            )

    @property
    def no_load_speed(self) -> float:
        """V/(k_t·N): the output speed at which the back-EMF takes the whole supply [rad/s]."""
        return self.voltage / (self.torque_constant * self.gear_ratio)

    @property
    def rated_speed(self) -> float:
        """``max_speed``, or the no-load speed when it is not given [rad/s]."""
        return self.no_load_speed if self.max_speed is None else self.max_speed

    @property
    def armature(self) -> float:
        """The rotor's inertia reflected to the joint, N²·J [kg·m²]."""
        return self.gear_ratio**2 * self.rotor_inertia

    def with_gear_ratio(self, ratio: float) -> Actuator:
        """The same motor behind a gearbox of ratio N' = ``ratio`` (the module's rule).

        Raises:
            ParameterError: ``gear_ratio`` out of range, or a scaled rating out of its own.

        """
        scale = ratio / self.gear_ratio
        torque = min(scale, 1.0)
        return dataclasses.replace(
            self,
            gear_ratio=ratio,
            peak_torque=self.peak_torque * torque,
            continuous_torque=self.continuous_torque * torque,
            max_speed=None if self.max_speed is None else self.max_speed / scale,
        )

    def as_dict(self) -> dict[str, Any]:
        """Every key as given (``max_speed`` ``None`` when derived) and ``rated_speed``."""
        out: dict[str, Any] = {spec.name: getattr(self, spec.name) for spec in ACTUATOR_FIELDS}
        return out | {"rated_speed": self.rated_speed, "armature": self.armature}

    def to_table(self) -> dict[str, Any]:
        """The design file's ``[actuators.<joint>]`` table: every key that is set."""
        values = {spec.name: getattr(self, spec.name) for spec in ACTUATOR_FIELDS}
        return {key: value for key, value in values.items() if value is not None}


ACTUATOR_FIELDS: tuple[FieldSpec, ...] = field_specs(Actuator)
"""Every actuator key's declaration, in order: validation, files, listing and docs read it."""

ACTUATOR_NUMBERS: tuple[FieldSpec, ...] = tuple(s for s in ACTUATOR_FIELDS if s.kind == "number")
"""The keys that are numbers (all but ``catalog``)."""

Actuator.__doc__ = (
    cast(str, Actuator.__doc__).rstrip() + "\n\n" + attributes_section(ACTUATOR_FIELDS)
)


@dataclass(frozen=True)
class Actuators:
    """The three joint types' actuators (every leg's joint of a type has the same).

    Attributes:
        root: The root (yaw) joints' actuator.
        hip: The hip joints' actuator.
        knee: The knee joints' actuator.
        winding_temperature: The windings' temperature T [°C] (default the datasheets'
            reference, 25 °C): every resistance is scaled to it (:attr:`resistances`).

    """

    root: Actuator
    hip: Actuator
    knee: Actuator
    winding_temperature: float = REFERENCE_TEMPERATURE

    def __post_init__(self) -> None:
        for joint in LEG_JOINTS:
            if not isinstance(getattr(self, joint), Actuator):
                raise ParameterError(f"{TABLE}.{joint}", getattr(self, joint), "an Actuator")
        temperature = require_in_range(
            f"{TABLE}.{TEMPERATURE_KEY}", self.winding_temperature,
            *WINDING_TEMPERATURE_RANGE, "°C",
        )  # fmt: skip
        object.__setattr__(self, "winding_temperature", temperature)

    @property
    def joints(self) -> tuple[Actuator, Actuator, Actuator]:
        """(root, hip, knee)."""
        return (self.root, self.hip, self.knee)

    def values(self, key: str) -> tuple[float, float, float]:
        """One key of each joint type's actuator, (root, hip, knee)."""
        root, hip, knee = (getattr(a, key) for a in self.joints)
        return (root, hip, knee)

    @property
    def rated_torques(self) -> tuple[float, float, float]:
        """Peak torques (root, hip, knee) [N·m]: what replaces a design's rated torques."""
        return self.values("peak_torque")

    @property
    def continuous_torques(self) -> tuple[float, float, float]:
        """Continuous torques (root, hip, knee) [N·m]: the RMS torque's ratings."""
        return self.values("continuous_torque")

    @property
    def rated_speeds(self) -> tuple[float, float, float]:
        """Speed ratings (root, hip, knee) [rad/s]: what replaces a design's rated speeds."""
        return self.values("rated_speed")

    @property
    def resistances(self) -> tuple[float, float, float]:
        """Winding resistances (root, hip, knee) at :attr:`winding_temperature` [Ω].

        R·(1 + α·(T − 25)), α = :data:`COPPER_ALPHA`: the datasheets' R at 25 °C.
        """
        scale = 1.0 + COPPER_ALPHA * (self.winding_temperature - REFERENCE_TEMPERATURE)
        root, hip, knee = (r * scale for r in self.values("resistance"))
        return (root, hip, knee)

    def supply_voltage(self) -> float:
        """The voltage the three actuators share [V]: their bus when no battery gives one.

        Raises:
            ParameterError: ``battery.voltage`` is needed: their voltages differ (named).

        """
        voltages = self.values("voltage")
        if len(set(voltages)) > 1:
            named = ", ".join(f"{j} {v:g} V" for j, v in zip(LEG_JOINTS, voltages, strict=True))
            raise ParameterError(
                "battery.voltage",
                None,
                f"is required: one bus feeds every motor, and the actuators' voltages differ "
                f"({named}); give the bus voltage [V] > 0 in [battery]",
            )
        return voltages[0]

    @property
    def armatures(self) -> tuple[float, float, float]:
        """Reflected rotor inertias N²·J (root, hip, knee) [kg·m²]."""
        return self.values("armature")

    @property
    def masses(self) -> tuple[float, float, float]:
        """Actuator masses (root, hip, knee) [kg]."""
        return self.values("mass")

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready form: each joint type's keys (SI units), as a design file's table.

        :func:`~hexaleg.actuator_catalog.actuators_from_table` reads it back;
        :meth:`Actuator.as_dict` adds the derived numbers.
        """
        return self.to_table()

    def to_table(self) -> dict[str, Any]:
        """The design file's ``[actuators]`` table: each joint type's keys that are set.

        ``winding_temperature`` only when it is not the datasheets' reference.
        """
        table: dict[str, Any] = {}
        if self.winding_temperature != REFERENCE_TEMPERATURE:
            table[TEMPERATURE_KEY] = self.winding_temperature
        return table | {joint: getattr(self, joint).to_table() for joint in LEG_JOINTS}

    @property
    def total_mass(self) -> float:
        """The six legs' actuators: 6·(root + hip + knee) [kg]."""
        return 6 * sum(self.masses)
