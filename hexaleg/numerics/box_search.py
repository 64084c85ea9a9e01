"""The least score on the unit box: DIRECT for the basin, then Nelder–Mead into its corner.

Pure numerics, independent of the robot. :func:`box_minimum` minimizes a score over
[0, 1]ⁿ, deterministically and in two stages:

- SciPy's DIRECT (Jones' dividing rectangles, locally biased) samples the box for the
  basin of the least score: a score that is piecewise smooth with cliffs (a design that
  breaks a constraint scores a penalty), whose best often lies where a ridge meets such
  a cliff, a corner a grid only approaches;
- Nelder–Mead, in rounds of shrinking initial simplices, climbs from the best point
  found (DIRECT's, or a given point if that scores less) into that corner.

The given point is a candidate too: the answer never scores more than it. The score is
called on points of the box only (clipped), and a caller that memoizes it pays each point
once.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import numpy.typing as npt
from scipy.optimize import direct, minimize

from hexaleg._typing import ArrayF

TOLERANCE = 1e-10
"""Nelder–Mead's tolerances on the unit box and on the score; DIRECT's on a side."""


def box_minimum(
    score: Callable[[ArrayF], float],
    given: npt.ArrayLike,
    *,
    global_evaluations: int,
    polish: Sequence[tuple[int, float]],
) -> ArrayF:
    """The point of the unit box [0, 1]ⁿ with the least ``score`` found.

    Args:
        score: The score of a point of the box (n,).
        given: A point (n,) that is a candidate too (e.g. the design as given).
        global_evaluations: Points DIRECT evaluates (its ``maxfun``).
        polish: Nelder–Mead's rounds from the best point so far: (most points, the legs of
            its initial simplex on the box).

    """
    start = np.clip(np.asarray(given, dtype=float), 0.0, 1.0)
    bounds = [(0.0, 1.0)] * len(start)
    found = direct(
        lambda x: score(np.clip(x, 0.0, 1.0)),
        bounds,
        maxfun=global_evaluations,
        locally_biased=True,
        vol_tol=0.0,
        len_tol=TOLERANCE,
    )
    best = min((np.clip(found.x, 0.0, 1.0), start), key=score)
    for most, size in polish:
        polished = minimize(
            lambda x: score(np.clip(x, 0.0, 1.0)),
            best,
            method="Nelder-Mead",
            bounds=bounds,
            options={
                "maxfev": most,
                "xatol": TOLERANCE,
                "fatol": TOLERANCE,
                "initial_simplex": simplex(best, size),
            },
        )
        candidate = np.clip(polished.x, 0.0, 1.0)
        if score(candidate) < score(best):
            best = candidate
    return best


def simplex(point: ArrayF, size: float) -> ArrayF:
    """A right-angled simplex of legs ``size`` at ``point``, turned inward at the box's faces."""
    steps = np.where(point + size <= 1.0, size, -size)
    corners: ArrayF = np.vstack((point, point + np.diag(steps)))
    return corners
