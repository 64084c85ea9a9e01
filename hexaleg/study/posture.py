"""The best posture of given lengths: the nominal hip and knee angles that make a goal best.

A leg's lengths are judged at their best use. :func:`best_posture` keeps the design's
segments, body and motors and searches its nominal posture θ = (0, θ2, θ3), θ2 and θ3
within the design's stance limits, for the design that meets every requirement of a
:class:`~hexaleg.evaluation.goal.Goal` with the best objective (default: the largest walking
payload capacity), measured by the one :func:`~hexaleg.evaluation.evaluate.evaluate` every
decision uses. The answer is a :class:`~hexaleg.study.decide.DecideResult` whose free
variables are θ2 and θ3, so that it is put on the workshop's grid (0.001 rad), checked,
re-measured (from its own URDF) and printed exactly as ``decide`` answers its best; the design
as posed is "yours".

The search is deterministic and two-stage, on the box of the stance limits scaled to the
unit square (:func:`~hexaleg.numerics.box_search.box_minimum`, which the report's
recommendation shares):

- SciPy's DIRECT (Jones' dividing rectangles, locally biased, :data:`GLOBAL_EVALUATIONS`
  designs) finds the basin of the best posture: the objective of a posture is piecewise
  smooth with cliffs (a posture whose walk breaks a joint limit carries nothing), and its
  best often lies where a ridge (two joints at their ratings) meets such a cliff, a
  corner a grid only approaches;
- Nelder–Mead, twice (:data:`POLISH`), from DIRECT's best with a small simplex, climbs to
  that corner.

Each point scores feasibility first: a design meeting every requirement scores its cost
(the objective, negated when maximized); one that does not scores :data:`PENALTY` plus its
scaled violations (:func:`~hexaleg.study.optimize.objective_and_constraints`); one that
cannot stand (its feet above its body, say) scores more still. The posture as given is a
candidate too: the answer is never worse than it. The tests hold the answer against a
brute-force grid over the stance limits on seeded random designs.
"""

from __future__ import annotations

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.goal import Goal, Objective
from hexaleg.evaluation.metrics import METRICS
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.numerics.box_search import box_minimum
from hexaleg.robot.robot import POSTURE_FIELD, Robot, as_robot
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.study.decide import CheckedDesign, DecideResult, posture_figures, workshop_answer
from hexaleg.study.decide_grid import Rounding
from hexaleg.study.optimize import INVALID, objective_and_constraints
from hexaleg.study.search_space import POSTURE, FreeVariable, SearchSpace

__all__ = [
    "DEFAULT_OBJECTIVE",
    "best_posture",
    "posture_figures",
    "posture_variables",
]

DEFAULT_OBJECTIVE = Objective(METRICS.walking_payload_capacity.name)
"""What a posture makes best unless told otherwise: the payload carried walking."""

GLOBAL_EVALUATIONS = 100
"""Designs DIRECT evaluates to find the best posture's basin."""

POLISH: tuple[tuple[int, float], ...] = ((80, 1e-2), (40, 1e-3))
"""Nelder–Mead's rounds after DIRECT: (most designs, initial simplex size on the unit box)."""

PENALTY = 1e9
"""Score added to a posture that misses a requirement (its violations are added to it)."""

METHOD = (
    f"DIRECT (locally biased, {GLOBAL_EVALUATIONS} designs) over the stance limits, then "
    f"Nelder–Mead ({' then '.join(str(most) for most, _ in POLISH)} designs); feasibility first"
)
"""The search in words, as a decision states its method."""


def posture_variables(design: HexapodDesign) -> tuple[FreeVariable, FreeVariable]:
    """θ2 and θ3, each within the design's stance limits [rad]."""
    limits = design.stance_limits
    return FreeVariable(POSTURE[0], *limits.theta2), FreeVariable(POSTURE[1], *limits.theta3)


