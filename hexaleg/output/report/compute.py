"""Step 1 of the report: run every analysis on one design and the paper's sweeps.

:func:`compute_report` returns a frozen :class:`ReportData` holding every result the
report shows. It writes nothing: the sections turn it into text, the renderer into files.
"""

from __future__ import annotations

import sys
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np
import pandas as pd
from tqdm import tqdm

from hexaleg._typing import ArrayF
from hexaleg._version import __version__
from hexaleg.design import MAX_L3_POINTS, HexapodDesign, l3_ratio_grid
from hexaleg.exceptions import HexalegError
from hexaleg.paper import L1_RATIOS, L3_RATIO_POINTS
from hexaleg.paper.reproduction import table5_reproduction, table6_reproduction
from hexaleg.robot.model import HexapodModel, LegModel
from hexaleg.stance.axis_locked import axis_locked_flexibility
from hexaleg.stance.extremes import FlexibilityResult, FlexibilityWarning
from hexaleg.stance.free_coupled import free_flexibility
from hexaleg.study.executors import local_pool, max_workers
from hexaleg.study.recommendation import Recommendation, recommend
from hexaleg.study.sensitivity import sensitivity_table
from hexaleg.study.sweep import StudySpec, peak_table, study_table, sweep
from hexaleg.swing.manipulability import (
    AverageManipulabilityMap,
    ManipulabilityAnalysis,
    analyze_manipulability,
    average_manipulability_map,
)
from hexaleg.swing.workspace import (
    MAX_SAMPLES,
    WorkspaceAnalysis,
    analyze_workspace,
    improved_area_closed_form,
)

T = TypeVar("T")

MAX_SENSITIVITY_POINTS = 400
"""Most tibia ratios per variant in the sensitivity table (8 variants × 2 coxa ratios)."""


@dataclass(frozen=True)
class ReportOptions:
    """How much of the paper's sweeps the report runs.

    Attributes:
        l3_points: Tibia ratios per coxa ratio in the sweeps (the paper: 80).
        sensitivity_points: Tibia ratios per coxa ratio in the posture sensitivity table.
        monte_carlo_samples: Samples of the Monte Carlo workspace.
        workers: Local processes for the flexibility study (default: CPUs).
        progress: Show a progress bar; by default only on a terminal.

    """

    l3_points: int = L3_RATIO_POINTS
    sensitivity_points: int = 40
    monte_carlo_samples: int = 20_000
    workers: int | None = None
    progress: bool | None = None

    def __post_init__(self) -> None:
        for name, (lower, upper) in {
            "l3_points": (2, MAX_L3_POINTS),
            "sensitivity_points": (2, MAX_SENSITIVITY_POINTS),
            "monte_carlo_samples": (1, MAX_SAMPLES),
            "workers": (1, max_workers()),
        }.items():
            value = getattr(self, name)
            if value is not None and not lower <= value <= upper:
                raise HexalegError(f"{name} = {value} is not valid: must lie in {lower}..{upper}")


@dataclass(frozen=True)
class ReportData:
    """Every result the report shows, computed once.

    Attributes:
        design: The analysed design.
        options: The sweep sizes used.
        model: The design's Pinocchio model (its URDF is ``model.urdf``).
        workspace: Swing-phase workspace of the design's leg (§4).
        table5: Table 5's designs recomputed (see :mod:`hexaleg.paper.reproduction`).
        manipulability: Optimum pose and w_A of the design's leg (§5).
        average_map: w_A over the paper's coxa ratios × the sweep's tibia ratios (Fig 11).
        table6: Table 6 recomputed beside the printed values.
        axis: Axis-locked flexibility, all six feet down (§6).
        free: Free-coupled flexibility, all six feet down.
        study_spec: The FB sweep (Fig 14–15) on the design's body and posture.
        study: Its table, one row per design.
        sensitivity: Peak FB per posture/body variant.
        recommendation: Recommended segment ratios and the scores behind them.

    """

    design: HexapodDesign
    options: ReportOptions
    model: HexapodModel
    workspace: WorkspaceAnalysis
    table5: list[dict[str, Any]]
    manipulability: ManipulabilityAnalysis
    average_map: AverageManipulabilityMap
    table6: list[dict[str, Any]]
    axis: FlexibilityResult
    free: FlexibilityResult
    study_spec: StudySpec
    study: pd.DataFrame
    sensitivity: pd.DataFrame
    recommendation: Recommendation

    @property
    def study_peaks(self) -> pd.DataFrame:
        """Per coxa ratio, the tibia ratio of the largest FB and that FB."""
        return peak_table(self.study)

    def to_json(self) -> dict[str, Any]:
        """The report's numbers as ``report.json`` holds them (SI units, radians)."""
        rec = self.recommendation
        total = self.design.leg_length
        w_map = self.average_map
        return _plain(
            {
                "hexaleg_version": __version__,
                "design": self.design.as_dict(),
                "workspace": self.workspace.to_dict(),
                "table5": self.table5,
                "manipulability": self.manipulability.to_dict(),
                "table6": self.table6,
                "average_manipulability_peaks": [
                    {"l1_ratio": r1, "rectangular_peak_l3_ratio": a, "improved_peak_l3_ratio": b}
                    for r1, a, b in zip(
                        w_map.l1_ratios, w_map.peak_rectangular, w_map.peak_improved, strict=True
                    )
                ],
                "flexibility": {"axis": self.axis.to_dict(), "free": self.free.to_dict()},
                "study_peaks": self.study_peaks.to_dict(orient="records"),
                "sensitivity": self.sensitivity.to_dict(orient="records"),
                "recommendation": {
                    "l1_ratio": rec.l1_ratio,
                    "l2_ratio": rec.l2_ratio,
                    "l3_ratio": rec.l3_ratio,
                    "l3_band": list(rec.l3_band),
                    "peaks": rec.peaks.to_dict(orient="records"),
                    "lengths_m": [rec.l1_ratio * total, rec.l2_ratio * total, rec.l3_ratio * total],
                },
            }
        )


