"""The motor equations: a gait period's joint torques and speeds as current, voltage and energy.

For each joint and each sample of one period, with output torque τ [N·m] and output speed
ω [rad/s], and the joint type's actuator (:mod:`hexaleg.actuators`: gear ratio N, gearbox
efficiency η, torque constant k_t [N·m/A], resistance R [Ω] at the windings' temperature
(:attr:`~hexaleg.actuators.Actuators.resistances`), and the bus voltage V [V] that feeds
every motor (:attr:`~hexaleg.design.HexapodDesign.bus_voltage`)):

- motor speed ω_m = N·ω [rad/s];
- motor torque τ_m = τ/(N·η) when τ·ω ≥ 0 (motoring: the motor also pays the gearbox's
  losses) and τ_m = τ·η/N when τ·ω < 0 (braking: the joint drives the motor through the
  gearbox, which keeps its losses) [N·m];
- current i = τ_m/k_t [A] and copper loss P_cu = i²·R [W];
- electrical power P_e = τ_m·ω_m + P_cu [W];
- battery power P_b = P_e when P_e ≥ 0, else r·P_e, r the battery's regeneration [W];
- voltage needed |k_t·ω_m| + |i|·R [V], which must not exceed V at any sample.

Over the period T [s], sampled as the gait samples it (t_k = k·T/N_s, k = 0 … N_s − 1)
and summed by the same rule as the mechanical positive work of :mod:`hexaleg.gait.metrics`:

- energy E = Σ_joints Σ_k P_b·T/N_s + P₀·T [J], P₀ the electronics' power;
- average power E/T [W]; electrical cost of transport E/(M·g·v·T) [-] (M the mass
  carried, g gravity, v the body's speed); energy per km E/(v·T)·1000/3600 [Wh/km];
- battery runtime capacity·(1 − reserve)/(E/T) [h] and range runtime·v·3.6 [km]
  (unbounded, ``None`` in JSON, when the period takes nothing from the battery).

Ratings, per leg and joint: its peak |τ| against the peak torque / F, its RMS τ over the
period against the continuous torque, its largest voltage needed against the bus voltage V
and its largest |ω| against the speed rating / F (F ≥ 1 the safety factor). Each gives a
ratio value/rating; a ratio above 1 is an :class:`~hexaleg.statics.ratings.OverRating`, and
the largest ratio is the rating that binds first
(:func:`~hexaleg.electrical.ratings.binding_rating`, what a max-speed search bisects on). A
joint type's RMS torque is its worst leg's; its energy is the sum over its legs
(:mod:`hexaleg.electrical.period`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from hexaleg._checks import require_instance
from hexaleg._typing import ArrayF
from hexaleg.actuators import Actuators
from hexaleg.exceptions import ParameterError
from hexaleg.layouts import LEG_NAMES


@dataclass(frozen=True)
class MotorSamples:
    """The motor equations at every sample, each array shaped as the torques given.

    Attributes:
        motor_speed: ω_m [rad/s].
        motor_torque: τ_m [N·m].
        current: i [A].
        copper_loss: P_cu [W].
        electrical_power: P_e [W].
        battery_power: P_b [W].
        voltage: Voltage needed [V].

    """

    motor_speed: ArrayF
    motor_torque: ArrayF
    current: ArrayF
    copper_loss: ArrayF
    electrical_power: ArrayF
    battery_power: ArrayF
    voltage: ArrayF


def motor_samples(
    torques: npt.ArrayLike, speeds: npt.ArrayLike, actuators: Actuators, regeneration: float = 0.0
) -> MotorSamples:
    """The motor equations (module docstring) for torques and speeds of any shape (..., 3).

    Args:
        torques: Output torques τ [N·m], the last axis (root, hip, knee).
        speeds: Output speeds ω [rad/s], the same shape.
        actuators: The joint types' actuators.
        regeneration: Share r ∈ [0, 1] of a braking motor's power the battery takes back.

    """
    tau, omega = np.asarray(torques, dtype=float), np.asarray(speeds, dtype=float)
    ratio, kt, eta = (
        np.array(actuators.values(key))
        for key in ("gear_ratio", "torque_constant", "gearbox_efficiency")
    )
    resistance = np.array(actuators.resistances)  # at the windings' temperature
    motor_speed = ratio * omega
    motor_torque = np.where(tau * omega >= 0, tau / (ratio * eta), tau * eta / ratio)
    current = motor_torque / kt
    copper = current**2 * resistance
    electrical = motor_torque * motor_speed + copper
    battery = np.where(electrical >= 0, electrical, regeneration * electrical)
    voltage = np.abs(kt * motor_speed) + np.abs(current) * resistance
    return MotorSamples(motor_speed, motor_torque, current, copper, electrical, battery, voltage)


def require_samples(
    torques: npt.ArrayLike, speeds: npt.ArrayLike, legs: Sequence[str] | None
) -> tuple[ArrayF, ArrayF, tuple[str, ...]]:
    """One period's τ and ω as (N, L, 3) finite arrays, and the legs' names (L,).

    Raises:
        ParameterError: The arrays differ in shape, are not (N, L, 3), hold NaN or
            infinity, or the legs' names do not match them (six legs by default).

    """
    tau, omega = np.asarray(torques, dtype=float), np.asarray(speeds, dtype=float)
    if tau.ndim != 3 or tau.shape[0] < 1 or tau.shape[2] != 3:
        raise ParameterError("torques", tau.shape, "must be (samples, legs, 3) [N·m]")
    if omega.shape != tau.shape:
        raise ParameterError("speeds", omega.shape, f"must have the torques' shape {tau.shape}")
    for name, values in (("torques", tau), ("speeds", omega)):
        if not np.isfinite(values).all():
            raise ParameterError(name, "NaN or infinity", "must be finite")
    names = LEG_NAMES if legs is None else tuple(legs)
    if len(names) != tau.shape[1]:
        raise ParameterError("legs", names, f"must name the {tau.shape[1]} legs")
    return tau, omega, names


def require_actuators(actuators: object) -> Actuators:
    """``actuators`` if it is an :class:`~hexaleg.actuators.Actuators`; else a ParameterError."""
    return require_instance("actuators", actuators, Actuators, "the root, hip and knee Actuators")
