"""The best leg by the ranking rule, its posture free: what the recommendation searches.

A leg here is the user's robot with its segments at a coxa and a tibia ratio of its leg
length (or its own segments) and its nominal posture θ = (0, θ2, θ3), θ2 and θ3 within its
stance limits. :class:`Legs` measures each leg at most once — every metric the report
shows, its analyses kept, in one :func:`~hexaleg.evaluation.evaluate.evaluate` — and ranks
it by the rule of :mod:`hexaleg.study.ranking`: the constraint first, then the score. Two
searches use it:

- :func:`best_posture_of` keeps the lengths and frees the posture: the user's lengths at
  their best posture, where only the posture changes (the user's posture is a candidate,
  so it is never worse than the design as posed);
- :func:`best_leg_at` frees the tibia ratio and the posture at one coxa ratio.

Both search the unit box of their free variables with
:func:`~hexaleg.numerics.box_search.box_minimum` (DIRECT, then Nelder–Mead), feasibility
first: a leg meeting the constraint costs −log(score), one that does not
:data:`PENALTY` plus its shortfall, one that cannot exist or stand :data:`UNSTANDING`.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable
from dataclasses import dataclass

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.design import SEGMENTS, HexapodDesign
from hexaleg.evaluation.evaluate import Conditions, Evaluation, evaluate
from hexaleg.evaluation.metrics import Metrics, MetricSpec
from hexaleg.exceptions import HexalegError
from hexaleg.grids import ratio_lengths
from hexaleg.numerics.box_search import box_minimum
from hexaleg.robot.robot import Robot
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.study.ranking import WALKING, WalkingConstraint, score

PENALTY = 1e6
"""Cost of a leg that misses the constraint (its shortfall, at most 1, is added)."""

UNSTANDING = 10 * PENALTY
"""Cost of a leg that cannot exist or stand at a point of the box."""

POSTURE_SEARCH = (100, ((80, 1e-2), (40, 1e-3)))
"""The posture search's budget: DIRECT's points, then Nelder–Mead's rounds (points, simplex)."""

LEG_SEARCH = (150, ((100, 5e-2), (60, 5e-3)))
"""The tibia-and-posture search's budget, as :data:`POSTURE_SEARCH`."""


@dataclass(frozen=True)
class Leg:
    """One leg measured and ranked.

    Attributes:
        robot: The robot at the leg's segments and posture.
        evaluation: Its one evaluation.
        score: Its score by the ranking rule [-] (NaN: it has none).
        meets: Whether it meets the constraint (walks the gait carrying the payload).

    """

    robot: Robot
    evaluation: Evaluation
    score: float
    meets: bool

    @property
    def design(self) -> HexapodDesign:
        """The leg's design."""
        return self.robot.design

    @property
    def l1_ratio(self) -> float:
        """Coxa ratio l1/L [-]."""
        return self.design.l1 / self.design.leg_length

    @property
    def l3_ratio(self) -> float:
        """Tibia ratio l3/L [-]."""
        return self.design.l3 / self.design.leg_length

    @property
    def ranked(self) -> bool:
        """Whether it meets the constraint and has a score."""
        return self.meets and math.isfinite(self.score)

    @property
    def capacity(self) -> float:
        """Its walking payload capacity [kg] (NaN: not measured)."""
        return self.evaluation.metrics.value(WALKING)

    @property
    def limited_by(self) -> str:
        """What limits its walking payload capacity (or why it has none)."""
        cause = self.evaluation.causes[WALKING]
        return str(cause) if cause is not None else self.evaluation.unmeasured[WALKING] or ""

    def cost(self, constraint: WalkingConstraint) -> float:
        """What the searches minimize: −log(score), or a penalty (see the module docstring)."""
        if self.evaluation.error:
            return UNSTANDING
        if not self.meets:
            return PENALTY + constraint.shortfall(self.capacity, self.evaluation.walks)
        return -math.log(self.score) if math.isfinite(self.score) else PENALTY + 1.0


