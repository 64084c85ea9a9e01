"""Report part: the swing-phase workspace (paper §4): areas, Fig 5–8 and Table 5."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.output.figures import write_workspace_figures
from hexaleg.output.report.document import Figure, Section, table, write_csv
from hexaleg.output.report.part import Part, ReportData, where_legs_are_the_designs
from hexaleg.paper import L1_RATIOS
from hexaleg.paper.reproduction import table5_reproduction
from hexaleg.swing.workspace import CoxaSeries, WorkspaceAnalysis, analyze_workspace, coxa_series


@dataclass(frozen=True)
class WorkspaceRecord:
    """The design's leg workspace and the paper's coxa series.

    Attributes:
        analysis: Monte Carlo cloud and planar workspaces of the design's leg.
        series: Fig 8: the improved workspace per coxa ratio, area against tibia ratio.
        table5: Table 5's designs recomputed (see :mod:`hexaleg.paper.reproduction`).

    """

    analysis: WorkspaceAnalysis
    series: CoxaSeries
    table5: list[dict[str, Any]]


def compute(data: ReportData) -> WorkspaceRecord:
    """Workspace of the design's leg, Fig 8's series and Table 5."""
    design = data.design
    return WorkspaceRecord(
        analysis=analyze_workspace(design, samples=data.options.monte_carlo_samples),
        series=coxa_series(design, L1_RATIOS),
        table5=table5_reproduction(
            design.leg_length, design.improved_limits, design.workspace_limits
        ),
    )


def section(data: ReportData) -> Section:
    """Swing phase: workspace areas, figures and Table 5 (§4)."""
    record = data[WorkspaceRecord]
    area = record.analysis.to_dict()["area"]
    return Section(
        "Swing phase: workspace (paper §4)",
        (
            f"Planar workspace of this leg at θ1 = 0: **{area['rectangular']:.4f} m²** on the "
            f"rectangular domain (Table 3), **{area['improved']:.4f} m²** on the improved domain "
            f"(Table 4), against eq 16's 2π·l2·l3/3 = {area['improved_closed_form']:.4f} m². "
            "Areas are exact boundary integrals (Green's theorem), not pixel counts.",
            Figure(
                "workspace_monte_carlo",
                "Reachable foot positions of one leg, by Monte Carlo (Table 2 limits; the paper's "
                "Fig 5)",
            ),
            Figure(
                "workspace_planar",
                "Foot workspace in the leg's plane on the rectangular and improved joint domains "
                "(the paper's Fig 6–7)",
            ),
            Figure(
                "workspace_l1_series",
                "Improved workspace for each coxa ratio, its area, and the area against tibia "
                "ratio: it peaks at femur = tibia (the paper's Fig 8)",
            ),
            "Table 5 designs (1 m leg; lengths in mm as in the paper): the numerical improved "
            "area equals eq 16 to rounding error, and shrinks as the coxa grows.",
            _table5(record.table5),
        ),
    )


def _table5(rows: list[dict[str, Any]]) -> str:
    return table(
        [
            "l1 ratio",
            "l1, l2, l3 [mm]",
            "improved area [m²]",
            "eq 16 [m²]",
            "rel. diff",
            "rectangular [m²]",
        ],
        [
            (
                f"{r['l1_ratio']:.2f}",
                f"{r['l1_mm']:g}, {r['l2_mm']:g}, {r['l3_mm']:g}",
                f"{r['improved_area_m2']:.6f}",
                f"{r['eq16_area_m2']:.6f}",
                f"{r['relative_difference']:.1e}",
                f"{r['rectangular_area_m2']:.6f}",
            )
            for r in rows
        ],
    )


def write_files(data: ReportData, out: Path) -> None:
    """Fig 5–8 and ``table5.csv``."""
    record = data[WorkspaceRecord]
    write_workspace_figures(record.analysis, out, record.series, svg=data.options.svg)
    write_csv(out / "table5.csv", record.table5)


def to_json(record: WorkspaceRecord) -> dict[str, Any]:
    """``workspace`` and ``table5``."""
    return {"workspace": record.analysis.to_dict(), "table5": record.table5}


PAPER_SWEEPS = where_legs_are_the_designs(
    "The paper's workspace and manipulability sweeps (Fig 8–11) and its Tables 5 and 6",
    "they reproduce the paper's leg over its segment ratios; your robot's own legs are "
    "measured in the swing-phase section instead",
)
"""Where the paper's swing-phase sections hold: every leg the paper's leg of l1, l2, l3."""

PART = Part(WorkspaceRecord, compute, section, step="workspace", files=write_files, json=to_json,
            holds=PAPER_SWEEPS)  # fmt: skip
