"""hexaleg's names for a robot file's six legs, by where each leg points around the body.

Each leg has a direction around the body: from the leg roots' centre to the point one coxa
and femur beyond its root along its coxa at q = 0, the angle α of that in the body's xy
plane (REP 103: x forward, y left). Counter-clockwise from straight ahead, three
consecutive legs are the left side — the three whose directions point farthest left
(largest Σ sin α; of equal splits, the one whose first leg points nearest straight ahead)
— named ``lf lm lr`` in that order, and the other three ``rr rm rf``: front is the leg
nearest +x on each side. Legs whose roots all lie on the body's axis (a narrow body, coxas
pointing ±y) are named by where they point, not by a root's y of 0.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from hexaleg._typing import ArrayF

__all__ = ["leg_directions", "leg_names"]

LEFT = ("lf", "lm", "lr")
"""The left side's names, counter-clockwise (front to rear)."""
RIGHT = ("rr", "rm", "rf")
"""The right side's names, counter-clockwise (rear to front)."""

TIE = 1e-9
"""Splits whose Σ sin α differ by less than this are equally far left [-]."""


def leg_directions(mounts: Sequence[ArrayF], reaches: Sequence[float]) -> ArrayF:
    """Each leg's direction α around the body (N,) [rad], in (−π, π].

    Args:
        mounts: Each leg-root frame (4, 4) in the body frame (x along the coxa at q = 0).
        reaches: How far beyond its root each leg points [m] (its coxa and femur).

    """
    roots = np.array([m[:3, 3] for m in mounts])
    centre = roots.mean(axis=0)
    ends = [m[:3, 3] - centre + reach * m[:3, 0] for m, reach in zip(mounts, reaches, strict=True)]
    return np.array([math.atan2(float(e[1]), float(e[0])) for e in ends])


def leg_names(directions: ArrayF) -> list[str]:
    """Hexaleg's name of each of six legs pointing at ``directions`` [rad] (see module)."""
    around = sorted(range(len(directions)), key=lambda i: directions[i] % (2 * math.pi))

    def farthest_left(start: int) -> tuple[float, float]:
        """How far left the three legs from ``start`` point, then how far from ahead."""
        left = [around[(start + k) % len(around)] for k in range(len(LEFT))]
        lateral = sum(math.sin(directions[i]) for i in left)
        return (-round(lateral / TIE) * TIE, abs(math.remainder(directions[left[0]], math.tau)))

    start = min(range(len(around)), key=farthest_left)
    names = [""] * len(directions)
    for k, name in enumerate((*LEFT, *RIGHT)):
        names[around[(start + k) % len(around)]] = name
    return names
