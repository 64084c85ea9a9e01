"""The recommended segment ratios: the best score on the (coxa, tibia) ratio grid, refined.

Every design of a grid of (coxa ratio, tibia ratio) at a fixed total leg length has the
four ranked metrics (:data:`~hexaleg.study.ranking.RANKED_METRICS`: improved area, w_A,
FB, payload capacity) and its score by the one ranking rule (:mod:`hexaleg.study.ranking`):
relative to the user's design, so a design's score never depends on which other designs
the grid holds. The recommendation is the best-scoring design among the candidate coxa
ratios (the paper's practical ones, ≥ 0.10, unless the user fixes the coxa), its tibia
ratio refined between grid points; the band keeps ≥ 97 % of its score.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt
import pandas as pd
from scipy import optimize

from hexaleg._typing import ArrayF
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.evaluate import Conditions, evaluate
from hexaleg.evaluation.metrics import METRICS, Metrics, MetricSpec
from hexaleg.exceptions import HexalegError
from hexaleg.gait.spec import Gait
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.study.ranking import (
    RANKED_METRICS,
    ranked_values,
    relative_values,
    score,
    scores,
)
from hexaleg.swing.manipulability import AverageManipulabilityMap
from hexaleg.swing.workspace import improved_area_closed_form

BAND = 0.97
"""Share of the best score that defines the recommended band."""

PRACTICAL_L1_RATIO = 0.10
"""Smallest coxa ratio the paper calls practical (§5.3: "between 0.1 and 0.2"); every
kinematic metric improves as the coxa shrinks, so unless the user fixes the coxa, the
recommendation is made among coxa ratios at least this large."""


@dataclass(frozen=True)
class Recommendation:
    """Recommended ratios and the evidence behind them.

    Attributes:
        l1_ratio: Recommended coxa ratio [-].
        l3_ratio: Recommended tibia ratio at that coxa ratio, refined between grid points [-].
        l3_band: The tibia ratios keeping ≥ 97 % of its score: of the grid, and the refined one [-].
        reference: The user's design's ranked metrics: what every score is relative to.
        metrics: The recommended design's ranked metrics [m², m³, -, kg].
        score: Its score [-] (the user's design: 1).
        peaks: Per coxa ratio, the tibia ratio at which each metric and the score peak.
        scores: Every grid design's metrics, each relative to the user's, and score.

    """

    l1_ratio: float
    l3_ratio: float
    l3_band: tuple[float, float]
    reference: Metrics
    metrics: Metrics
    score: float
    peaks: pd.DataFrame
    scores: pd.DataFrame

    @property
    def l2_ratio(self) -> float:
        """Femur ratio 1 − l1 − l3 [-]."""
        return 1.0 - self.l1_ratio - self.l3_ratio


@dataclass(frozen=True)
class DecisionOptions:
    """What the decision may choose from.

    Attributes:
        l1_ratios: Coxa ratios the recommendation may take; ``None``: the swept ones at
            least :data:`~.recommendation.PRACTICAL_L1_RATIO` (all of them if none is).
        collisions: The robot's own parts touching also stop the body (FB).
        gait: The gait the walking metrics walk (the design file's ``[gait]``, else the
            default gait).

    """

    l1_ratios: tuple[float, ...] | None = None
    collisions: bool = False
    gait: Gait = field(default_factory=Gait)

    @property
    def conditions(self) -> Conditions:
        """What the ranked metrics are measured under: level ground, no payload, :attr:`gait`."""
        return Conditions(gait=self.gait, collisions=self.collisions)

    def describe_candidates(self) -> str:
        """The allowed coxa ratios, in words."""
        if self.l1_ratios:
            listed = ", ".join(f"{r:.3g}" for r in self.l1_ratios)
            return f"the coxa ratios you allowed ({listed})"
        return f"the paper's practical coxa ratios (≥ {PRACTICAL_L1_RATIO:.2f})"


def your_metrics(
    design: HexapodDesign, model: HexapodModel, template: StanceGeometry, options: DecisionOptions
) -> Metrics:
    """The user's design's four ranked metrics: what every score is relative to."""
    found = evaluate(design, RANKED_METRICS, options.conditions, model=model, template=template)
    if found.error:
        raise HexalegError(f"your design cannot be ranked: {found.error}")
    return found.metrics


def ratio_metrics(
    base: HexapodDesign,
    l1_ratio: float,
    l3_ratio: float,
    model: HexapodModel,
    template: StanceGeometry,
    options: DecisionOptions,
) -> Metrics:
    """The ranked metrics of ``base`` with segments at these ratios of its leg length.

    ``model`` is ``base``'s (the design's is derived from it). A design that cannot exist
    or stand scores NaN in every metric.
    """
    try:
        design = base.with_ratios(l1_ratio, l3_ratio)
    except HexalegError:
        return _unranked()
    found = evaluate(
        design,
        RANKED_METRICS,
        options.conditions,
        model=model.with_design(design),
        template=template,
    )
    if found.error or not found.walks:  # a leg that cannot walk has no score
        return _unranked()
    return found.metrics


def _unranked() -> Metrics:
    """Every ranked metric NaN: a design without a score."""
    return _ranked(np.full(len(RANKED_METRICS), np.nan))


def _ranked(values: ArrayF) -> Metrics:
    """The ranked metrics of ``values`` (M,), in :data:`RANKED_METRICS` order."""
    return Metrics(**{spec.name: float(v) for spec, v in zip(RANKED_METRICS, values, strict=True)})


def grid_recommendation(
    design: HexapodDesign,
    model: HexapodModel,
    template: StanceGeometry,
    average_map: AverageManipulabilityMap,
    study: pd.DataFrame,
    options: DecisionOptions,
) -> Recommendation:
    """Recommend ratios from the four metrics on the (coxa, tibia) ratio grid.

    Args:
        design: The user's design (its leg length, body and posture are kept).
        model: Its Pinocchio model (the grid's designs' are derived from it).
        template: The stance geometry of its body and mounts.
        average_map: w_A on the grid (its ratios define the grid).
        study: The study on the same grid (columns ``fb``, ``walking_payload_capacity`` and
            ``walks``: a leg that cannot walk the gait unloaded has no score).
        options: The allowed coxa ratios and collision setting.

    """
    r1, r3 = average_map.l1_ratios, average_map.l3_ratios
    total = design.leg_length
    l2 = (1 - r1[:, None] - r3[None, :]) * total
    area = np.where(l2 > 0, improved_area_closed_form(l2, r3[None, :] * total), np.nan)
    fb, walking = METRICS.fb, METRICS.walking_payload_capacity
    maps = {
        METRICS.improved_area: area,
        METRICS.average_manipulability: average_map.improved,
        fb: _study_map(study, fb.name, r1, len(r3)),
        walking: _study_map(study, walking.name, r1, len(r3)),
    }
    walks = _study_map(study, "walks", r1, len(r3)) == 1  # the others have no score
    maps = {spec: np.where(walks, values, np.nan) for spec, values in maps.items()}
    return recommend(
        r1,
        r3,
        maps,
        your_metrics(design, model, template, options),
        candidates=options.l1_ratios,
        evaluate=lambda a, b: ratio_metrics(design, a, b, model, template, options),
    )


def _study_map(study: pd.DataFrame, column: str, l1_ratios: np.ndarray, width: int) -> np.ndarray:
    """A study column on the (coxa, tibia) grid: each coxa ratio's rows in tibia order."""
    values = np.full((len(l1_ratios), width), np.nan)
    if column in study:
        for i, ratio in enumerate(l1_ratios):
            values[i] = study.loc[np.isclose(study["l1_ratio"], ratio), column].to_numpy(float)
    return values


