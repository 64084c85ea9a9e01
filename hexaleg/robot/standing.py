"""The posture a robot file stands in: the design's nominal angles, or the nearest that stands.

A posture stands when, the body level, every leg joint lies within the file's limits, the
feet are level (within :data:`LEVEL_FEET`) and the body's box is above the ground: the
feet's mean depth below the roots' plane (the standing height H) exceeds the box's depth
below it.

The design's nominal angles θ (the paper's (0, 0, −π/2) unless given) are tried first on
every leg, a joint outside a leg's limits moved :data:`ROUND_OFF_ROOM` inside them (so that
no round-off puts it beyond). If they do not stand, a feasibility search takes the posture
nearest the design's (hip and knee angles the same on every leg, θ1 the design's) among
those on a grid over the legs' common limits that stand with room to move: every joint at
least :data:`JOINT_ROOM` inside its limits, the body at least :data:`CLEARANCE_SHARE` of
H above the ground. One warning says what the design's posture breaks and which was chosen;
when none stands, the robot is refused, naming what the design's posture breaks (the leg
and joint and the angle against its limits, the feet's heights, or the body's depth).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.exceptions import RobotImportError, RobotImportWarning
from hexaleg.kinematics import foot_position
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.imported import ImportedLeg, ImportedRobot

__all__ = ["LEVEL_FEET", "Standing", "foot_heights", "standing_posture"]

LEVEL_FEET = 1e-3
"""Largest spread of the feet's heights at the nominal posture, body level [m]."""

ROUND_OFF_ROOM = 1e-6
"""How far inside its limits a nominal angle that lies outside them is moved [rad]."""

JOINT_ROOM = 0.05
"""Room the searched posture leaves every joint inside its limits [rad] (about 3°)."""

CLEARANCE_SHARE = 0.1
"""Ground clearance the searched posture leaves, over the standing height [-]."""

GRID = 121
"""Hip and knee angles tried by the search, each, over the legs' common limits [-]."""

OPEN = math.pi
"""A continuous joint's range in the search: ±π about its zero [rad]."""


@dataclass(frozen=True, eq=False)
class Standing:
    """The posture a robot stands in.

    Attributes:
        angles: Each leg's θ (6, 3) [rad], in the robot's leg order.
        moved: Each leg's joints whose design angle lay outside the leg's limits.
        chosen: Why the design's posture was left for this one (``None``: it stands).

    """

    angles: ArrayF
    moved: tuple[tuple[str, ...], ...]
    chosen: str | None = None


def standing_posture(robot: ImportedRobot, nominal: Sequence[float], body_depth: float) -> Standing:
    """The posture ``robot`` stands in (see the module docstring).

    Args:
        robot: The robot.
        nominal: The design's nominal angles θ (3,) [rad].
        body_depth: How far the body's box reaches below the roots' plane [m].

    Raises:
        RobotImportError: No posture stands; the message names what the design's breaks.

    """
    return _standing(robot, tuple(float(t) for t in nominal), float(body_depth))


@lru_cache(maxsize=16)
def _standing(robot: ImportedRobot, nominal: tuple[float, float, float], depth: float) -> Standing:
    """:func:`standing_posture`, once per robot and posture (its warning said once)."""
    lower, upper = _limits(robot.legs)
    wanted = np.tile(nominal, (len(robot.legs), 1))
    inside = np.clip(wanted, lower + ROUND_OFF_ROOM, upper - ROUND_OFF_ROOM)
    inside = np.where((wanted >= lower) & (wanted <= upper), wanted, inside)
    moved = tuple(
        tuple(LEG_JOINTS[j] for j in range(3) if inside[i, j] != wanted[i, j])
        for i in range(len(robot.legs))
    )
    broken = _broken(robot, inside, depth)
    if broken is None:
        return Standing(inside, moved)
    found = _search(robot, np.asarray(nominal), lower, upper, depth, inside[:, 0])
    said = f"the nominal posture θ = ({_angles(nominal)}) rad"
    if any(moved):
        said += (
            f" (moved inside the file's limits: ({_angles(inside[0])}) on leg {robot.legs[0].name})"
        )
    said += f" does not stand: {broken}"
    if found is None:
        raise RobotImportError(
            f"{said}; no posture with the same hip and knee angles on every leg stands within "
            f"the file's limits (give --nominal-angles, or check the file's limits and feet)"
        )
    chosen = f"{said}; it stands at θ2, θ3 = {_angles(found[0, 1:])} rad instead, the nearest "
    chosen += "that stands with room to move (found by a search within the file's limits)"
    warnings.warn(chosen, RobotImportWarning, stacklevel=4)
    return Standing(found, moved, chosen)