class Legs:
    """Legs of one robot, each measured once, ranked against the user's design.

    Args:
        base: The user's robot (its body, mounts, motors and stance limits are every leg's).
        metrics: What each leg is measured for (the report's metrics).
        conditions: What each leg is measured under.
        constraint: What each leg must do first.
        reference: The user's design's metrics, which scores are relative to.
        known: Legs already measured (the user's design as posed): never measured again.

    """

    def __init__(
        self,
        base: Robot,
        metrics: Collection[MetricSpec],
        conditions: Conditions,
        constraint: WalkingConstraint,
        reference: Metrics,
        known: Iterable[Leg] = (),
    ) -> None:
        self.base, self.metrics, self.conditions = base, tuple(metrics), conditions
        self.constraint, self.reference = constraint, reference
        self.template = StanceGeometry.template_of(base.model, conditions.stance)
        self.seen: dict[HexapodDesign, Leg] = {}
        self.measured = 0
        self.know(known)

    def know(self, known: Iterable[Leg]) -> None:
        """Legs measured elsewhere: never measured again here."""
        self.seen |= {leg.design: leg for leg in known}

    def posed(self, robot: Robot, angles: tuple[float, float]) -> Leg | None:
        """``robot`` at θ = (0, θ2, θ3), measured once; ``None`` if it cannot stand so."""
        try:
            return self._measured(robot.at(nominal_angles=(0.0, *angles)))
        except HexalegError:
            return None

    def at(self, l1_ratio: float, l3_ratio: float, angles: tuple[float, float]) -> Leg | None:
        """The base at these ratios of its leg length and posture; ``None`` if it cannot exist."""
        try:
            lengths = ratio_lengths(l1_ratio, l3_ratio, self.base.design.leg_length)
            robot = self.base.at(
                **dict(zip(SEGMENTS, lengths, strict=True)), nominal_angles=(0.0, *angles)
            )
            return self._measured(robot)
        except HexalegError:
            return None

    def _measured(self, robot: Robot) -> Leg:
        """``robot``'s leg: its one evaluation, made the first time it is asked for."""
        design = robot.design
        if design not in self.seen:
            found = evaluate(
                design,
                self.metrics,
                self.conditions,
                model=robot.model,
                template=self.template,
            )
            self.seen[design] = ranked_leg(robot, found, self.constraint, self.reference)
            self.measured += 1
        return self.seen[design]

    def cost(self, leg: Leg | None) -> float:
        """A leg's cost for the searches (:meth:`Leg.cost`; a leg that cannot exist: most)."""
        return UNSTANDING if leg is None else leg.cost(self.constraint)


def ranked_leg(
    robot: Robot, evaluation: Evaluation, constraint: WalkingConstraint, reference: Metrics
) -> Leg:
    """``robot`` ranked from its evaluation: whether it meets ``constraint``, its score."""
    meets = constraint.meets(evaluation)
    found = score(evaluation.metrics, reference) if meets else math.nan
    return Leg(robot, evaluation, found, meets)


class _Box:
    """The unit box mapped onto free variables [lower, upper] each."""

    def __init__(self, bounds: Iterable[tuple[float, float]]) -> None:
        pairs = np.array(list(bounds), dtype=float)
        self.lower, self.span = pairs[:, 0], pairs[:, 1] - pairs[:, 0]

    def values(self, unit: ArrayF) -> tuple[float, ...]:
        """The variables at a point of the unit box."""
        return tuple(float(v) for v in self.lower + np.clip(unit, 0.0, 1.0) * self.span)

    def unit(self, values: Iterable[float]) -> ArrayF:
        """A point of the unit box of the variables ``values`` (clipped to it)."""
        point: ArrayF = (np.asarray(list(values), dtype=float) - self.lower) / self.span
        return np.clip(point, 0.0, 1.0)


def best_posture_of(legs: Legs, robot: Robot) -> Leg:
    """``robot``'s lengths at their best posture: θ2, θ3 within its stance limits free.

    ``robot``'s own posture is a candidate: the answer is never worse than it.
    """
    limits = robot.design.stance_limits
    box = _Box((limits.theta2, limits.theta3))
    given = robot.design.nominal_angles[1:]

    def leg(unit: ArrayF) -> Leg | None:
        theta2, theta3 = box.values(unit)
        return legs.posed(robot, (theta2, theta3))

    evaluations, polish = POSTURE_SEARCH
    best = box_minimum(
        lambda unit: legs.cost(leg(unit)),
        box.unit(given),
        global_evaluations=evaluations,
        polish=polish,
    )
    found = leg(best)
    start = legs.posed(robot, (given[0], given[1]))
    return min((x for x in (found, start) if x is not None), key=legs.cost)


def best_leg_at(
    legs: Legs,
    l1_ratio: float,
    l3_range: tuple[float, float],
    start: tuple[float, float, float] | None = None,
) -> Leg | None:
    """The best leg at coxa ratio ``l1_ratio``: its tibia ratio and posture free.

    Args:
        legs: The legs measured so far, and how to measure and rank one.
        l1_ratio: The coxa ratio [-].
        l3_range: The tibia ratios searched [-].
        start: A candidate (tibia ratio, θ2, θ3); the box's centre if omitted.

    Returns:
        The best leg found (it may miss the constraint: see :attr:`Leg.ranked`); ``None``
        when no leg of the box can exist.

    """
    limits = legs.base.design.stance_limits
    box = _Box((l3_range, limits.theta2, limits.theta3))

    def leg(unit: ArrayF) -> Leg | None:
        l3_ratio, theta2, theta3 = box.values(unit)
        return legs.at(l1_ratio, l3_ratio, (theta2, theta3))

    evaluations, polish = LEG_SEARCH
    given = np.full(3, 0.5) if start is None else box.unit(start)
    best = box_minimum(
        lambda unit: legs.cost(leg(unit)), given, global_evaluations=evaluations, polish=polish
    )
    return leg(best)
