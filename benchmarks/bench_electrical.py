"""Workload on the motor equations: a gait period through its motors beside one without."""

from __future__ import annotations

from harness import Row, median_times

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.actuator_catalog import shipped_catalog
from hexaleg.actuators import Actuators
from hexaleg.battery import Battery
from hexaleg.gait import Gait, analyze_gait

CATALOG_ENTRIES = ("hd_cha_17a_e_100", "hd_cha_25a_100", "hd_cha_20a_100")
"""Root, hip and knee actuators of the workload (catalog entries)."""


def bench_electrical(repeats: int) -> list[Row]:
    """The default design's period, and the same with actuators and a battery (≤ 1.2×)."""
    catalog = shipped_catalog()
    actuators = Actuators(*(catalog.entry(name).actuator for name in CATALOG_ENTRIES))
    # one bus for the catalog's 48 V root and 680 V hip and knee drives: the 680 V ones'
    battery = Battery(capacity=500.0, specific_energy=200.0, regeneration=0.3, voltage=680.0)
    bare = HexapodDesign()
    motors = bare.replace(actuators=actuators, battery=battery)
    models = HexapodModel(bare), HexapodModel(motors)
    gait = Gait()

    def period():
        return analyze_gait(bare, gait, model=models[0], limits=False).over_rating

    def period_and_electrical():
        walked = analyze_gait(motors, gait, model=models[1], limits=False)
        return walked.over_rating  # the records too, as a command would print them

    t_without, t_with = median_times([period, period_and_electrical], repeats, min_time=0.0)
    name = f"gait period + motor equations ({gait.samples} samples, six legs)"
    return [
        Row(name, "hexaleg analyze_gait, no actuators", t_without, None, None),
        Row(
            name,
            "hexaleg analyze_gait, actuators and battery",
            t_with,
            t_with / t_without,
            None,
            "≤ 1.2× without",
            note="ratio here: with / without, measured round-robin in one process",
        ),
    ]