def _limits(legs: Sequence[ImportedLeg]) -> tuple[ArrayF, ArrayF]:
    """Each leg's limits on θ (6, 3) [rad], a continuous joint's ±:data:`OPEN`."""
    lower = np.array([leg.theta_limits[0] for leg in legs], dtype=float)
    upper = np.array([leg.theta_limits[1] for leg in legs], dtype=float)
    return np.maximum(lower, -OPEN), np.minimum(upper, OPEN)


def foot_heights(robot: ImportedRobot, angles: ArrayF) -> ArrayF:
    """Each foot's height over the roots' mean plane (..., 6) [m] (negative: below), level.

    ``angles``: each leg's θ (..., 6, 3) [rad].
    """
    plane = np.mean([leg.reading.mount[2, 3] for leg in robot.legs])
    heights = []
    for i, leg in enumerate(robot.legs):
        foot = foot_position(leg.reading.geometry, angles[..., i, :])[..., 2]
        heights.append(leg.reading.mount[2, 3] - plane + foot)
    return np.stack(heights, axis=-1)


def _broken(robot: ImportedRobot, angles: ArrayF, depth: float) -> str | None:
    """What posture ``angles`` (6, 3) breaks, in words; ``None`` if it stands."""
    lower, upper = _limits(robot.legs)
    outside = (angles < lower) | (angles > upper)
    if outside.any():
        i, j = (int(k) for k in np.argwhere(outside)[0])
        return (
            f"leg {robot.legs[i].name}'s {LEG_JOINTS[j]} at {angles[i, j]:.4g} rad, outside its "
            f"limits [{lower[i, j]:.4g}, {upper[i, j]:.4g}] rad"
        )
    feet = foot_heights(robot, angles)
    names = [leg.name for leg in robot.legs]
    if feet.max() - feet.min() > LEVEL_FEET:
        high, low = int(np.argmax(feet)), int(np.argmin(feet))
        return (
            f"the feet are {1000 * (feet.max() - feet.min()):.3g} mm apart in height (leg "
            f"{names[high]}'s {1000 * feet[high]:.4g} mm, leg {names[low]}'s "
            f"{1000 * feet[low]:.4g} mm from the roots' plane; level is within "
            f"{1000 * LEVEL_FEET:g} mm)"
        )
    height = -float(feet.mean())
    if height - depth <= 0:
        return (
            f"the body's lowest point is {1000 * (depth - height):.3g} mm below the ground (its "
            f"box reaches {1000 * depth:.3g} mm below the roots, the feet {1000 * height:.3g} mm)"
        )
    return None


def _search(
    robot: ImportedRobot,
    nominal: ArrayF,
    lower: ArrayF,
    upper: ArrayF,
    depth: float,
    roots: ArrayF,
) -> ArrayF | None:
    """The standing posture (6, 3) nearest ``nominal`` with room, on the grid; ``None``: none."""
    low = lower[:, 1:].max(axis=0) + JOINT_ROOM
    high = upper[:, 1:].min(axis=0) - JOINT_ROOM
    if np.any(low > high):
        return None
    hips, knees = (np.linspace(a, b, GRID) for a, b in zip(low, high, strict=True))
    t2, t3 = (g.ravel() for g in np.meshgrid(hips, knees, indexing="ij"))
    angles = np.empty((t2.size, len(robot.legs), 3))
    angles[..., 0], angles[..., 1], angles[..., 2] = roots, t2[:, None], t3[:, None]
    feet = foot_heights(robot, angles)
    height = -feet.mean(axis=1)
    stands = (np.ptp(feet, axis=1) <= LEVEL_FEET) & (height - depth >= CLEARANCE_SHARE * height)
    stands &= height > 0
    if not stands.any():
        return None
    distance = np.hypot(t2 - nominal[1], t3 - nominal[2])
    best = int(np.argmin(np.where(stands, distance, np.inf)))
    return np.asarray(angles[best])


def _angles(values: Sequence[float] | ArrayF) -> str:
    return ", ".join(f"{float(v):.4g}" for v in values)
