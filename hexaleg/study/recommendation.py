"""Combine workspace, manipulability and flexibility into recommended segment ratios.

Each metric is evaluated on the same grid of (coxa ratio, tibia ratio) at a
fixed total leg length, normalized by its best value over the tibia ratios of
that coxa ratio, and averaged with equal weights. The recommended tibia ratio
maximizes that combined score; the band around it keeps ≥ 97 % of the best
score, the range within which the other design constraints can decide.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF

BAND = 0.97
"""Share of the best combined score that defines the recommended band."""

PRACTICAL_L1_RATIO = 0.10
"""Smallest coxa ratio the paper calls practical (§5.3: "between 0.1 and 0.2"); every
metric improves as the coxa shrinks, so the recommendation is made at this ratio."""


@dataclass(frozen=True)
class Recommendation:
    """Recommended ratios and the evidence behind them.

    Attributes:
        l1_ratio: Recommended coxa ratio [-].
        l3_ratio: Recommended tibia ratio at that coxa ratio [-].
        l3_band: Tibia ratios keeping ≥ 97 % of the best combined score [-].
        peaks: Per coxa ratio, the tibia ratio at which each metric and the score peak.
        scores: Normalized metrics and combined score on the whole grid.

    """

    l1_ratio: float
    l3_ratio: float
    l3_band: tuple[float, float]
    peaks: Any
    scores: Any

    @property
    def l2_ratio(self) -> float:
        """Femur ratio 1 − l1 − l3 [-]."""
        return 1.0 - self.l1_ratio - self.l3_ratio


METRICS = ("improved_area", "average_manipulability", "flexibility")


def recommend(
    l1_ratios: npt.ArrayLike,
    l3_ratios: npt.ArrayLike,
    improved_area: npt.ArrayLike,
    average_manipulability: npt.ArrayLike,
    flexibility: npt.ArrayLike,
    practical_l1_ratio: float = PRACTICAL_L1_RATIO,
) -> Recommendation:
    """Recommend ratios from three metric maps of shape (coxa ratios, tibia ratios).

    Args:
        l1_ratios: Coxa ratios (R1,) [-].
        l3_ratios: Tibia ratios (R3,) [-].
        improved_area: Improved workspace area (R1, R3) [m²].
        average_manipulability: w_A on the improved domain (R1, R3) [m³].
        flexibility: FB (R1, R3) [-]; NaN where a design could not stand.
        practical_l1_ratio: Coxa ratio at which to recommend a tibia ratio.

    """
    import pandas as pd

    r1 = np.asarray(l1_ratios, dtype=float)
    r3 = np.asarray(l3_ratios, dtype=float)
    maps = {
        "improved_area": np.asarray(improved_area, dtype=float),
        "average_manipulability": np.asarray(average_manipulability, dtype=float),
        "flexibility": np.asarray(flexibility, dtype=float),
    }
    normalized = {
        name: values / np.nanmax(values, axis=1, keepdims=True) for name, values in maps.items()
    }
    score = np.mean([normalized[name] for name in METRICS], axis=0)
    rows = []
    for i, ratio in enumerate(r1):
        row: dict[str, float] = {"l1_ratio": float(ratio)}
        for name in METRICS:
            row[f"{name}_peak_l3_ratio"] = _peak(r3, maps[name][i])
        row["combined_peak_l3_ratio"] = _peak(r3, score[i])
        row["combined_best_score"] = float(np.nanmax(score[i]))
        rows.append(row)
    peaks = pd.DataFrame(rows)
    grid1, grid3 = np.meshgrid(r1, r3, indexing="ij")
    scores = pd.DataFrame(
        {
            "l1_ratio": grid1.ravel(),
            "l3_ratio": grid3.ravel(),
            **{f"{name}_normalized": normalized[name].ravel() for name in METRICS},
            "combined_score": score.ravel(),
        }
    )
    chosen = int(np.argmin(np.abs(r1 - practical_l1_ratio)))
    best = float(np.nanmax(score[chosen]))
    inside = r3[score[chosen] >= BAND * best]
    return Recommendation(
        l1_ratio=float(r1[chosen]),
        l3_ratio=_peak(r3, score[chosen]),
        l3_band=(float(inside.min()), float(inside.max())),
        peaks=peaks,
        scores=scores,
    )


def _peak(ratios: ArrayF, values: ArrayF) -> float:
    if np.all(np.isnan(values)):
        return float("nan")
    return float(ratios[int(np.nanargmax(values))])
