"""Report part: manipulability (paper §5): optimum pose, Table 6, w_A and Fig 10–11."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.design import l3_ratio_grid
from hexaleg.output.figures import table5_surfaces, write_manipulability_figures
from hexaleg.output.report.document import Figure, Section, table, write_csv
from hexaleg.output.report.part import Part, ReportData
from hexaleg.output.report.workspace import PAPER_SWEEPS
from hexaleg.paper import CLAIMED_W_A_PEAK
from hexaleg.paper.reproduction import digits_transposed, table6_reproduction
from hexaleg.robot.leg_model import LegModel
from hexaleg.swing.manipulability import (
    AverageManipulabilityMap,
    ManipulabilityAnalysis,
    ManipulabilitySurface,
    analyze_manipulability,
    average_manipulability_map,
)


@dataclass(frozen=True)
class ManipulabilityRecord:
    """Manipulability of the design's leg and over the paper's grid of designs.

    Attributes:
        analysis: Optimum pose and w_A of the design's leg.
        average_map: w_A over the swept coxa ratios × the sweep's tibia ratios (Fig 11).
        surfaces: w over (θ2, θ3) for the design, then Table 5's designs (Fig 10).
        table6: Table 6 recomputed beside the printed values.

    """

    analysis: ManipulabilityAnalysis
    average_map: AverageManipulabilityMap
    surfaces: tuple[ManipulabilitySurface, ...]
    table6: list[dict[str, Any]]


def compute(data: ReportData) -> ManipulabilityRecord:
    """The design's optimum pose and w_A, the w_A map, the surfaces and Table 6."""
    design, options = data.design, data.options
    analysis = analyze_manipulability(design, LegModel(design))
    return ManipulabilityRecord(
        analysis=analysis,
        average_map=average_manipulability_map(
            options.swept_l1_ratios,
            l3_ratio_grid(options.l3_points),
            design.leg_length,
            design.manipulability_limits,
        ),
        surfaces=tuple(table5_surfaces(analysis)),
        table6=table6_reproduction(design.manipulability_limits),
    )


def section(data: ReportData) -> Section:
    """Manipulability: optimum pose, Table 6, w_A peaks (§5)."""
    record = data[ManipulabilityRecord]
    analysis, w_map = record.analysis, record.average_map
    o = analysis.optimum
    return Section(
        "Manipulability (paper §5)",
        (
            f"Optimum pose of this leg within eq 26: θ2 = {math.degrees(o.theta2):.4f}°, "
            f"θ3 = {math.degrees(o.theta3):.4f}°, w = {o.w:.5g} m³ (condition number "
            f"{analysis.optimum_indices.condition_number:.3g}, smallest singular value "
            f"{analysis.optimum_indices.min_singular_value:.3g} m/rad). Average manipulability "
            f"w_A = {analysis.average_rectangular:.5g} m³ on eq 26's rectangle, "
            f"{analysis.average_improved:.5g} m³ on the improved domain.",
            "**Table 6 reproduced** (angles in degrees, w in mm³ as printed). hexaleg's optimum "
            "is bounded L-BFGS-B from the best local maxima of a 1° grid; the last columns "
            "evaluate eq 25 at the paper's own angles.",
            _table6(record.table6),
            _table6_flags(record.table6),
            Figure(
                "manipulability_surface",
                "Manipulability w over the hip and knee angles for this design's leg",
            ),
            Figure(
                "manipulability_surfaces_table5",
                "The same for the Table 5 designs (the paper's Fig 10)",
            ),
            Figure(
                "manipulability_average_map",
                "Average manipulability w_A against tibia ratio, for each coxa ratio, on both "
                "joint domains; the dashed line is the paper's claim (the paper's Fig 11)",
            ),
            table(
                [
                    "l1 ratio",
                    "w_A refined peak l3 ratio, rectangular",
                    "w_A refined peak l3 ratio, improved",
                ],
                [
                    (f"{r1:.2f}", f"{a:.3f}", f"{b:.3f}")
                    for r1, a, b in zip(
                        w_map.l1_ratios, w_map.peak_rectangular, w_map.peak_improved, strict=True
                    )
                ],
            ),
            f"The paper says w_A peaks at l3 ≈ {CLAIMED_W_A_PEAK} (§5.4). On eq 26's rectangular "
            "domain hexaleg "
            f"finds {w_map.peak_rectangular.min():.3f}–{w_map.peak_rectangular.max():.3f}: the "
            "claim does **not** hold there. On the improved domain the peak is "
            f"{w_map.peak_improved.min():.3f}–{w_map.peak_improved.max():.3f}, near the claim "
            "for the smallest coxa ratios only.",
        ),
    )


