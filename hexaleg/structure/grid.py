"""The tubes sizing chooses from: round tubes on a grid of diameters and walls.

Outer diameters D on a 1 mm grid from 4 mm to 120 mm; walls t in 0.5 mm steps from
0.5 mm up to D/2 (a solid rod), with D/t ≤ 50 against local buckling of a thin wall
(:class:`TubeGrid`, each number a field). Of those, sizing needs only the tubes no other
is as light, as strong and as stiff as (:attr:`TubeGrid.useful`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from functools import cached_property
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.exceptions import ParameterError
from hexaleg.leg_structure import Tube


@dataclass(frozen=True)
class TubeGrid:
    """The tubes sizing chooses from.

    Attributes:
        smallest_diameter: The smallest outer diameter D [m].
        largest_diameter: The largest outer diameter D [m].
        diameter_step: D's step [m].
        wall_step: The wall's step, and its thinnest [m].
        max_slenderness: The largest D/t [-] (against local buckling of the wall).

    """

    smallest_diameter: float = 0.004
    largest_diameter: float = 0.120
    diameter_step: float = 0.001
    wall_step: float = 0.0005
    max_slenderness: float = 50.0

    def __post_init__(self) -> None:
        if not 0 < self.smallest_diameter <= self.largest_diameter:
            raise ParameterError(
                "largest_diameter", self.largest_diameter, "at least smallest_diameter > 0 [m]"
            )
        if not (self.diameter_step > 0 and self.wall_step > 0 and self.max_slenderness >= 2):
            raise ParameterError("grid", self, "positive steps [m] and max_slenderness ≥ 2 [-]")

    @cached_property
    def tubes(self) -> tuple[ArrayF, ArrayF]:
        """Every tube of the grid: outer diameters and walls (n,) each [m]."""
        count = round((self.largest_diameter - self.smallest_diameter) / self.diameter_step)
        diameters, walls = [], []
        for d in self.smallest_diameter + self.diameter_step * np.arange(count + 1):
            steps = np.arange(1, math.floor(d / 2 / self.wall_step + 1e-9) + 1) * self.wall_step
            kept = steps[d / steps <= self.max_slenderness + 1e-9]
            diameters += [d] * len(kept)
            walls += list(kept)
        return np.round(diameters, 9), np.round(walls, 9)  # to the nanometre: 0.039, not …01

    @cached_property
    def useful(self) -> npt.NDArray[np.intp]:
        """The grid tubes no other is as light, as strong and as stiff as (indices).

        Tube a beats tube b when its area is no larger and its section modulus 2I/D and
        second moment I no smaller (one of them strictly): a's stresses (N/A, M/(2I/D),
        T/(4I/D)) and deflection are then no larger, for no more mass, so sizing never
        needs b.
        """
        outer, wall = self.tubes
        area, moment = _area(outer, wall), _moment(outer, wall)
        modulus = 2 * moment / outer
        beaten = np.zeros(len(outer), dtype=bool)
        for start in range(0, len(outer), 512):  # by blocks: n² booleans at once are many
            rows = slice(start, start + 512)
            no_worse = (
                (area[None, :] <= area[rows, None])
                & (modulus[None, :] >= modulus[rows, None])
                & (moment[None, :] >= moment[rows, None])
            )
            better = (
                (area[None, :] < area[rows, None])
                | (modulus[None, :] > modulus[rows, None])
                | (moment[None, :] > moment[rows, None])
            )
            beaten[rows] = (no_worse & better).any(axis=1)
        return np.flatnonzero(~beaten)

    @cached_property
    def sections(self) -> tuple[ArrayF, ArrayF, ArrayF]:
        """The useful tubes' outer diameters [m], areas [m²], second moments [m⁴]."""
        outer, wall = (values[self.useful] for values in self.tubes)
        return outer, _area(outer, wall), _moment(outer, wall)

    @cached_property
    def by_area(self) -> npt.NDArray[np.int64]:
        """The useful tubes (indices into :attr:`sections`) by area, the stiffer first."""
        _, area, moment = self.sections
        return np.lexsort((-moment, area)).astype(np.int64)

    def tube(self, index: int) -> Tube:
        """The useful tube ``index`` (into :attr:`sections`)."""
        outer, wall = (values[self.useful] for values in self.tubes)
        return Tube(float(outer[index]), float(wall[index]))

    def to_dict(self) -> dict[str, float]:
        """JSON-ready (m, -)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def __reduce__(self) -> tuple[Any, tuple[float, ...]]:
        """Pickled by its fields alone, not its 7 000 tubes (120 kB a sized design).

        A sized design comes back from a worker with its grid; the default grid unpickles
        as this process's own, its tubes found once.
        """
        return _grid, tuple(getattr(self, f.name) for f in fields(self))


DEFAULT_GRID = TubeGrid()
"""The grid sizing chooses from unless told (its useful tubes found once per process)."""


def _grid(*values: float) -> TubeGrid:
    """The grid of these fields: :data:`DEFAULT_GRID` itself when they are its."""
    grid = TubeGrid(*values)
    return DEFAULT_GRID if grid == DEFAULT_GRID else grid


def _area(outer: ArrayF, wall: ArrayF) -> ArrayF:
    inner = np.maximum(outer - 2 * wall, 0.0)
    return np.pi / 4 * (outer**2 - inner**2)


def _moment(outer: ArrayF, wall: ArrayF) -> ArrayF:
    inner = np.maximum(outer - 2 * wall, 0.0)
    return np.pi / 64 * (outer**4 - inner**4)
