"""Mirror symmetry of a stance: which reflections map the robot onto itself.

A robot that is its own mirror image reaches, in each mirrored direction, the mirror
image of what it reaches in the other: y−, roll− and yaw− mirror y+, roll+ and yaw+
under the left-right reflection, x−, pitch− and yaw− mirror x+, pitch+ and yaw+ under
the front-back one. The flexibility searches solve one of each pair and take the other
from the mirror, re-checked like any answer.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.stance.constraints import AXES
from hexaleg.stance.geometry import StanceGeometry

MIRRORS: dict[str, tuple[ArrayF, ArrayF]] = {
    "left-right": (np.diag([1.0, -1.0, 1.0]), np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])),
    "front-back": (np.diag([-1.0, 1.0, 1.0]), np.array([-1.0, 1.0, 1.0, 1.0, -1.0, -1.0])),
}
"""Reflections of the body frame (3 × 3) and what each does to a displacement
(x, y, z, roll, pitch, yaw): the reflected pose of d is flip·d (R → M·R·M in rpy)."""
SYMMETRY_TOLERANCE = 1e-9
"""Mounts, footholds and limits must mirror to this [m or rad] for a symmetry to count."""


def mirror_flips(geometry: StanceGeometry) -> list[ArrayF]:
    """The displacement flips (:data:`MIRRORS`) of the reflections the stance is symmetric under.

    Symmetric: each stance leg's root, coxa direction and foothold reflect onto another
    stance leg's, whose leg is the mirror image of the first (a reflection negates θ1
    and a general leg's lateral offset e, so the root joint's limits and e must mirror,
    every other dimension and limit be equal), and the body (a centred box or cylinder)
    is its own mirror image.
    """
    legs = geometry.leg_parameters  # (a1, l2, l3, h, e) per leg
    lower, upper = geometry.joint_lower, geometry.joint_upper
    flips = []
    keep_handed = np.diag([1.0, -1.0, 1.0])  # the mirrored leg frame stays right-handed
    for reflection, flip in MIRRORS.values():
        roots = geometry.root_positions @ reflection
        feet = geometry.footholds @ reflection
        frames = reflection @ geometry.root_rotations @ keep_handed
        mirrored_legs = legs @ np.diag([1.0, 1.0, 1.0, 1.0, -1.0])
        mirrored_lower = np.column_stack([-upper[:, 0], lower[:, 1:]])
        mirrored_upper = np.column_stack([-lower[:, 0], upper[:, 1:]])
        matched = all(
            any(
                _close(roots[i], geometry.root_positions[j])
                and _close(feet[i], geometry.footholds[j])
                and _close(frames[i], geometry.root_rotations[j])
                and _close(mirrored_legs[i], legs[j])
                and _close(mirrored_lower[i], lower[j])
                and _close(mirrored_upper[i], upper[j])
                for j in range(len(geometry.legs))
            )
            for i in range(len(geometry.legs))
        )
        if matched:
            flips.append(flip)
    return flips


def _close(a: ArrayF, b: ArrayF) -> bool:
    return bool(np.abs(np.asarray(a) - np.asarray(b)).max() < SYMMETRY_TOLERANCE)


def search_flips(geometry: StanceGeometry, every_leg_stands: bool = True) -> list[ArrayF]:
    """The flips a search may use.

    :func:`mirror_flips`, or none where parts other than the stance legs matter
    (self-collision) and some legs swing.
    """
    return mirror_flips(geometry) if every_leg_stands else []


def mirror_sources(
    directions: Sequence[tuple[str, int]], flips: list[ArrayF]
) -> dict[int, tuple[int, ArrayF]]:
    """Which directions to take from a mirror image: index → (its source's index, flip).

    Of each pair (axis, +) and (axis, −) that a flip maps onto each other, the one listed
    first is solved and the other taken from it; every direction not named is solved.
    """
    index = {direction: i for i, direction in enumerate(directions)}
    sources: dict[int, tuple[int, ArrayF]] = {}
    for i, (axis, sign) in enumerate(directions):
        source = index.get((axis, -sign))
        reverse = reversing(AXES.index(axis), flips)
        if reverse and source is not None and source < i and source not in sources:
            sources[i] = (source, reverse[0])
    return sources


def reversing(k: int, flips: list[ArrayF]) -> list[ArrayF]:
    """The flips that map coordinate k's + direction onto its − one (and back)."""
    return [flip for flip in flips if flip[k] < 0]


def keeping(k: int, flips: list[ArrayF]) -> list[ArrayF]:
    """The symmetries (products of the flips, identity excluded) that keep coordinate k.

    They map an optimum of direction (k, ±) onto equally good ones: its mirror images.
    """
    group = {tuple(np.ones(6))}
    for flip in flips:
        group |= {tuple(np.asarray(g) * flip) for g in group}
    group.discard(tuple(np.ones(6)))
    return [np.array(g) for g in sorted(group) if g[k] > 0]
