"""What a decision may change: the free variables, their bounds, and the design at a point.

By default the three segment lengths l1, l2, l3 are free, each from
:data:`SEGMENT_FLOOR` of the leg length up to the leg length (l1 from ``min_coxa`` if
required); the leg-length requirement bounds their sum. ``--free-posture`` also frees
the nominal hip and knee angles (``theta2``, ``theta3``) within the stance limits, and
``--free FIELD=LOWER:UPPER`` any body field of :data:`~hexaleg.field_sweep.SWEEPABLE`
(or narrows a segment's or an angle's bounds). ``--choose-actuators`` adds one
categorical variable per joint type (``actuator_root``, ``actuator_hip``,
``actuator_knee``): a point's coordinate in [0, K) picks the catalog's ⌊x⌋-th of its K
actuators, and ``--free-gear-ratio`` its gear ratio
(:mod:`hexaleg.study.actuator_variables`). A ``range_km`` requirement frees the battery's
capacity (``battery_capacity`` [Wh], from :data:`CAPACITY_BOUNDS`) of a design that has
a ``[battery]``.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.actuators import Actuator, Actuators
from hexaleg.battery import Battery
from hexaleg.design import FIELD_RANGES, SEGMENT_RANGE, SEGMENTS, HexapodDesign
from hexaleg.exceptions import ParameterError
from hexaleg.field_sweep import SWEEPABLE
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.robot import Robot, template_robot
from hexaleg.study.actuator_variables import (
    CHOICES,
    GEARS,
    actuator_bounds,
    choice_coordinate,
    gear_coordinate,
    geared_entry,
)

SEGMENT_FLOOR = 0.02
"""Smallest segment searched, as a share of the leg length [-] (2 cm on a 1 m leg)."""

POSTURE = ("theta2", "theta3")
"""The nominal hip and knee angles [rad] that ``--free-posture`` frees (θ1 stays)."""

BATTERY = "battery_capacity"
"""The battery's capacity [Wh], free when a range is required."""
CAPACITY_BOUNDS = (1.0, 5e4)
"""The capacities a required range searches [Wh]: a watt-hour to 50 kWh."""

FREEABLE = (*SEGMENTS, *POSTURE, *SWEEPABLE, *CHOICES, *GEARS, BATTERY)
"""Every variable a search can free."""

LEG_CAP = "l1 + l2 + l3 at most the leg length"
STANCE_CAP = "the design's stance limits"
"""Why a segment's and a nominal angle's bounds are what they are, in words."""

AT_BOUND_SHARE = 1e-3
"""A free variable within this share of its range from a bound is at that bound [-]."""


@dataclass(frozen=True)
class FreeVariable:
    """One free variable and its bounds.

    Attributes:
        name: A segment (``l1``), a nominal angle (``theta2``) or a body field.
        lower: Its smallest value [m or rad].
        upper: Its largest value [m or rad].

    """

    name: str
    lower: float
    upper: float

    def __post_init__(self) -> None:
        if self.name not in FREEABLE:
            raise ParameterError("--free", self.name, "a field among " + ", ".join(FREEABLE))
        if not (math.isfinite(self.lower) and math.isfinite(self.upper)):
            raise ParameterError(f"--free {self.name}", self.typed, "finite bounds")
        if not self.lower < self.upper:
            raise ParameterError(f"--free {self.name}", self.typed, "LOWER must be below UPPER")
        if self.name in FIELD_RANGES:
            low, high, unit = FIELD_RANGES[self.name]
            if self.lower < low or self.upper > high:
                raise ParameterError(
                    f"--free {self.name}",
                    self.typed,
                    f"bounds within [{low:g}, {high:g}] [{unit}]",
                )

    @property
    def typed(self) -> str:
        """Its bounds as ``--free`` takes them: ``0.1:0.5``."""
        return f"{self.lower:g}:{self.upper:g}"

    @property
    def unit(self) -> str:
        """Its unit: ``"m"``, ``"rad"`` (or a body field's own; ``"-"`` for a choice)."""
        if self.name in (*CHOICES, *GEARS):
            return "-"
        if self.name == BATTERY:
            return "Wh"
        return FIELD_RANGES[self.name][2] if self.name in FIELD_RANGES else "rad"

    @classmethod
    def parse(cls, text: str) -> FreeVariable:
        """``FIELD=LOWER:UPPER``, e.g. ``body_width=0.4:0.8``."""
        match = re.fullmatch(r"\s*([a-z_0-9]+)\s*=\s*([^:]+):([^:]+)\s*", text)
        if match is None:
            raise ParameterError("--free", text, "FIELD=LOWER:UPPER, e.g. body_width=0.4:0.8")
        if match[1] in CHOICES:
            raise ParameterError("--free", text, "--choose-actuators frees the actuators")
        if match[1] in GEARS:
            raise ParameterError("--free", text, "--free-gear-ratio frees the gear ratios")
        try:
            lower, upper = float(match[2]), float(match[3])
        except ValueError:
            raise ParameterError("--free", text, "LOWER and UPPER numbers") from None
        return cls(match[1], lower, upper)