class _Scores:
    """Each posture's score, measured once: the unit square mapped onto θ2 and θ3."""

    def __init__(self, robot: Robot, goal: Goal) -> None:
        self.robot, self.design, self.goal = robot, robot.design, goal
        self.variables = posture_variables(self.design)
        self.lower = np.array([v.lower for v in self.variables])
        self.span = np.array([v.upper - v.lower for v in self.variables])
        self.template = StanceGeometry.from_model(robot.model)
        self.seen: dict[tuple[float, float], float] = {}

    def angles(self, unit: ArrayF) -> tuple[float, float]:
        """θ2, θ3 [rad] of a point of the unit square (clipped to it)."""
        theta2, theta3 = self.lower + np.clip(unit, 0.0, 1.0) * self.span
        return float(theta2), float(theta3)

    def unit(self, design: HexapodDesign) -> ArrayF:
        """A design's posture as a point of the unit square."""
        unit: ArrayF = (np.array(design.nominal_angles[1:]) - self.lower) / self.span
        return unit

    def posed(self, angles: tuple[float, float]) -> Robot:
        """The robot at θ = (0, θ2, θ3) (its model derived from the robot's)."""
        return self.robot.at(nominal_angles=(0.0, *angles))

    def __call__(self, unit: ArrayF) -> float:
        """The score of the posture at ``unit`` (see the module docstring)."""
        key = self.angles(np.asarray(unit, dtype=float))
        if key not in self.seen:
            self.seen[key] = self._score(key)
        return self.seen[key]

    def _score(self, angles: tuple[float, float]) -> float:
        try:
            posed = self.posed(angles)
            evaluation = self.goal.evaluate(posed.design, posed.model, self.template)
        except HexalegError:
            return 10 * PENALTY
        cost, violations = objective_and_constraints(self.goal, evaluation)
        if cost >= INVALID:
            return 10 * PENALTY
        missed = float(np.maximum(violations, 0.0).sum())
        return PENALTY + missed if missed > 0 else cost


def best_posture(
    robot: Robot | HexapodDesign,
    requirements: Requirements | None = None,
    objective: Objective = DEFAULT_OBJECTIVE,
    rounding: Rounding | None = None,
) -> DecideResult:
    """The best nominal posture of ``robot``'s lengths for ``objective``, meeting ``requirements``.

    Args:
        robot: The robot (a design: hexaleg's template at it): its lengths, body, motors
            and stance limits are kept; its posture is "yours" and a candidate. Each
            posture's robot is derived from it (:meth:`~hexaleg.robot.robot.Robot.at`).
        requirements: What the robot must do (none by default).
        objective: What to make best (default: the walking payload capacity).
        rounding: The grid the answer's angles are put on (default 0.001 rad), as
            ``decide``'s (:func:`~hexaleg.study.decide.workshop_answer`).

    Returns:
        The decision over θ2 and θ3: ``best`` the lengths at their best posture on the
        grid, re-measured from their own URDF; ``yours`` the robot as posed.

    Raises:
        ParameterError: ``robot`` is neither a robot nor a design; a robot whose posture is
            not searched (a robot file stands as its file does); a requirement or the
            objective the robot cannot measure (a table its design file lacks).

    """
    robot = _robot(robot)
    requirements = requirements or Requirements()  # the lengths stay: no leg length to hold
    goal = Goal(requirements, objective).measurable(robot.design)
    scores = _Scores(robot, goal)
    best = box_minimum(
        scores, scores.unit(robot.design), global_evaluations=GLOBAL_EVALUATIONS, polish=POLISH
    )
    space = SearchSpace(robot.design, scores.variables, robot=robot)
    feasible = scores(best) < PENALTY  # meets every requirement
    checked, rounded = workshop_answer(
        space, goal, scores.angles(best), feasible, rounding or Rounding(), None
    )
    return DecideResult(
        requirements=requirements, objective=objective, variables=scores.variables,
        best=checked, yours=CheckedDesign.of(robot, goal), feasible=checked.meets_all,
        conflict=None, method=METHOD, evaluations=len(scores.seen), seed=0,
        robot=robot.source.path, rounded=rounded,
    )  # fmt: skip


def _robot(given: Robot | HexapodDesign) -> Robot:
    """The robot posed (a design: hexaleg's template at it), if its posture may be searched.

    Raises:
        ParameterError: Neither a robot nor a design; a robot file (its posture is its own).

    """
    given = as_robot(given)
    if not given.searches(POSTURE_FIELD):
        raise ParameterError(
            "robot", given.name, "a robot whose posture may change: a robot file stands as "
            "its file does"
        )  # fmt: skip
    return given
