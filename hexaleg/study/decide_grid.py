"""A workshop's answer: the search's best rounded to what can be built, and measured so.

A search returns lengths to a micrometre and angles to a microradian; a workshop cuts tubes
to a millimetre and sets joints to a milliradian. :class:`Rounding` puts every free length
(a segment, a body field in metres) on a grid of :attr:`Rounding.resolution` (default 1 mm)
and every free angle (the posture, a body yaw) on a grid of :attr:`Rounding.angle_step`
(0.001 rad), each within its search bounds (a grid point past a bound moves one step
inside); a catalog's pick, a gear ratio and a battery's capacity are kept as found.

Rounding moves a design by up to half a step, which can break a requirement the search held
to its limit, and the nearest grid point need not be the best. :func:`grid_search` measures
the grid points around the search's best — the corners of the grid cell it lies in, then
moves of one or two variables by a step while they find a better point, feasibility first —
and the decision answers the best of them that meets every requirement, measured again from
its own URDF (:func:`~hexaleg.study.decide.workshop_answer`). It prints exactly what it
measured, so any command run at the printed numbers measures the same.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from typing import Any, cast

import numpy as np
import numpy.typing as npt

from hexaleg._checks import require_in_range
from hexaleg._typing import ArrayF
from hexaleg.study.search_space import FreeVariable, SearchSpace

__all__ = [
    "ANGLE_STEP",
    "DEFAULT_RESOLUTION",
    "RESOLUTION_RANGE",
    "Rounded",
    "Rounding",
    "Score",
    "grid_search",
]

DEFAULT_RESOLUTION = 1e-3
"""The grid a free length is rounded to [m]: a millimetre, what a workshop cuts to."""

RESOLUTION_RANGE = (1e-6, 0.1)
"""The resolutions accepted [m]: a micrometre to ten centimetres."""

ANGLE_STEP = 1e-3
"""The grid a free angle is rounded to [rad]: a milliradian (0.057°)."""

DIGITS = 12
"""Significant digits a grid point is written with: a multiple of the step, as a decimal."""

ROUNDS = 20
"""Most rounds of one- and two-variable moves of :func:`grid_search`."""


@dataclass(frozen=True)
class Rounding:
    """The grids an answer is rounded to.

    Attributes:
        resolution: The step of every free length [m] (a segment, a body field in m).
        angle_step: The step of every free angle [rad] (the posture, a body yaw).

    """

    resolution: float = DEFAULT_RESOLUTION
    angle_step: float = ANGLE_STEP

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "resolution", require_in_range("resolution", self.resolution,
                                                 *RESOLUTION_RANGE, "m")
        )  # fmt: skip
        object.__setattr__(
            self, "angle_step", require_in_range("angle_step", self.angle_step, 1e-6, 0.1, "rad")
        )

    def step(self, variable: FreeVariable) -> float | None:
        """The grid step of ``variable`` [m or rad]; ``None``: it is kept as found."""
        return {"m": self.resolution, "rad": self.angle_step}.get(variable.unit)

    def nearest(self, variable: FreeVariable, value: float) -> float:
        """The grid point nearest ``value`` within the variable's bounds (kept if none is)."""
        step = self.step(variable)
        if step is None:
            return float(value)
        return _within(variable, step, round(value / step))

    def rounded(self, space: SearchSpace, x: npt.ArrayLike) -> ArrayF:
        """The point ``x`` with each free length and angle on its grid."""
        return np.array(
            [self.nearest(v, value) for v, value in zip(space.variables, _floats(x), strict=True)]
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``resolution`` [m], ``angle_step`` [rad]."""
        return {"resolution": self.resolution, "angle_step": self.angle_step}


Score = tuple[float, float]
"""A grid point's score, least best: (its requirements' total scaled violation, its cost);
a point meeting every requirement has violation 0, so it beats any that does not."""


def grid_search(
    rounding: Rounding,
    space: SearchSpace,
    x: npt.ArrayLike,
    score: Callable[[list[ArrayF]], list[Score]],
    rounds: int = ROUNDS,
) -> list[tuple[Score, ArrayF]]:
    """Grid points around ``x`` scored by ``score`` (a batch at a time), best first.

    The corners of the grid cell ``x`` lies in (each rounded variable's grid point just below
    and just above it, 2^V points); then, from the best point so far, every move of one or
    two variables by one step (2V + 2V(V − 1) points), while a move finds a better point,
    for at most ``rounds`` rounds. A variable kept as found (:meth:`Rounding.step` ``None``)
    keeps its value. Feasibility first, as the search: rounding that breaks a requirement
    (a sum of lengths over the leg length, a clearance half a step short) is repaired by the
    moves before the objective is.
    """
    values = _floats(x)
    seen: dict[tuple[float, ...], Score] = {}

    def measure(points: Iterable[tuple[float, ...]]) -> None:
        fresh = list(dict.fromkeys(p for p in points if p not in seen))
        if fresh:
            seen.update(zip(fresh, score([np.array(p) for p in fresh]), strict=True))

    corners = [_cell(rounding, v, value) for v, value in zip(space.variables, values, strict=True)]
    measure(itertools.product(*corners))
    best = min(seen, key=seen.__getitem__)
    for _ in range(rounds):
        measure(_moves(rounding, space, best))
        found = min(seen, key=seen.__getitem__)
        if seen[found] >= seen[best]:
            break
        best = found
    ranked = sorted(seen.items(), key=lambda item: item[1])
    return [(points_score, np.array(point)) for point, points_score in ranked]


def _moves(
    rounding: Rounding, space: SearchSpace, point: tuple[float, ...]
) -> Iterator[tuple[float, ...]]:
    """``point`` with one or two of its rounded variables moved one step, within the bounds."""
    steps = [rounding.step(v) for v in space.variables]
    movable = [k for k, step in enumerate(steps) if step is not None]
    for count in (1, 2):
        for chosen in itertools.combinations(movable, count):
            for signs in itertools.product((-1, 1), repeat=count):
                moved = list(point)
                for k, sign in zip(chosen, signs, strict=True):
                    step, variable = cast(float, steps[k]), space.variables[k]
                    moved[k] = _within(variable, step, round(point[k] / step) + sign)
                if tuple(moved) != point:
                    yield tuple(moved)


def _cell(rounding: Rounding, variable: FreeVariable, value: float) -> list[float]:
    """The grid points of ``variable`` just below and above ``value`` (its value if kept)."""
    step = rounding.step(variable)
    if step is None:
        return [float(value)]
    below = math.floor(value / step)
    return sorted({_within(variable, step, k) for k in (below, below + 1)})


def _within(variable: FreeVariable, step: float, multiple: int) -> float:
    """``multiple``·``step`` moved inside the variable's bounds by whole steps, as a decimal.

    When no multiple of the step lies within the bounds (bounds narrower than a step), the
    bound nearest the grid point.
    """
    low, high = math.ceil(variable.lower / step - 1e-9), math.floor(variable.upper / step + 1e-9)
    if low > high:
        return min(max(multiple * step, variable.lower), variable.upper)
    return float(f"{min(max(multiple, low), high) * step:.{DIGITS}g}")


def _floats(x: npt.ArrayLike) -> list[float]:
    return [float(v) for v in np.asarray(x, dtype=float)]


@dataclass(frozen=True)
class Rounded:
    """How a decision's answer was put on the grid.

    Attributes:
        rounding: The grids.
        names: The free variables, in the order of a point's coordinates.
        searched: The search's best point, before rounding [m, rad, ...].
        answer: The grid point answered.
        measured: Grid points around the search's best measured to choose it (0: only the
            nearest, when the search met not every requirement).
        units: Each free variable's unit (``m`` and ``rad`` are rounded; empty: both).

    """

    rounding: Rounding
    names: tuple[str, ...]
    searched: tuple[float, ...]
    answer: tuple[float, ...]
    measured: int = 0
    units: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the grids, the search's unrounded best, the grid points measured."""
        return self.rounding.to_dict() | {
            "searched": dict(zip(self.names, self.searched, strict=True)),
            "grid_points_measured": self.measured,
        }

    def describe(self) -> str:
        """How the answer was rounded, in words."""
        units = set(self.units) or {"m", "rad"}
        grids = " and ".join(
            text
            for unit, text in (
                ("m", f"lengths on a {self.rounding.resolution * 1e3:g} mm grid"),
                ("rad", f"angles on {self.rounding.angle_step:g} rad"),
            )
            if unit in units
        )
        if not self.measured:
            return f"{grids}: the grid point nearest the search's best, measured again"
        return (
            f"{grids}: the best of {self.measured} grid points around the search's best, "
            "measured again"
        )
