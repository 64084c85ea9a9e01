"""Step 1 of the report: run every analysis on one design and the paper's sweeps.

:func:`compute_report` returns a frozen :class:`ReportData` holding every result the
report shows. It writes nothing: the sections turn it into text, the renderer into files.
"""

from __future__ import annotations

import math
import sys
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

import numpy as np
import pandas as pd
from tqdm import tqdm

from hexaleg._checks import require_int
from hexaleg._typing import ArrayF
from hexaleg._version import __version__
from hexaleg.design import MAX_L3_POINTS, HexapodDesign, l3_ratio_grid, require_ratio
from hexaleg.exceptions import HexalegError
from hexaleg.paper import L1_RATIOS, L3_RATIO_POINTS
from hexaleg.paper.reproduction import table5_reproduction, table6_reproduction
from hexaleg.robot.model import HexapodModel, LegModel
from hexaleg.stance.axis_locked import axis_locked_flexibility
from hexaleg.stance.extremes import FlexibilityResult, FlexibilityWarning
from hexaleg.stance.free_coupled import free_flexibility
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.statics.loads import LoadsAnalysis, loads_at_extremes
from hexaleg.study.executors import local_pool, max_workers
from hexaleg.study.metrics import design_metrics, ratio_metrics
from hexaleg.study.pareto import pareto_table
from hexaleg.study.recommendation import (
    PRACTICAL_L1_RATIO,
    Metrics,
    Recommendation,
    combined_score,
    recommend,
)
from hexaleg.study.sensitivity import FieldSweep, sensitivity_table
from hexaleg.study.sweep import MAX_L1_RATIOS, StudySpec, peak_table, study_table, sweep
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