def recommend(
    l1_ratios: npt.ArrayLike,
    l3_ratios: npt.ArrayLike,
    maps: Mapping[MetricSpec, npt.ArrayLike],
    reference: Metrics,
    candidates: Sequence[float] | None = None,
    evaluate: Callable[[float, float], Metrics] | None = None,
) -> Recommendation:
    """Recommend ratios from the metric maps of shape (coxa ratios, tibia ratios).

    Args:
        l1_ratios: Coxa ratios (R1,) [-].
        l3_ratios: Tibia ratios (R3,) [-].
        maps: Each of :data:`~hexaleg.study.ranking.RANKED_METRICS` on the grid (R1, R3), by
            its declaration;
            NaN where a design cannot stand.
        reference: The user's design's metrics, which scores are relative to.
        candidates: Coxa ratios the recommendation may take; by default those
            ≥ :data:`PRACTICAL_L1_RATIO` (all of them if none is).
        evaluate: Metrics of the design (l1 ratio, l3 ratio); if given, the best tibia
            ratio is refined between its grid neighbours by a bounded scalar search.

    Raises:
        HexalegError: no allowed design of the grid has every metric.

    """
    r1 = np.asarray(l1_ratios, dtype=float)
    r3 = np.asarray(l3_ratios, dtype=float)
    values = np.stack([np.asarray(maps[spec], dtype=float) for spec in RANKED_METRICS], axis=-1)
    grid_scores = scores(values, reference)  # (R1, R3)
    allowed = np.where(candidate_mask(r1, candidates)[:, None], grid_scores, np.nan)
    if np.isnan(allowed).all():
        raise HexalegError("no design of the grid has every metric: nothing to recommend")
    i, j = (int(k) for k in np.unravel_index(int(np.nanargmax(allowed)), allowed.shape))
    best, l3_ratio = float(grid_scores[i, j]), float(r3[j])
    metrics = _ranked(values[i, j])
    if evaluate is not None:
        l3_ratio, best, metrics = _refine(r1[i], r3, j, (best, metrics), reference, evaluate)
    inside = np.append(r3[grid_scores[i] >= BAND * best], l3_ratio)  # the refined ratio is in it
    band = (float(inside.min()), float(inside.max()))
    return Recommendation(
        l1_ratio=float(r1[i]),
        l3_ratio=l3_ratio,
        l3_band=band,
        reference=reference,
        metrics=metrics,
        score=best,
        peaks=_peaks(r1, r3, values, grid_scores),
        scores=_scores(r1, r3, values, reference, grid_scores),
    )


