"""Basins: climbs of the free-coupled search (:mod:`.free_coupled`) that ended at one value.

Climbs from many starts end at a few local optima; those ending within
:data:`BASIN_TOLERANCE` of each other form a :class:`Basin`, whose members the polish
tries in turn.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from hexaleg._typing import ArrayF

BASIN_TOLERANCE = 1e-4
"""Climbs ending within this (relative, at least 1 unit) of each other share a basin:
a climb stops some 1e-5 short of an optimum where it has to creep along the boundary."""
POLISH_TRIES = 3
"""Members of a basin polished (:meth:`Basin.tries`) until one gives an answer."""


@dataclass(frozen=True)
class Basin:
    """Climbs that ended at one value.

    Attributes:
        value: The best value among them [m or rad].
        points: Where they ended, the deepest inside the constraints first.
        margins: The smallest exact margin at each point.
        values: The value each reached [m or rad].

    """

    value: float
    points: tuple[ArrayF, ...]
    margins: tuple[float, ...]
    values: tuple[float, ...]

    @property
    def climbs(self) -> int:
        """How many climbs ended here."""
        return len(self.points)

    def tries(self) -> tuple[ArrayF, ...]:
        """The members to polish, in turn: the deepest, then the best-valued.

        Climbs that end on a plane of symmetry (the deepest, often) can stop at a
        saddle a hair below the optimum just off the plane, which others reach.
        """
        rest = sorted(range(1, self.climbs), key=lambda i: -self.values[i])
        return tuple(self.points[i] for i in [0, *rest][:POLISH_TRIES])


def grouped(members: Sequence[tuple[float, ArrayF, float]]) -> list[Basin]:
    """Climb ends (value, point, smallest exact margin) grouped into basins, best first."""
    groups: list[list[tuple[float, ArrayF, float]]] = []
    for member in sorted(members, key=lambda member: -member[0]):
        if groups and groups[-1][0][0] - member[0] <= BASIN_TOLERANCE * max(1.0, abs(member[0])):
            groups[-1].append(member)
        else:
            groups.append([member])
    basins = []
    for group in groups:  # the deepest first
        values, points, margins = zip(*sorted(group, key=lambda m: -m[2]), strict=True)
        basins.append(Basin(max(values), points, margins, values))
    return basins
