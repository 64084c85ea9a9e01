"""The metrics of one walked gait period: peaks, RMS, costs, energy, ZMP margin, motors.

What :func:`~hexaleg.study.evaluation.evaluate` takes from a feasible period
(:class:`~hexaleg.gait.analysis.GaitAnalysis`), and why a metric through the motors has no
value when the design has no actuators or no battery.
"""

from __future__ import annotations

import math

from hexaleg.gait.analysis import GaitAnalysis
from hexaleg.limits import LEG_JOINTS

__all__ = ["ELECTRICAL_METRICS", "period_values", "unmeasured_electrical"]

ELECTRICAL_METRICS = (
    "energy_per_km", "electrical_cost_of_transport", "continuous_load", "battery_range",
)  # fmt: skip
"""The metrics of the period through the design's motors (:mod:`hexaleg.electrical`)."""


def _electrical_values(walked: GaitAnalysis) -> dict[str, float]:
    """The period's metrics through the motors: energy, cost, continuous load, range."""
    electrical = walked.electrical
    if electrical is None:
        return dict.fromkeys(ELECTRICAL_METRICS, math.nan)
    ratios = electrical.ratings.ratios[1]  # RMS over continuous torque (L, 3)
    battery = electrical.battery
    return {
        "energy_per_km": electrical.energy_per_km,
        "electrical_cost_of_transport": electrical.cost_of_transport,
        "continuous_load": float(ratios.max()),
        "battery_range": math.nan if battery is None else battery.range,
    }


def unmeasured_electrical(walked: GaitAnalysis) -> dict[str, str]:
    """Why a metric through the motors has no value: no actuators, or no battery."""
    if walked.design.actuators is None:
        return dict.fromkeys(ELECTRICAL_METRICS, "the design has no [actuators]")
    if walked.design.battery is None:
        return {"battery_range": "the design has no [battery]"}
    return {}


def period_values(walked: GaitAnalysis) -> dict[str, float]:
    """The metrics of a feasible gait period: peaks, RMS, cost, energy per km, ZMP margin."""
    metrics = walked.metrics
    distance = walked.gait.speed * walked.gait.period  # per period [m]
    values = {
        "gait_peak_torque": max(metrics.peak_torque.values()),
        "mechanical_cost_of_transport": metrics.cost_of_transport,
        "mechanical_energy_per_km": metrics.positive_work / distance * 1000 / 3600,
        "min_zmp_margin": walked.min_zmp_margin,
        **_electrical_values(walked),
    }
    for joint in LEG_JOINTS:
        values[f"gait_peak_{joint}_torque"] = metrics.peak_torque[joint]
        values[f"gait_rms_{joint}_torque"] = metrics.rms_torque[joint]
    return values
