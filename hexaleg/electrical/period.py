"""One gait period's electrical figures: energy, power, cost of transport, battery, ratings.

:func:`analyze_electrical` applies the motor equations (:mod:`hexaleg.electrical.equations`,
whose docstring has them all) to every joint and sample of one period and sums them by
the gait's own rule, Σ_k (·)·T/N_s over its samples t_k = k·T/N_s, the rule of the
mechanical positive work (:mod:`hexaleg.gait.metrics`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any, cast

import numpy as np
import numpy.typing as npt

from hexaleg._checks import require_finite, require_instance
from hexaleg._typing import ArrayF
from hexaleg.actuators import Actuators
from hexaleg.battery import Battery
from hexaleg.electrical.equations import (
    MotorSamples,
    motor_samples,
    require_actuators,
    require_samples,
)
from hexaleg.electrical.ratings import RatingBinding, RatingLoads, rating_loads
from hexaleg.exceptions import ParameterError
from hexaleg.limits import LEG_JOINTS
from hexaleg.statics.ratings import OverRating

JOULES_PER_WATT_HOUR = 3600.0
"""1 Wh = 3600 J."""


@dataclass(frozen=True)
class JointElectrical:
    """One joint type's electrical figures over the period.

    Attributes:
        rms_torque: RMS τ of its worst leg [N·m].
        peak_current: Largest |i| of any of its legs [A].
        peak_voltage: Largest voltage needed by any of its legs [V].
        energy_per_period: Σ P_b·T/N_s over its legs [J].

    """

    rms_torque: float
    peak_current: float
    peak_voltage: float
    energy_per_period: float

    def to_dict(self) -> dict[str, float]:
        """JSON-ready form (N·m, A, V, J)."""
        return dict(vars(self))


@dataclass(frozen=True)
class BatteryUse:
    """What walking the period asks of the battery.

    Attributes:
        mass: The battery's mass [kg].
        capacity: Its capacity [Wh].
        reserve: The share of it never used [-].
        runtime: capacity·(1 − reserve) / average power [h] (infinite if the period
            takes nothing).
        range: runtime·v [km] (infinite likewise).

    """

    mass: float
    capacity: float
    reserve: float
    runtime: float
    range: float

    def to_dict(self) -> dict[str, float | None]:
        """JSON-ready form (kg, Wh, h, km); an unbounded runtime or range is ``None``."""
        return {k: v if math.isfinite(v) else None for k, v in vars(self).items()}


@dataclass(frozen=True)
class ElectricalResult:
    """One gait period, electrically: energy, power, cost of transport, battery, ratings.

    Arrays are per sample (N_s, at t_k = k·T/N_s), leg (L) and joint (root, hip, knee).

    Attributes:
        period: T [s].
        speed: The body's speed v [m/s].
        legs: Leg names (L,).
        energy_per_period: E, what the battery gives over the period [J].
        copper_loss_per_period: Σ P_cu·T/N_s [J].
        mechanical_power: Σ_joints τ_m·ω_m averaged over the period: what the motors'
            shafts give, net [W].
        copper_power: The copper loss averaged over the period [W]; mechanical_power +
            copper_power is the motors' net electrical power, before regeneration.
        electronics_power: P₀ [W].
        average_power: E/T [W].
        cost_of_transport: E/(M·g·v·T) [-].
        energy_per_km: E/(v·T)·1000/3600 [Wh/km].
        per_joint: Each joint type's figures (root, hip, knee).
        current: i (N_s, L, 3) [A].
        voltage: The voltage needed (N_s, L, 3) [V].
        electrical_power: P_e (N_s, L, 3) [W].
        battery: What the period asks of the battery (``None`` without one).
        ratings: Each joint against its ratings (peaks, RMS, voltage, speed).
        supply: The bus voltage every motor is fed from [V].
        winding_temperature: The windings' temperature the resistances are taken at [°C].

    """

    period: float
    speed: float
    legs: tuple[str, ...]
    energy_per_period: float
    copper_loss_per_period: float
    mechanical_power: float
    copper_power: float
    electronics_power: float
    average_power: float
    cost_of_transport: float
    energy_per_km: float
    per_joint: dict[str, JointElectrical]
    current: ArrayF
    voltage: ArrayF
    electrical_power: ArrayF
    battery: BatteryUse | None
    ratings: RatingLoads
    supply: float
    winding_temperature: float

    @property
    def times(self) -> ArrayF:
        """t_k = k·T/N_s (N_s,) [s]."""
        samples = len(self.current)
        return cast(ArrayF, np.arange(samples) * (self.period / samples))

    @cached_property
    def over_rating(self) -> tuple[OverRating, ...]:
        """Each joint over its peak torque, continuous torque, voltage or speed rating."""
        return self.ratings.over_rating(self.times)

    @property
    def binding(self) -> RatingBinding:
        """The rating that binds first, and by what ratio (at most 1: within all)."""
        return self.ratings.binding()

    def time_series(self) -> dict[str, ArrayF]:
        """Per leg and joint ``<leg>_<joint>_current`` [A], ``_voltage`` [V], ``_power`` [W].

        Columns (N_s,) each, at :attr:`times` (the gait's own ``t`` column), for a CSV.
        """
        columns = {}
        for i, leg in enumerate(self.legs):
            for j, joint in enumerate(LEG_JOINTS):
                columns[f"{leg}_{joint}_current"] = self.current[:, i, j]
                columns[f"{leg}_{joint}_voltage"] = self.voltage[:, i, j]
                columns[f"{leg}_{joint}_power"] = self.electrical_power[:, i, j]
        return columns

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: ``electrical`` and ``battery`` (``None`` without a battery).

        Units: V, °C, J, W, - and Wh/km; per joint N·m, A, V and J; the battery's kg, Wh,
        -, h, km.
        """
        electrical = {
            "supply": self.supply,
            "winding_temperature": self.winding_temperature,
            "energy_per_period": self.energy_per_period,
            "copper_loss_per_period": self.copper_loss_per_period,
            "mechanical_power": self.mechanical_power,
            "copper_power": self.copper_power,
            "average_power": self.average_power,
            "cost_of_transport": self.cost_of_transport,
            "energy_per_km": self.energy_per_km,
            "per_joint": {joint: figures.to_dict() for joint, figures in self.per_joint.items()},
        }
        battery = None if self.battery is None else self.battery.to_dict()
        return {"electrical": electrical, "battery": battery}


def analyze_electrical(
    torques: npt.ArrayLike,
    speeds: npt.ArrayLike,
    period: float,
    speed: float,
    mass: float,
    gravity: float,
    actuators: Actuators,
    battery: Battery | None = None,
    legs: Sequence[str] | None = None,
    supply: float | None = None,
    safety_factor: float = 1.0,
) -> ElectricalResult:
    """The electrical figures of one gait period (see the module docstring).

    Args:
        torques: Output torques τ (N_s, L, 3) [N·m] at t_k = k·T/N_s.
        speeds: Output speeds ω (N_s, L, 3) [rad/s] at the same samples.
        period: T [s].
        speed: The body's speed v [m/s].
        mass: The mass carried M [kg] (the whole robot, its payload included).
        gravity: g [m/s²].
        actuators: The joint types' actuators.
        battery: The battery (regeneration r and electronics' power P₀; both 0 without).
        legs: Leg names (L,); :data:`~hexaleg.layouts.LEG_NAMES` for six legs if omitted.
        supply: The bus voltage V [V]; the actuators' own, when they agree, if omitted.
        safety_factor: F ≥ 1 [-]: peak torques and speeds are held within rating / F.

    Raises:
        ParameterError: An input of the wrong shape, not finite, or not positive.

    """
    tau, omega, names = require_samples(torques, speeds, legs)
    actuators = require_actuators(actuators)
    period, speed, weight = _period_speed_weight(period, speed, mass, gravity)
    regeneration, electronics = _battery_terms(battery)
    motors = motor_samples(tau, omega, actuators, regeneration)
    joint_energy = motors.battery_power.sum(axis=(0, 1)) * (period / len(tau))  # (3,) [J]
    sums = _sums(motors, period, electronics)
    energy, average = sums["energy_per_period"], sums["average_power"]
    bus = actuators.supply_voltage() if supply is None else _positive("supply", supply, "V")
    ratings = rating_loads(tau, omega, actuators, names, motors.voltage, bus, safety_factor)
    return ElectricalResult(
        period=period,
        speed=speed,
        legs=names,
        **sums,
        electronics_power=electronics,
        cost_of_transport=energy / (weight * speed * period),
        energy_per_km=energy / (speed * period) * 1000.0 / JOULES_PER_WATT_HOUR,
        per_joint=_per_joint(ratings, motors.current, joint_energy),
        current=motors.current,
        voltage=motors.voltage,
        electrical_power=motors.electrical_power,
        battery=None if battery is None else _battery_use(battery, average, speed),
        ratings=ratings,
        supply=bus,
        winding_temperature=actuators.winding_temperature,
    )


def _sums(motors: MotorSamples, period: float, electronics: float) -> dict[str, float]:
    """The period's energy, copper loss, and its shaft, copper and average power [J, W]."""
    step = period / len(motors.current)
    energy = float(motors.battery_power.sum() * step + electronics * period)
    copper = float(motors.copper_loss.sum() * step)
    shaft = float((motors.motor_torque * motors.motor_speed).sum() * step)
    return {"energy_per_period": energy, "copper_loss_per_period": copper,
            "mechanical_power": shaft / period, "copper_power": copper / period,
            "average_power": energy / period}  # fmt: skip


def _per_joint(ratings: RatingLoads, current: ArrayF, energy: ArrayF) -> dict[str, JointElectrical]:
    """Each joint type's worst-leg RMS torque, peak current and voltage, and energy (3,)."""
    rms, voltage = ratings.values[1].max(axis=0), ratings.values[2].max(axis=0)  # worst legs
    current = np.abs(current).max(axis=(0, 1))
    return {
        joint: JointElectrical(
            float(rms[j]), float(current[j]), float(voltage[j]), float(energy[j])
        )
        for j, joint in enumerate(LEG_JOINTS)
    }


def _battery_terms(battery: Battery | None) -> tuple[float, float]:
    """The battery's regeneration r [-] and electronics' power P₀ [W] (0 and 0 without one)."""
    if battery is None:
        return 0.0, 0.0
    require_instance("battery", battery, Battery, "a Battery or None")
    return battery.regeneration, battery.electronics_power


def _period_speed_weight(
    period: float, speed: float, mass: float, gravity: float
) -> tuple[float, float, float]:
    """T [s], v [m/s] and the weight M·g [N], each checked positive."""
    checked = [
        _positive(name, value, unit)
        for name, value, unit in (
            ("period", period, "s"),
            ("speed", speed, "m/s"),
            ("mass", mass, "kg"),
            ("gravity", gravity, "m/s²"),
        )
    ]
    return checked[0], checked[1], checked[2] * checked[3]


def _battery_use(battery: Battery, average_power: float, speed: float) -> BatteryUse:
    """Runtime capacity·(1 − reserve)/(E/T) [h] and range runtime·v·3.6 [km] (∞ if E ≤ 0)."""
    runtime = battery.usable / average_power if average_power > 0 else math.inf
    return BatteryUse(
        battery.mass, battery.capacity, battery.reserve, runtime, runtime * speed * 3.6
    )


def _positive(name: str, value: float, unit: str) -> float:
    number = require_finite(name, value)
    if not number > 0:
        raise ParameterError(name, value, f"must be positive [{unit}]")
    return number
