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

from hexaleg.kinematics import inverse_kinematics
from hexaleg.stance import AXES, DIRECTIONS, StanceGeometry, direction_poses


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

    def feasible(axis: int, value: float) -> bool:  # in NumPy: IK (eq 8-9), limits, the ground
        rotation, translation = direction_poses(geometry, axis, value)
        feet = geometry.feet_in_roots(rotation, translation)
        legs = inverse_kinematics(geometry.lengths, feet, tol=0.0)
        within = legs.reachable.all() and geometry.limits.contains(legs.theta).all()
        return bool(within and geometry.lowest_body_height(rotation, translation) >= 0)

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
