"""The alternatives hexaleg is timed against: optional tools and straightforward methods.

robotics-toolbox-python and ikpy come from the ``[bench]`` extra and are skipped
(with a note in the table) where not installed; step-and-bisect is the obvious
way to find an axis-locked extreme, written here as a user would.
"""

from __future__ import annotations

import importlib
import math
import warnings

import numpy as np

from hexaleg.stance import AXES, DIRECTIONS, StanceGeometry, direction_poses, stance_margins


def optional(module: str):
    """Import an alternative if the [bench] extra is installed, else None."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return importlib.import_module(module)
    except ImportError:
        return None


def rtb_leg(lengths):
    """The paper's D-H table (Table 1) as a robotics-toolbox DHRobot."""
    rtb = optional("roboticstoolbox")
    if rtb is None:
        return None
    l1, l2, l3 = lengths
    return rtb.DHRobot(
        [rtb.RevoluteDH(a=l1, alpha=math.pi / 2), rtb.RevoluteDH(a=l2), rtb.RevoluteDH(a=l3)]
    )


def step_and_bisect_extremes(
    geometry: StanceGeometry, translation_step: float = 1e-3, angle_step: float = 1e-3
):
    """The straightforward way: step each direction until infeasible, then bisect 50 times."""

    def feasible(axis: int, value: float) -> bool:
        rotation, translation = direction_poses(geometry, axis, value)
        return bool(stance_margins(geometry, rotation, translation).min() >= 0)

    values = []
    for axis_name, sign in DIRECTIONS:
        axis = AXES.index(axis_name)
        step = translation_step if axis < 3 else angle_step
        t = 0.0
        while feasible(axis, sign * (t + step)):
            t += step
        lo, hi = t, t + step
        for _ in range(50):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if feasible(axis, sign * mid) else (lo, mid)
        values.append(sign * lo)
    return np.array(values)
