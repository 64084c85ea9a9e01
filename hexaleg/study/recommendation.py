"""Combine workspace, manipulability and flexibility into recommended segment ratios.

Each metric is evaluated on the same grid of (coxa ratio, tibia ratio) at a fixed
total leg length and divided by its best value over the **whole** grid, so scores
compare across coxa ratios; the combined score is their equal-weight mean. The
recommendation is the best-scoring design among the candidate coxa ratios (the
paper's practical ones, ≥ 0.10, unless the user fixes the coxa), its tibia ratio
refined between grid points; the band keeps ≥ 97 % of its score.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import pandas as pd
from scipy import optimize

from hexaleg._typing import ArrayF

BAND = 0.97
"""Share of the best combined score that defines the recommended band."""

PRACTICAL_L1_RATIO = 0.10
"""Smallest coxa ratio the paper calls practical (§5.3: "between 0.1 and 0.2"); every
metric improves as the coxa shrinks, so unless the user fixes the coxa, the
recommendation is made among coxa ratios at least this large."""

METRICS = ("improved_area", "average_manipulability", "flexibility")
"""The combined metrics: improved area [m²] (eq 16), w_A [m³] (eq 27), FB [-] (eq 29)."""

Metrics = Mapping[str, float]
"""One design's value of each of :data:`METRICS`."""


@dataclass(frozen=True)
class Recommendation:
    """Recommended ratios and the evidence behind them.

    Attributes:
        l1_ratio: Recommended coxa ratio [-].
        l3_ratio: Recommended tibia ratio at that coxa ratio, refined between grid points [-].
        l3_band: Tibia ratios keeping ≥ 97 % of the best combined score [-].
        maxima: Best value of each metric over the grid: the normalization.
        score: Combined score of the recommended design [-] (1 would be best in every metric).
        peaks: Per coxa ratio, the tibia ratio at which each metric and the score peak.
        scores: Normalized metrics and combined score on the whole grid.

    """

    l1_ratio: float
    l3_ratio: float
    l3_band: tuple[float, float]
    maxima: dict[str, float]
    score: float
    peaks: pd.DataFrame
    scores: pd.DataFrame

    @property
    def l2_ratio(self) -> float:
        """Femur ratio 1 − l1 − l3 [-]."""
        return 1.0 - self.l1_ratio - self.l3_ratio


def combined_score(metrics: Metrics, maxima: Metrics) -> float:
    """Equal-weight mean of each metric over its grid maximum [-]."""
    return float(np.mean([metrics[name] / maxima[name] for name in METRICS]))


def recommend(
    l1_ratios: npt.ArrayLike,
    l3_ratios: npt.ArrayLike,
    maps: Mapping[str, npt.ArrayLike],
    candidates: Sequence[float] | None = None,
    evaluate: Callable[[float, float], Metrics] | None = None,
) -> Recommendation:
    """Recommend ratios from the metric maps of shape (coxa ratios, tibia ratios).

    Args:
        l1_ratios: Coxa ratios (R1,) [-].
        l3_ratios: Tibia ratios (R3,) [-].
        maps: Each of :data:`METRICS` on the grid (R1, R3); NaN where a design cannot stand.
        candidates: Coxa ratios the recommendation may take; by default those
            ≥ :data:`PRACTICAL_L1_RATIO` (all of them if none is).
        evaluate: Metrics of the design (l1 ratio, l3 ratio); if given, the best tibia
            ratio is refined between its grid neighbours by a bounded scalar search.

    """
    r1 = np.asarray(l1_ratios, dtype=float)
    r3 = np.asarray(l3_ratios, dtype=float)
    values = {name: np.asarray(maps[name], dtype=float) for name in METRICS}
    maxima = {name: float(np.nanmax(values[name])) for name in METRICS}
    normalized = {name: values[name] / maxima[name] for name in METRICS}
    score = np.mean([normalized[name] for name in METRICS], axis=0)
    chosen = candidate_mask(r1, candidates)
    row_best = np.array([np.nanmax(score[i]) if chosen[i] else -np.inf for i in range(len(r1))])
    i = int(np.argmax(row_best))
    j = int(np.nanargmax(score[i]))
    best = float(score[i, j])
    l3_ratio = float(r3[j])
    if evaluate is not None:
        l3_ratio, best = _refine(r1[i], r3, j, best, maxima, evaluate)
    inside = r3[score[i] >= BAND * best]
    band = (float(inside.min()), float(inside.max())) if inside.size else (l3_ratio, l3_ratio)
    return Recommendation(
        l1_ratio=float(r1[i]),
        l3_ratio=l3_ratio,
        l3_band=band,
        maxima=maxima,
        score=best,
        peaks=_peaks(r1, r3, values, score),
        scores=_scores(r1, r3, normalized, score),
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
    grid_best: float,
    maxima: Metrics,
    evaluate: Callable[[float, float], Metrics],
) -> tuple[float, float]:
    """The tibia ratio of the best combined score between the grid neighbours of ``j``."""
    lo, hi = r3[max(j - 1, 0)], r3[min(j + 1, len(r3) - 1)]

    def negative(l3_ratio: float) -> float:
        value = combined_score(evaluate(l1_ratio, l3_ratio), maxima)
        return -value if np.isfinite(value) else np.inf

    result = optimize.minimize_scalar(
        negative, bounds=(lo, hi), method="bounded", options={"xatol": 1e-5}
    )
    if np.isfinite(result.fun) and -result.fun > grid_best:
        return float(result.x), float(-result.fun)
    return float(r3[j]), grid_best


def _peaks(r1: ArrayF, r3: ArrayF, values: Mapping[str, ArrayF], score: ArrayF) -> pd.DataFrame:
    rows = []
    for i, ratio in enumerate(r1):
        row: dict[str, float] = {"l1_ratio": float(ratio)}
        for name in METRICS:
            row[f"{name}_peak_l3_ratio"] = _peak(r3, values[name][i])
        row["combined_peak_l3_ratio"] = _peak(r3, score[i])
        row["combined_best_score"] = float(np.nanmax(score[i]))
        rows.append(row)
    return pd.DataFrame(rows)


def _scores(
    r1: ArrayF, r3: ArrayF, normalized: Mapping[str, ArrayF], score: ArrayF
) -> pd.DataFrame:
    grid1, grid3 = np.meshgrid(r1, r3, indexing="ij")
    return pd.DataFrame(
        {
            "l1_ratio": grid1.ravel(),
            "l3_ratio": grid3.ravel(),
            **{f"{name}_normalized": normalized[name].ravel() for name in METRICS},
            "combined_score": score.ravel(),
        }
    )


def _peak(ratios: ArrayF, values: ArrayF) -> float:
    if np.all(np.isnan(values)):
        return float("nan")
    return float(ratios[int(np.nanargmax(values))])