def compute_report(design: HexapodDesign, options: ReportOptions) -> ReportData:
    """Run every analysis of the report on ``design``, with a progress bar on a terminal."""
    show = sys.stdout.isatty() if options.progress is None else options.progress
    with tqdm(total=7, disable=not show, file=sys.stderr, unit="step") as bar:

        def step(name: str, run: Callable[[], T]) -> T:
            bar.set_description(name)
            result = run()
            bar.update()
            return result

        l3_ratios = l3_ratio_grid(options.l3_points)
        model = step("model and URDF", lambda: HexapodModel(design))
        workspace = step(
            "workspace", lambda: analyze_workspace(design, samples=options.monte_carlo_samples)
        )
        manipulability, average_map = step(
            "manipulability", lambda: _manipulability(design, l3_ratios)
        )
        axis, free = step("body flexibility", lambda: _flexibility(design, model))
        spec = StudySpec(tuple(L1_RATIOS), tuple(l3_ratios), design.leg_length, base=design)
        study = step("design study", lambda: _study(spec, options.workers))
        sensitivity = step(
            "posture sensitivity",
            lambda: sensitivity_table(
                (L1_RATIOS[1], L1_RATIOS[3]),
                tuple(l3_ratio_grid(options.sensitivity_points)),
                design.leg_length,
                base=design,
            ),
        )
        recommendation = step(
            "recommendation", lambda: _recommendation(average_map, study, design.leg_length)
        )
    return ReportData(
        design=design,
        options=options,
        model=model,
        workspace=workspace,
        table5=table5_reproduction(
            design.leg_length, design.improved_limits, design.workspace_limits
        ),
        manipulability=manipulability,
        average_map=average_map,
        table6=table6_reproduction(design.manipulability_limits),
        axis=axis,
        free=free,
        study_spec=spec,
        study=study,
        sensitivity=sensitivity,
        recommendation=recommendation,
    )


def _manipulability(
    design: HexapodDesign, l3_ratios: ArrayF
) -> tuple[ManipulabilityAnalysis, AverageManipulabilityMap]:
    analysis = analyze_manipulability(design, LegModel(design))
    average_map = average_manipulability_map(
        L1_RATIOS, l3_ratios, design.leg_length, design.manipulability_limits
    )
    return analysis, average_map


def _flexibility(
    design: HexapodDesign, model: HexapodModel
) -> tuple[FlexibilityResult, FlexibilityResult]:
    axis = axis_locked_flexibility(design, "all", model)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexibilityWarning)  # reported as "converged"
        free = free_flexibility(design, "all", model)
    return axis, free


def _study(spec: StudySpec, workers: int | None) -> pd.DataFrame:
    with local_pool(workers) as pool:
        return study_table(spec, sweep(spec, pool))


def _recommendation(
    average_map: AverageManipulabilityMap, study: pd.DataFrame, total: float
) -> Recommendation:
    """Recommend ratios from the three metrics on the (coxa, tibia) ratio grid."""
    r1, r3 = average_map.l1_ratios, average_map.l3_ratios
    l2 = (1 - r1[:, None] - r3[None, :]) * total
    area = np.where(l2 > 0, improved_area_closed_form(l2, r3[None, :] * total), np.nan)
    fb = np.full(area.shape, np.nan)
    for i, ratio in enumerate(r1):
        rows = study[np.isclose(study["l1_ratio"], ratio)]
        fb[i] = rows["fb"].to_numpy(dtype=float) if "fb" in rows else np.nan
    return recommend(r1, r3, area, average_map.improved, fb)


def _plain(value: Any) -> Any:
    """NumPy scalars and arrays to plain Python for JSON."""
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    return value
