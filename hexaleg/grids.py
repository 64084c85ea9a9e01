"""The tibia-ratio grid of hexaleg's design sweeps, and the segments of a ratio pair."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from hexaleg._checks import require_ratio
from hexaleg.exceptions import ParameterError

L3_RATIO_RANGE: tuple[float, float] = (0.10, 0.75)
"""Tibia-ratio range of hexaleg's design sweeps [-]. The paper gives only the count
(:data:`L3_RATIO_POINTS`); this range leaves a femur of at least 5 % of the leg for every
coxa ratio up to 0.20."""

L3_RATIO_POINTS = 80
"""Tibia ratios per coxa ratio in the paper's design study (§6.2): the sweeps' default."""

MAX_L3_POINTS = 1000
"""Most tibia ratios per coxa ratio in a sweep."""


def l3_ratio_grid(points: int = L3_RATIO_POINTS) -> npt.NDArray[np.float64]:
    """Evenly spaced tibia ratios over :data:`L3_RATIO_RANGE` [-]."""
    if not 2 <= points <= MAX_L3_POINTS:
        raise ParameterError("l3_points", points, f"from 2 to {MAX_L3_POINTS} tibia ratios")
    return np.linspace(*L3_RATIO_RANGE, points)


def ratio_lengths(l1_ratio: float, l3_ratio: float, total: float) -> tuple[float, float, float]:
    """(l1, l2, l3) [m] of coxa and tibia ratios [-] of a total leg length ``total`` [m].

    Raises:
        ParameterError: A ratio outside (0, 1), or their sum not below 1 (no femur).

    """
    l1_ratio = require_ratio("l1_ratio", l1_ratio)
    l3_ratio = require_ratio("l3_ratio", l3_ratio)
    if not l1_ratio + l3_ratio < 1.0:
        raise ParameterError(
            "l1_ratio + l3_ratio",
            l1_ratio + l3_ratio,
            "must be < 1 so that the femur ratio 1 - l1_ratio - l3_ratio is positive",
        )
    l1, l3 = l1_ratio * total, l3_ratio * total
    return (l1, total - l1 - l3, l3)