def candidate_mask(
    l1_ratios: npt.ArrayLike, candidates: Sequence[float] | None
) -> npt.NDArray[np.bool_]:
    """Which coxa ratios the recommendation may take.

    Args:
        l1_ratios: Coxa ratios (N,) [-], e.g. of a grid or of a study's rows.
        candidates: The allowed coxa ratios; by default those ≥ :data:`PRACTICAL_L1_RATIO`.

    Returns:
        A mask (N,); all true if no ratio is allowed (the whole grid competes).

    """
    r1 = np.asarray(l1_ratios, dtype=float)
    if candidates is not None:
        mask = np.isclose(r1[:, None], np.asarray(candidates, dtype=float)[None, :]).any(axis=1)
    else:
        mask = r1 >= PRACTICAL_L1_RATIO - 1e-12
    return mask if mask.any() else np.ones_like(mask)


def _refine(
    l1_ratio: float,
    r3: ArrayF,
    j: int,
    grid_best: tuple[float, Metrics],
    reference: Metrics,
    evaluate: Callable[[float, float], Metrics],
) -> tuple[float, float, Metrics]:
    """The best-scoring tibia ratio between the grid neighbours of ``j``.

    Returns its ratio, score and metrics; the grid point's if none between scores higher.
    """
    lo, hi = r3[max(j - 1, 0)], r3[min(j + 1, len(r3) - 1)]
    seen: dict[float, Metrics] = {}

    def negative(l3_ratio: float) -> float:
        seen[l3_ratio] = evaluate(l1_ratio, l3_ratio)
        value = score(seen[l3_ratio], reference)
        return -value if np.isfinite(value) else np.inf

    with np.errstate(invalid="ignore"):  # a leg that cannot walk scores inf: Brent's steps
        result = optimize.minimize_scalar(  # then subtract it, and fall back to golden section
            negative, bounds=(lo, hi), method="bounded", options={"xatol": 1e-5}
        )
    if np.isfinite(result.fun) and -result.fun > grid_best[0]:
        metrics = _ranked(ranked_values(seen[float(result.x)]))
        return float(result.x), float(-result.fun), metrics
    return float(r3[j]), *grid_best


def _peaks(r1: ArrayF, r3: ArrayF, values: ArrayF, grid_scores: ArrayF) -> pd.DataFrame:
    """Per coxa ratio: where each metric and the score peak, and the best score."""
    rows = []
    for i, ratio in enumerate(r1):
        row: dict[str, float] = {"l1_ratio": float(ratio)}
        for k, spec in enumerate(RANKED_METRICS):
            row[f"{spec.name}_peak_l3_ratio"] = _peak(r3, values[i, :, k])
        row["score_peak_l3_ratio"] = _peak(r3, grid_scores[i])
        finite = grid_scores[i][np.isfinite(grid_scores[i])]
        row["best_score"] = float(finite.max()) if finite.size else float("nan")
        rows.append(row)
    return pd.DataFrame(rows)


def _scores(
    r1: ArrayF, r3: ArrayF, values: ArrayF, reference: Metrics, grid_scores: ArrayF
) -> pd.DataFrame:
    """Every grid design: ratios, each metric, each metric relative to yours, the score."""
    grid1, grid3 = np.meshgrid(r1, r3, indexing="ij")
    relative = relative_values(values, reference)
    return pd.DataFrame(
        {
            "l1_ratio": grid1.ravel(),
            "l3_ratio": grid3.ravel(),
            **{spec.name: values[..., k].ravel() for k, spec in enumerate(RANKED_METRICS)},
            **{
                f"{spec.name}_relative": relative[..., k].ravel()
                for k, spec in enumerate(RANKED_METRICS)
            },
            "score": grid_scores.ravel(),
        }
    )


def _peak(ratios: ArrayF, values: ArrayF) -> float:
    if np.all(np.isnan(values)):
        return float("nan")
    return float(ratios[int(np.nanargmax(values))])