MIN_L3_POINTS = 10
"""Fewest tibia ratios a report accepts: coarser grids cannot bracket the peaks [-]."""

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
        l1_ratios: Coxa ratios to sweep and recommend from (a fixed coxa: one ratio);
            by default the paper's four, recommending among the practical ones (≥ 0.10).
        collisions: The robot's own parts touching also stop the body, in the design's
            flexibility and in the study.
        sweep: A body field to sweep in the sensitivity table instead of the posture and
            body variants (``--sweep body_width=0.4:0.8:9``).

    """

    l3_points: int = L3_RATIO_POINTS
    sensitivity_points: int = 40
    monte_carlo_samples: int = 20_000
    workers: int | None = None
    progress: bool | None = None
    l1_ratios: tuple[float, ...] | None = None
    collisions: bool = False
    sweep: FieldSweep | None = None

    def __post_init__(self) -> None:
        if self.l1_ratios is not None:
            object.__setattr__(self, "l1_ratios", tuple(float(r) for r in self.l1_ratios))
            if not 1 <= len(self.l1_ratios) <= MAX_L1_RATIOS:
                raise HexalegError(f"l1_ratios: give 1 to {MAX_L1_RATIOS} coxa ratios")
            for ratio in self.l1_ratios:
                require_ratio("l1_ratios", ratio)
        for name, (lower, upper) in {
            "l3_points": (2, MAX_L3_POINTS),
            "sensitivity_points": (2, MAX_SENSITIVITY_POINTS),
            "monte_carlo_samples": (1, MAX_SAMPLES),
            "workers": (1, max_workers()),
        }.items():
            if getattr(self, name) is not None:
                require_int(name, getattr(self, name), lower, upper)
        if self.l3_points < MIN_L3_POINTS:
            raise HexalegError(
                f"l3_points = {self.l3_points} is too coarse to locate the peaks: "
                f"the report needs {MIN_L3_POINTS}..{MAX_L3_POINTS} tibia ratios"
            )

    @property
    def swept_l1_ratios(self) -> tuple[float, ...]:
        """The coxa ratios the sweeps cover [-]."""
        return self.l1_ratios or L1_RATIOS


@dataclass(frozen=True)
class Decision:
    """The user's design beside the recommended one, on the recommendation's scale.

    Attributes:
        yours: The user's design's metrics (:data:`~hexaleg.study.recommendation.METRICS`).
        your_score: Its combined score [-].
        recommended: The recommended ratios at the user's leg length, body and posture;
            ``None`` if that design cannot stand.
        recommended_metrics: The recommended design's metrics (NaN if it cannot stand).
        recommended_score: Its combined score [-].
        your_payload: The user's design's payload capacity [kg] (not in the score).
        recommended_payload: The recommended design's payload capacity [kg] (NaN if it
            cannot stand).

    """

    yours: Metrics
    your_score: float
    recommended: HexapodDesign | None
    recommended_metrics: Metrics
    recommended_score: float
    your_payload: float
    recommended_payload: float

    def to_json(self) -> dict[str, Any]:
        """JSON-ready form (metrics in m², m³ and 1)."""
        return {
            "yours": {
                "metrics": dict(self.yours),
                "score": self.your_score,
                "payload_capacity": self.your_payload,
            },
            "recommended": {
                "lengths_m": list(self.recommended.lengths) if self.recommended else None,
                "metrics": dict(self.recommended_metrics),
                "score": self.recommended_score,
                "payload_capacity": self.recommended_payload,
            },
        }


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
        sensitivity: Peak FB per posture/body variant, each relative to this design.
        recommendation: Recommended segment ratios and the scores behind them.
        decision: This design beside the recommended one, metric by metric.
        loads: Statics at the nominal stance and the axis-locked extremes.
        free_loads: Statics at the free-coupled extremes.
        pareto: The designs of the grid no other beats in area, w_A, FB and payload
            capacity at once, best score first (its first row is the Pareto recommendation).

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
    decision: Decision
    loads: LoadsAnalysis
    free_loads: LoadsAnalysis
    pareto: pd.DataFrame

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
                    "score": rec.score,
                    "maxima": rec.maxima,
                    "peaks": rec.peaks.to_dict(orient="records"),
                    "lengths_m": [rec.l1_ratio * total, rec.l2_ratio * total, rec.l3_ratio * total],
                },
                "decision": self.decision.to_json(),
                "loads": {
                    "axis": _without_design(self.loads.to_dict()),
                    "free": _without_design(self.free_loads.to_dict()),
                },
                "pareto_front": self.pareto.to_dict(orient="records"),
            }
        )


def compute_report(design: HexapodDesign, options: ReportOptions) -> ReportData:
    """Run every analysis of the report on ``design``, with a progress bar on a terminal."""
    show = sys.stdout.isatty() if options.progress is None else options.progress
    with tqdm(total=8, disable=not show, file=sys.stderr, unit="step") as bar:

        def step(name: str, run: Callable[[], T]) -> T:
            bar.set_description(name)
            result = run()
            bar.update()
            return result

        l3_ratios = l3_ratio_grid(options.l3_points)
        l1_ratios = options.swept_l1_ratios
        model = step("model and URDF", lambda: HexapodModel(design))
        workspace = step(
            "workspace", lambda: analyze_workspace(design, samples=options.monte_carlo_samples)
        )
        manipulability, average_map = step(
            "manipulability", lambda: _manipulability(design, l1_ratios, l3_ratios)
        )
        axis, free = step(
            "body flexibility", lambda: _flexibility(design, model, options.collisions)
        )
        spec = StudySpec(
            l1_ratios,
            tuple(l3_ratios),
            design.leg_length,
            base=design,
            collisions=options.collisions,
        )
        study = step("design study", lambda: _study(spec, options.workers))
        sensitivity = step(
            "posture sensitivity",
            lambda: sensitivity_table(
                _sensitivity_l1_ratios(l1_ratios),
                tuple(l3_ratio_grid(options.sensitivity_points)),
                design.leg_length,
                base=design,
                variants=None if options.sweep is None else options.sweep.variants(),
            ),
        )
        template = StanceGeometry.from_model(model, "all")
        recommendation = step(
            "recommendation",
            lambda: _recommendation(design, template, average_map, study, options),
        )
        loads, free_loads = step(
            "statics", lambda: (loads_at_extremes(model, axis), loads_at_extremes(model, free))
        )
        decision = _decision(design, model, template, recommendation, loads, options.collisions)
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
        decision=decision,
        loads=loads,
        free_loads=free_loads,
        pareto=pareto_table(
            _candidates(_pareto_grid(average_map, study, design.leg_length), options.l1_ratios)
        ),
    )


def _manipulability(
    design: HexapodDesign, l1_ratios: Sequence[float], l3_ratios: ArrayF
) -> tuple[ManipulabilityAnalysis, AverageManipulabilityMap]:
    analysis = analyze_manipulability(design, LegModel(design))
    average_map = average_manipulability_map(
        l1_ratios, l3_ratios, design.leg_length, design.manipulability_limits
    )
    return analysis, average_map


def _flexibility(
    design: HexapodDesign, model: HexapodModel, collisions: bool
) -> tuple[FlexibilityResult, FlexibilityResult]:
    axis = axis_locked_flexibility(design, "all", model, collisions=collisions)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexibilityWarning)  # reported as "converged"
        free = free_flexibility(design, "all", model, collisions=collisions)
    return axis, free


def _study(spec: StudySpec, workers: int | None) -> pd.DataFrame:
    with local_pool(workers) as pool:
        return study_table(spec, sweep(spec, pool))


def _sensitivity_l1_ratios(l1_ratios: Sequence[float]) -> tuple[float, ...]:
    """The paper's second and fourth coxa ratios, or the smallest and largest swept."""
    if tuple(l1_ratios) == L1_RATIOS:
        return (L1_RATIOS[1], L1_RATIOS[3])
    return tuple(sorted({min(l1_ratios), max(l1_ratios)}))


