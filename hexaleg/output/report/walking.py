"""The report's "Walking" section: the grid walking the default gait, against the sequel's claim.

Presentation only: the numbers come from :class:`~hexaleg.study.walking.WalkingComparison`
(computed with the report's data) and the study's ``gait_*`` columns. :func:`walking_section`
is one of the report's sections; :func:`write_walking_figure` writes its figure.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pandas as pd

from hexaleg.output.figures import save
from hexaleg.output.figures_gait import walking_study_figure
from hexaleg.output.report.sections import Section, figure, table
from hexaleg.study.walking import ENERGY, TORQUE, WalkingComparison

FIGURE = "study_walking.png"


def write_walking_figure(study: pd.DataFrame, out: Path) -> Path:
    """Write the study's peak torque and cost of transport figure into ``out``."""
    return save(walking_study_figure(study), out / FIGURE)


def walking_section(comparison: WalkingComparison | None) -> Section:
    """The section: the gait, the best walking legs against the paper's, and the figure."""
    if comparison is None:
        return Section("Walking", ("No design of the grid walks the default gait.",))
    gait = comparison.gait
    rows = [
        _row("the paper's leg", comparison.reference),
        _row("least peak torque", comparison.least_torque),
        _row("least cost of transport", comparison.least_energy),
    ]
    blocks = (
        f"Every design of the grid walks one period of the default gait: a "
        f"{gait['pattern']} at {gait['speed']:.2g} m/s (period {gait['period']:g} s, stride "
        f"{gait['stride']:g} m, step height {gait['step_height']:g} m), no payload; "
        f"{comparison.walking} of the {comparison.designs} designs can (the others break a "
        "stance limit or reach on the way). Torques from Pinocchio's inverse dynamics on the "
        "whole robot, the standing feet sharing the load by least forces.",
        table(
            ["leg", "l1/L", "l3/L", "peak torque [N·m]", "cost of transport", "max speed [m/s]"],
            rows,
        ),
        _claim(comparison),
        figure(
            FIGURE,
            "Walking the default gait: peak joint torque and cost of transport against "
            "the tibia ratio, per coxa ratio",
        ),
    )
    return Section("Walking", blocks)


def _row(name: str, row: dict[str, Any]) -> list[str]:
    return [
        name,
        f"{row['l1_ratio']:.3g}",
        f"{row['l3_ratio']:.3g}",
        f"{row[TORQUE]:.1f}",
        f"{row[ENERGY]:.4f}",
        f"{row['gait_max_speed']:.3f}",
    ]


def _claim(comparison: WalkingComparison) -> str:
    """The sequel's claim, and what the grid shows, whatever it is."""
    torque, energy = comparison.torque_saving, comparison.energy_saving
    if math.isnan(torque) or math.isnan(energy):
        return (
            "The paper's 0.2/0.4/0.4 leg cannot walk this gait, so the sequel's claim (an "
            "optimized leg cutting peak joint torque and energy by over 20 %) has no "
            "reference here."
        )
    energy_of_torque, torque_of_energy = comparison.cross_savings
    verdict = (
        "both exceed the sequel's 20 %"
        if min(torque, energy) > 0.2
        else "the torque saving exceeds the sequel's 20 %, the energy saving does not"
        if torque > 0.2
        else "neither reaches the sequel's 20 %"
    )
    return (
        "The sequel (Liu et al., *Dynamic Modeling and Dimensional Optimization of Legged "
        "Mechanisms for Construction Robots*) reports that optimizing the segment lengths "
        "cuts peak joint torque and energy by over 20 %. On this grid, walking this gait, "
        f"the least-torque leg saves {100 * torque:.0f} % of the paper's leg's peak torque "
        f"(and {100 * energy_of_torque:.0f} % of its energy), the least-energy leg "
        f"{100 * energy:.0f} % of its cost of transport (and {100 * torque_of_energy:.0f} % "
        f"of its peak torque): {verdict}. {_why(comparison)}"
    )


def _why(comparison: WalkingComparison) -> str:
    """Which joint carries the peak, how the best leg differs, and what it gives up."""
    reference, best = comparison.reference, comparison.least_torque
    joint = max(("root", "hip", "knee"), key=lambda j: reference[f"gait_peak_{j}_torque"])
    femur = 1 - float(best["l1_ratio"]) - float(best["l3_ratio"])
    paper_femur = 1 - float(reference["l1_ratio"]) - float(reference["l3_ratio"])
    slower = float(best["gait_max_speed"]) < float(reference["gait_max_speed"])
    return (
        f"The paper's leg's peak is at its {joint}; the least-torque leg's femur is "
        f"{femur:.2f} of the leg against {paper_femur:.2f}, and it walks "
        + ("slower" if slower else "at least as fast")
        + f" within its ratings ({float(best['gait_max_speed']):.2f} against "
        f"{float(reference['gait_max_speed']):.2f} m/s, {best['gait_max_speed_limited_by']})."
    )
