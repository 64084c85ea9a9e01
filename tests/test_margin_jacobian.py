"""The closed-form Jacobian of the smooth margins equals central differences of the oracle's."""

from __future__ import annotations

import numpy as np
import pytest
from margin_oracle import displaced
from test_margin_kernel import VARIANTS, _geometry

from hexaleg.stance.margin_jacobian import pose_margins_and_jacobian
from hexaleg.stance.margin_kernel import column_count, kernel_geometry

STEP = 1e-6
"""Central-difference step [m or rad]: truncation ~1e-12, round-off ~1e-10."""
KINK = 1e-4
"""Forward and backward quotients this far apart: d sits on a kink (a clip, a max, |·|)."""
SCALE = np.array([0.8, 0.8, 0.5, 1.2, 1.2, 2.5])
"""Displacements up to these [m, rad]: from near nominal to far out of reach (clipped IK)."""


def _numpy_margins(geometry, displacements: np.ndarray) -> np.ndarray:
    return displaced(geometry, displacements, smooth=True)


def _differences(geometry, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Central differences (C, 6) and where they are trustworthy (no kink within the step)."""
    steps = STEP * np.eye(6)
    here = _numpy_margins(geometry, d[None])[0]
    forward = _numpy_margins(geometry, d + steps)
    backward = _numpy_margins(geometry, d - steps)
    central = ((forward - backward) / (2 * STEP)).T
    smooth = (np.abs((forward - here) - (here - backward)) / STEP < KINK).T
    return central, smooth


@pytest.mark.parametrize("reach", [0.15, 1.0], ids=["near nominal", "far out"])
@pytest.mark.parametrize("name", list(VARIANTS))
def test_the_jacobian_equals_central_differences(name, reach):
    geometry = _geometry(name)
    kernel = kernel_geometry([geometry], smooth=True)
    columns = column_count(kernel)
    rng = np.random.default_rng([list(VARIANTS).index(name), int(reach * 100)])
    checked = total = 0
    for d in rng.uniform(-reach, reach, size=(12, 6)) * SCALE:
        values, jacobian = np.empty(columns), np.empty((columns, 6))
        pose_margins_and_jacobian(kernel, 0, d, values, jacobian)
        np.testing.assert_allclose(values, _numpy_margins(geometry, d[None])[0], atol=1e-12)
        central, smooth = _differences(geometry, d)
        np.testing.assert_allclose(jacobian[smooth], central[smooth], rtol=1e-6, atol=1e-6)
        checked, total = checked + smooth.sum(), total + smooth.size
    assert checked >= 0.97 * total  # kinks are rare: the comparison covers the Jacobian
