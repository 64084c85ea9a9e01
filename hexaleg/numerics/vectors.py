"""Small-vector arithmetic that NumPy's general functions make slow on a handful of numbers."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF

_NEXT, _AFTER = np.array([1, 2, 0]), np.array([2, 0, 1])
"""Each component's next and after next, cyclically: (a × b)_i = a_j·b_k − a_k·b_j."""


def cross(a: npt.ArrayLike, b: npt.ArrayLike) -> ArrayF:
    """The cross product a × b over the last axis, broadcast (faster than NumPy's on small ones)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    product: ArrayF = np.take(a, _NEXT, axis=-1) * np.take(b, _AFTER, axis=-1) - np.take(
        a, _AFTER, axis=-1
    ) * np.take(b, _NEXT, axis=-1)
    return product