def _recommendation(
    design: HexapodDesign,
    template: StanceGeometry,
    average_map: AverageManipulabilityMap,
    study: pd.DataFrame,
    options: ReportOptions,
) -> Recommendation:
    """Recommend ratios from the three metrics on the (coxa, tibia) ratio grid."""
    r1, r3 = average_map.l1_ratios, average_map.l3_ratios
    total = design.leg_length
    l2 = (1 - r1[:, None] - r3[None, :]) * total
    area = np.where(l2 > 0, improved_area_closed_form(l2, r3[None, :] * total), np.nan)
    fb = np.full(area.shape, np.nan)
    for i, ratio in enumerate(r1):
        rows = study[np.isclose(study["l1_ratio"], ratio)]
        fb[i] = rows["fb"].to_numpy(dtype=float) if "fb" in rows else np.nan
    maps = {
        "improved_area": area,
        "average_manipulability": average_map.improved,
        "flexibility": fb,
    }
    return recommend(
        r1,
        r3,
        maps,
        candidates=options.l1_ratios,
        evaluate=lambda a, b: ratio_metrics(design, a, b, template, options.collisions),
    )


def _decision(
    design: HexapodDesign,
    model: HexapodModel,
    template: StanceGeometry,
    rec: Recommendation,
    loads: LoadsAnalysis,
    collisions: bool,
) -> Decision:
    yours = design_metrics(design, template, collisions)
    recommended_metrics = ratio_metrics(design, rec.l1_ratio, rec.l3_ratio, template, collisions)
    try:
        recommended: HexapodDesign | None = design.with_ratios(rec.l1_ratio, rec.l3_ratio)
    except HexalegError:
        recommended = None
    payload = math.nan
    if recommended is not None:
        their_model = model.with_design(recommended)
        locked = axis_locked_flexibility(recommended, "all", their_model, collisions=collisions)
        payload = loads_at_extremes(their_model, locked).capacity.mass
    return Decision(
        your_payload=loads.capacity.mass,
        recommended_payload=payload,
        yours=yours,
        your_score=combined_score(yours, rec.maxima),
        recommended=recommended,
        recommended_metrics=recommended_metrics,
        recommended_score=combined_score(recommended_metrics, rec.maxima),
    )


def _pareto_grid(
    average_map: AverageManipulabilityMap, study: pd.DataFrame, total: float
) -> pd.DataFrame:
    """Every design of the sweep with the four metrics of the Pareto front."""
    grid = study[["l1_ratio", "l3_ratio", "l1", "l2", "l3"]].copy()
    grid["improved_area"] = improved_area_closed_form(
        grid["l2"].to_numpy(dtype=float), grid["l3"].to_numpy(dtype=float)
    )
    w_a = {
        (r1, r3): value
        for i, r1 in enumerate(average_map.l1_ratios)
        for r3, value in zip(average_map.l3_ratios, average_map.improved[i], strict=True)
    }
    grid["average_manipulability"] = [
        w_a.get((r1, r3), np.nan) for r1, r3 in zip(grid["l1_ratio"], grid["l3_ratio"], strict=True)
    ]
    grid["flexibility"] = study["fb"] if "fb" in study else np.nan
    grid["payload_capacity"] = study["payload_capacity"] if "payload_capacity" in study else np.nan
    return grid


def _candidates(grid: pd.DataFrame, l1_ratios: Sequence[float] | None) -> pd.DataFrame:
    """The designs whose coxa ratio the recommendation may take (as :func:`recommend`)."""
    if l1_ratios is not None:
        return grid[np.isclose(grid["l1_ratio"].to_numpy()[:, None], l1_ratios).any(axis=1)]
    practical = grid[grid["l1_ratio"] >= PRACTICAL_L1_RATIO - 1e-12]
    return practical if len(practical) else grid


def _without_design(data: dict[str, Any]) -> dict[str, Any]:
    """A JSON object without its ``design`` (the report states it once)."""
    return {key: value for key, value in data.items() if key != "design"}


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