@dataclass(frozen=True)
class SearchSpace:
    """The designs a search may visit: a base design with some fields free.

    Attributes:
        base: Every field that is not free.
        variables: The free variables, in the order of a point's coordinates.
        entries: The actuators a choice variable picks from, in the catalog's order.
        ratio_ranges: Each entry's lowest and highest gear ratio [-] (None: its ratio
            only), what a gear ratio variable spans; empty without such variables.
        robot: The robot each point is, at the point's fields
            (:meth:`~hexaleg.robot.robot.Robot.at`); hexaleg's template over ``base`` if not
            given. It reaches workers as its recipe.

    """

    base: HexapodDesign
    variables: tuple[FreeVariable, ...]
    entries: tuple[Actuator, ...] = ()
    ratio_ranges: tuple[tuple[float, float] | None, ...] = ()
    robot: Robot = None  # type: ignore[assignment]  # hexaleg's template over base

    def __post_init__(self) -> None:
        if self.robot is None:
            object.__setattr__(self, "robot", template_robot(self.base))

    @property
    def names(self) -> tuple[str, ...]:
        """The free variables' names."""
        return tuple(v.name for v in self.variables)

    @property
    def lower(self) -> ArrayF:
        """Lower bounds (V,) [m or rad]."""
        return np.array([v.lower for v in self.variables])

    @property
    def upper(self) -> ArrayF:
        """Upper bounds (V,) [m or rad]."""
        return np.array([v.upper for v in self.variables])

    @property
    def same_body(self) -> bool:
        """Whether every design keeps the base's body and mounts (models derive in closed form)."""
        return all(name in (*SEGMENTS, *POSTURE, *CHOICES, *GEARS, BATTERY) for name in self.names)

    def design(self, x: npt.ArrayLike) -> HexapodDesign:
        """The design at point ``x`` (validated: raises if it cannot exist)."""
        return self.base.replace(**self.changes(x))

    def robot_at(self, x: npt.ArrayLike) -> Robot:
        """The robot at point ``x``: :attr:`robot` with the point's fields changed.

        Raises:
            HexalegError: A design that cannot exist, or a robot that cannot be built so.

        """
        return self.robot.at(**self.changes(x))

    def changes(self, x: npt.ArrayLike) -> dict[str, Any]:
        """The design fields point ``x`` sets over :attr:`base`'s."""
        changes: dict[str, Any] = {}
        angles = list(self.base.nominal_angles)
        picks: dict[str, int] = {}
        geared: dict[str, float] = {}
        for name, value in zip(self.names, np.asarray(x, dtype=float), strict=True):
            if name in CHOICES:
                pick = int(np.clip(np.floor(value), 0, len(self.entries) - 1))
                picks[name.removeprefix("actuator_")] = pick
            elif name in GEARS:
                geared[name.removeprefix("gear_ratio_")] = float(value)
            elif name == BATTERY:
                changes["battery"] = dataclasses.replace(self._battery, capacity=float(value))
            elif name in POSTURE:
                angles[1 + POSTURE.index(name)] = float(value)
            else:
                changes[name] = float(value)
        if tuple(angles) != self.base.nominal_angles:
            changes["nominal_angles"] = tuple(angles)
        chosen = {j: geared_entry(self.entries, self.ratio_ranges, pick, geared.get(j))
                  for j, pick in picks.items()}  # fmt: skip
        if chosen:
            given = self.base.actuators
            kept = {j: getattr(given, j) for j in LEG_JOINTS} if given is not None else {}
            changes["actuators"] = Actuators(**(kept | chosen))
        return changes

    def point(self, design: HexapodDesign) -> ArrayF:
        """``design``'s point, clipped into the bounds (V,)."""
        coordinates = {name: choice_coordinate for name in CHOICES} | {
            name: gear_coordinate for name in GEARS
        }
        values = [
            coordinates[name](self.entries, self.ratio_ranges, design, name)
            if name in coordinates
            else value_of(design, name)
            for name in self.names
        ]
        clipped: ArrayF = np.clip(np.array(values, dtype=float), self.lower, self.upper)
        return clipped

    @property
    def _battery(self) -> Battery:
        if self.base.battery is None:
            raise ParameterError(BATTERY, None, "needs a [battery] in the design to size")
        return self.base.battery

    def widened(
        self, name: str, lower: float | None = None, upper: float | None = None
    ) -> SearchSpace:
        """The same space with one variable's bounds moved (to search a relaxed requirement)."""
        variables = tuple(
            FreeVariable(
                v.name, v.lower if lower is None else lower, v.upper if upper is None else upper
            )
            if v.name == name
            else v
            for v in self.variables
        )
        return dataclasses.replace(self, variables=variables)