def _table6(rows: list[dict[str, Any]]) -> str:
    return table(
        [
            "l1 [mm]",
            "θ2 paper",
            "θ2 hexaleg",
            "θ3 paper",
            "θ3 hexaleg",
            "w paper",
            "eq 25 at paper's angles",
            "w hexaleg",
            "paper's w",
        ],
        [
            (
                f"{r['l1_mm']:g}",
                f"{r['paper_theta2_deg']:.4f}",
                f"{r['hexaleg_theta2_deg']:.4f}",
                f"{r['paper_theta3_deg']:.4f}",
                f"{r['hexaleg_theta3_deg']:.4f}",
                f"{r['paper_w_mm3']:.4e}",
                f"{r['eq25_at_paper_angles_mm3']:.5e}",
                f"{r['hexaleg_w_mm3']:.5e}",
                "agrees" if r["paper_w_matches_eq25"] else "**misprinted**",
            )
            for r in rows
        ],
    )


def _table6_flags(rows: list[dict[str, Any]]) -> str:
    flagged = [r for r in rows if not r["paper_w_matches_eq25"]]
    if not flagged:
        return "Every printed w agrees with eq 25 at the paper's angles."
    notes = []
    for r in flagged:
        printed, computed = r["paper_w_mm3"], r["eq25_at_paper_angles_mm3"]
        note = (
            f"l1 = {r['l1_mm']:g} mm prints {printed:.4e} but eq 25 at its own angles "
            f"gives {computed:.4e}"
        )
        if digits_transposed(printed, computed):
            note += " (the same digits, two transposed)"
        notes.append(note)
    return "Flagged: " + "; ".join(notes) + "."


def average_manipulability_rows(w_map: AverageManipulabilityMap) -> list[dict[str, Any]]:
    """w_A on both domains for every design of the map (``average_manipulability.csv``)."""
    return [
        {"l1_ratio": r1, "l3_ratio": r3, "w_a_rectangular_m3": a, "w_a_improved_m3": b}
        for i, r1 in enumerate(w_map.l1_ratios)
        for r3, a, b in zip(w_map.l3_ratios, w_map.rectangular[i], w_map.improved[i], strict=True)
    ]


# -- sections -----------------------------------------------------------------------------


def write_files(data: ReportData, out: Path) -> None:
    """Fig 10–11, ``table6.csv`` and ``average_manipulability.csv``."""
    record = data[ManipulabilityRecord]
    write_manipulability_figures(
        record.analysis, record.average_map, out, record.surfaces, svg=data.options.svg
    )
    write_csv(out / "table6.csv", record.table6)
    write_csv(out / "average_manipulability.csv", average_manipulability_rows(record.average_map))


def to_json(record: ManipulabilityRecord) -> dict[str, Any]:
    """``manipulability``, ``table6`` and ``average_manipulability_peaks``."""
    w_map = record.average_map
    return {
        "manipulability": record.analysis.to_dict(),
        "table6": record.table6,
        "average_manipulability_peaks": [
            {"l1_ratio": r1, "rectangular_peak_l3_ratio": a, "improved_peak_l3_ratio": b}
            for r1, a, b in zip(
                w_map.l1_ratios, w_map.peak_rectangular, w_map.peak_improved, strict=True
            )
        ],
    }


PART = Part(
    ManipulabilityRecord,
    compute,
    section,
    step="manipulability",
    files=write_files,
    json=to_json,
    holds=PAPER_SWEEPS,
)
