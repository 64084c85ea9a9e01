"""Electrical: the motor equations turn a gait's joint torques and speeds into energy.

:mod:`.equations` holds the equations (current, copper loss, electrical and battery
power, voltage needed, per sample), :mod:`.ratings` each joint against its actuator's
ratings (which binds first, which are exceeded) and :mod:`.period` one gait period's
figures (energy, power, cost of transport, battery runtime and range):
:func:`analyze_electrical`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

__all__ = [
    "BatteryUse",
    "ElectricalResult",
    "JointElectrical",
    "MotorSamples",
    "RatingBinding",
    "RatingLoads",
    "analyze_electrical",
    "binding_rating",
    "motor_loads",
    "motor_samples",
]

__getattr__, __dir__ = lazy_exports(__name__)

if TYPE_CHECKING:  # where each name is from: read by type checkers, the docs and lazy_exports
    from hexaleg.electrical.equations import MotorSamples, motor_samples
    from hexaleg.electrical.period import (
        BatteryUse,
        ElectricalResult,
        JointElectrical,
        analyze_electrical,
    )
    from hexaleg.electrical.ratings import RatingBinding, RatingLoads, binding_rating, motor_loads
