"""The tibia-ratio grid of hexaleg's design sweeps."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

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