@dataclass(frozen=True)
class AtBound:
    """A free variable that a design holds at one of its search bounds: that bound binds.

    Attributes:
        variable: The free variable, with its bounds.
        bound: ``"lower"`` or ``"upper"``.

    """

    variable: FreeVariable
    bound: Literal["lower", "upper"]

    @property
    def value(self) -> float:
        """The bound [m or rad]."""
        return self.variable.lower if self.bound == "lower" else self.variable.upper

    @property
    def remedy(self) -> str:
        """What moves the bound, in words (an option of ``decide``)."""
        name = self.variable.name
        moved = f"--free {name}=LOWER:UPPER moves it"
        if name == "l1" and self.bound == "lower":
            return f"--min-coxa sets the coxa you can build; {moved}"
        return f"stance_limits in the design file or {moved}" if name in POSTURE else moved

    def __str__(self) -> str:
        return (
            f"{self.variable.name} at its {self.bound} bound {self.value:.4g} {self.variable.unit}"
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (the variable's unit: m or rad)."""
        return {
            "variable": self.variable.name,
            "bound": self.bound,
            "value": self.value,
            "unit": self.variable.unit,
            "binds": True,
            "description": f"{self} (binds: {self.remedy})",
        }


def value_of(design: HexapodDesign, name: str) -> float:
    """The free variable ``name``'s value in ``design`` [m or rad]."""
    if name in POSTURE:
        return float(design.nominal_angles[1 + POSTURE.index(name)])
    if name == BATTERY:
        return math.nan if design.battery is None else design.battery.capacity
    return float(getattr(design, name))


def bounds_reached(
    variables: Sequence[FreeVariable],
    design: HexapodDesign,
    steps: Mapping[str, float | None] | None = None,
) -> tuple[AtBound, ...]:
    """Each free variable ``design`` holds at a bound (within :data:`AT_BOUND_SHARE` of its range).

    A search's answer pressed against a bound is limited by that bound, as by a requirement
    that binds: moving the bound would move the answer. ``steps``: each variable's grid
    step where the answer was rounded [m or rad]: the grid point next to a bound is at it.
    """
    reached = []
    for variable in variables:
        if variable.name in (*CHOICES, *GEARS):
            continue  # a catalog entry has no bound to press against; its ratio range is its own
        step = (steps or {}).get(variable.name) or 0.0
        value, near = (
            value_of(design, variable.name),
            max(AT_BOUND_SHARE * (variable.upper - variable.lower), step),
        )
        if value <= variable.lower + near:
            reached.append(AtBound(variable, "lower"))
        elif value >= variable.upper - near:
            reached.append(AtBound(variable, "upper"))
    return tuple(reached)


def segment_floor(leg_length: float) -> float:
    """A segment's default lower bound [m] for a leg of ``leg_length`` [m].

    :data:`SEGMENT_FLOOR` of the leg length, or the shortest segment a design may have if
    that is longer.
    """
    return max(SEGMENT_FLOOR * leg_length, SEGMENT_RANGE[0])


def search_space(
    base: HexapodDesign,
    leg_length: float,
    min_coxa: float | None = None,
    free_posture: bool = False,
    free: Sequence[FreeVariable] = (),
    actuators: Sequence[Actuator] = (),
    battery: bool = False,
    ratio_ranges: Sequence[tuple[float, float] | None] | None = None,
    robot: Robot | None = None,
) -> SearchSpace:
    """The default free variables of a decision, with ``free`` added or overriding them.

    Args:
        base: The user's design: every field not freed.
        leg_length: The largest l1 + l2 + l3 [m]: each segment's upper bound.
        min_coxa: The smallest coxa [m]: l1's lower bound (if above the floor).
        free_posture: Also free the nominal hip and knee angles, within the stance limits.
        free: More free variables, or other bounds for the default ones.
        actuators: The catalog's actuators, to pick one per joint type from (none: the
            design's own are kept).
        battery: Free the battery's capacity (a range is required), if the design has one.
        ratio_ranges: Each of ``actuators``' lowest and highest gear ratio [-] (None: its
            own only): free each joint type's within its entry's (None: ratios kept).
        robot: The robot the points are (hexaleg's template over ``base`` if omitted): its
            segments searched within its :meth:`~hexaleg.robot.robot.Robot.segment_bounds`.

    """
    robot = template_robot(base) if robot is None else robot
    chosen = _segments(leg_length, min_coxa, robot)
    limits = base.stance_limits
    if free_posture:
        chosen["theta2"] = FreeVariable("theta2", *limits.theta2)
        chosen["theta3"] = FreeVariable("theta3", *limits.theta3)
    allowed = {name: (SEGMENT_RANGE[0], leg_length, LEG_CAP) for name in SEGMENTS}
    if min_coxa is not None:
        allowed["l1"] = (min_coxa, leg_length, LEG_CAP + ", l1 at least min_coxa")
    allowed |= {name: (*getattr(limits, name), STANCE_CAP) for name in POSTURE}
    given: set[str] = set()
    for variable in free:
        if variable.name in given:
            raise ParameterError(
                "--free", f"{variable.name}={variable.typed}", f"{variable.name} is given twice"
            )
        given.add(variable.name)
        if variable.name in allowed:
            _check_within(variable, *allowed[variable.name])
        chosen[variable.name] = variable
    if BATTERY in chosen and base.battery is None:
        raise ParameterError(f"--free {BATTERY}", None, "needs a [battery] in the design")
    if battery and base.battery is not None and BATTERY not in chosen:
        chosen[BATTERY] = FreeVariable(BATTERY, *CAPACITY_BOUNDS)
    bounds, spans = actuator_bounds(actuators, ratio_ranges)
    chosen |= {name: FreeVariable(name, *bound) for name, bound in bounds.items()}
    return SearchSpace(base, tuple(chosen.values()), tuple(actuators), spans, robot)


def _segments(leg_length: float, min_coxa: float | None, robot: Robot) -> dict[str, FreeVariable]:
    """The segments' default bounds: the robot's (the whole leg, or around a file's own)."""
    own = robot.segment_bounds(segment_floor(leg_length), leg_length)
    if min_coxa is not None and min_coxa >= leg_length:
        raise ParameterError("min_coxa", min_coxa, f"must be below leg_length ({leg_length:g} m)")
    if min_coxa is not None and "l1" in own:
        own["l1"] = (max(min_coxa, own["l1"][0]), leg_length)
    return {name: FreeVariable(name, *bounds) for name, bounds in own.items()}


def _check_within(variable: FreeVariable, low: float, high: float, why: str) -> None:
    """Refuse a segment's bounds beyond the leg length, an angle's beyond the stance limits.

    A segment searched beyond the leg length (or below ``min_coxa``) would return a leg
    breaking the very requirement that set the bound; a nominal angle beyond the stance
    limits, only designs that cannot stand.
    """
    if variable.lower >= low and variable.upper <= high:
        return
    raise ParameterError(
        f"--free {variable.name}",
        variable.typed,
        f"bounds within [{low:.4g}, {high:.4g}] [{variable.unit}] ({why})",
    )
