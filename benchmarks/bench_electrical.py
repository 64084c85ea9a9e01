"""Workload on the motor equations: one gait period's electrical figures beside the period."""

from __future__ import annotations

from harness import Row, median_times

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.actuator_catalog import shipped_catalog
from hexaleg.actuators import Actuators
from hexaleg.battery import Battery
from hexaleg.electrical import analyze_electrical
from hexaleg.gait import Gait, analyze_gait

GRAVITY = 9.81
CATALOG_ENTRIES = ("hd_cha_17a_e_100", "hd_cha_25a_100", "hd_cha_20a_100")
"""Root, hip and knee actuators of the workload: catalog entries that hold the default gait."""


def bench_electrical(repeats: int) -> list[Row]:
    """The default design's period with and without its electrical figures (≤ 1.2×)."""
    design = HexapodDesign()
    model = HexapodModel(design)
    gait = Gait()
    catalog = shipped_catalog()
    actuators = Actuators(*(catalog.entry(name).actuator for name in CATALOG_ENTRIES))
    battery = Battery(capacity=500.0, specific_energy=200.0, regeneration=0.3)

    def period():
        return analyze_gait(design, gait, model=model, limits=False)

    def period_and_electrical():
        walked = period()
        result = analyze_electrical(
            walked.joint_torques,
            walked.joint_velocities,
            gait.period,
            gait.speed,
            walked.mass,
            GRAVITY,
            actuators,
            battery,
            walked.legs,
        )
        return result.over_rating  # the records too, as a command would print them

    t_without, t_with = median_times([period, period_and_electrical], repeats, min_time=0.0)
    name = f"gait period + motor equations ({gait.samples} samples, six legs)"
    return [
        Row(name, "hexaleg analyze_gait(limits=False)", t_without, None, None),
        Row(
            name,
            "hexaleg analyze_gait + analyze_electrical",
            t_with,
            t_with / t_without,
            None,
            "≤ 1.2× without",
            note="ratio here: with / without, measured round-robin in one process",
        ),
    ]
