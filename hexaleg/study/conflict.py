"""When no design meets every requirement: which ones conflict, and the nearest relaxations.

The search's least infeasible design shows where the requirements collide: each
requirement it violates or only just meets (it binds) is relaxed in turn, by a search
for the best value of that requirement among the designs that meet all the others —
the largest for an "at least" requirement, the smallest for an "at most" one. A
requirement whose relaxed search finds such a design is in the conflict, and that value
is its nearest relaxation: "payload 30 kg and slope 20° cannot both hold with hip
motors of 150 N·m; 26 kg or 17° can". If no single relaxation finds one, every violated
requirement is named and no relaxation is offered.

Payload and slope are one condition seen two ways (the payload is held on the required
slope, the slope stood on with the required payload), so relaxing either leaves the
other out too. The leg length and the coxa bound the search space: relaxing them widens
it (the leg up to :data:`LEG_RELAXATION` times as long).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from hexaleg.cause import Cause
from hexaleg.design import SEGMENTS, HexapodDesign
from hexaleg.evaluation.evaluate import Evaluation
from hexaleg.evaluation.goal import Goal, Objective
from hexaleg.evaluation.requirement_specs import (
    LEG_LENGTH,
    MIN_COXA,
    PAYLOAD,
    REQUIREMENTS,
    SLOPE,
)
from hexaleg.evaluation.requirements import Requirements
from hexaleg.limits import LEG_JOINTS
from hexaleg.statics.forces import DEFAULT_FRICTION
from hexaleg.study.optimize import SearchOutcome
from hexaleg.study.search_space import SearchSpace, segment_floor

LEG_RELAXATION = 2.0
"""How much longer than required a relaxed leg may grow [-]."""

COUPLED = {PAYLOAD.name: SLOPE.name, SLOPE.name: PAYLOAD.name}
"""Requirements that one condition states twice: relaxing one relaxes the other."""

Search = Callable[[SearchSpace, Goal], SearchOutcome]
"""Runs one search (the decision's executor, journal and settings bound in)."""


@dataclass(frozen=True)
class Relaxation:
    """The nearest value of one requirement that all the others allow.

    Attributes:
        name: The requirement.
        required: What was required [its unit].
        relaxed: The best value any design meeting all the others reaches [its unit].
        point: That design's point in the search space.

    """

    name: str
    required: float
    relaxed: float
    point: tuple[float, ...]

    @property
    def meets_original(self) -> bool:
        """Whether the relaxed value meets the original requirement after all."""
        return REQUIREMENTS[self.name].margin(self.required, self.relaxed) >= 0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (SI units, radians)."""
        return {"requirement": self.name, "required": self.required, "relaxed": self.relaxed}


@dataclass(frozen=True)
class Conflict:
    """Requirements that cannot all hold within the bounds, and how to make them hold.

    Attributes:
        requirements: The conflicting requirements.
        relaxations: For each one that can be relaxed alone, its nearest feasible value.
        description: The conflict in one sentence.

    """

    requirements: tuple[str, ...]
    relaxations: tuple[Relaxation, ...]
    description: str

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {
            "requirements": list(self.requirements),
            "relaxations": [r.to_dict() for r in self.relaxations],
            "description": self.description,
        }


def find_conflict(space: SearchSpace, goal: Goal, least: Evaluation, search: Search) -> Conflict:
    """The requirements that conflict at ``least`` (the least infeasible design), relaxed.

    Args:
        space: The decision's search space.
        goal: The decision's goal.
        least: The least infeasible design's evaluation.
        search: Runs one search of a space for a goal.

    """
    checks = goal.checks(least) if not least.error else ()
    asked = [name for name in goal.requirements.given if not REQUIREMENTS[name].implied]
    suspects = [c.name for c in checks if (not c.met or c.binds) and c.name in asked] or asked
    relaxations = []
    for name in suspects:
        relaxation = _relax(space, goal, name, search)
        if relaxation is not None:
            relaxations.append(relaxation)
    names = tuple(r.name for r in relaxations) or tuple(c.name for c in checks if not c.met)
    found = (least.causes[REQUIREMENTS[n].metric] for n in names)
    causes = [cause for cause in found if cause is not None]
    text = describe(names, goal.requirements, causes, space.base, relaxations)
    return Conflict(names, tuple(relaxations), text)


def _relax(space: SearchSpace, goal: Goal, name: str, search: Search) -> Relaxation | None:
    """The nearest value of requirement ``name`` that the others allow (None: they do not)."""
    requirements, spec = goal.requirements, REQUIREMENTS[name]
    required = float(requirements.required(spec) or 0.0)
    objective = Objective(spec.metric.name, "maximize" if spec.sense == "at least" else "minimize")
    if spec is LEG_LENGTH:
        longest = min(LEG_RELAXATION * required, spec.bounds[1])
        relaxed_goal = Goal(requirements.replace(**{name: longest}), objective)
        widened = space
        for segment in SEGMENTS:
            widened = widened.widened(segment, upper=longest)
    elif spec is MIN_COXA:
        relaxed_goal = Goal(requirements.replace(**{name: None}), objective)
        floor = segment_floor(requirements.required(LEG_LENGTH) or float(space.upper.max()))
        widened = space.widened("l1", lower=floor)
    else:
        relaxed = (name, COUPLED[name]) if COUPLED.get(name) in requirements.given else (name,)
        relaxed_goal, widened = Goal(requirements, objective, relaxed), space
    outcome = search(widened, relaxed_goal)
    if not outcome.feasible:
        return None
    value = outcome.evaluation.metrics.value(spec.metric)
    return Relaxation(name, required, value, tuple(float(v) for v in outcome.x))


def describe(
    names: Sequence[str],
    requirements: Requirements,
    causes: Sequence[Cause],
    design: HexapodDesign,
    relaxations: Sequence[Relaxation],
) -> str:
    """The conflict in one sentence.

    For example "payload 30 kg and slope 20° cannot both hold with hip motors of
    150 N·m; 26 kg or 17° can".
    """
    listed = [
        f"{spec.metric.label} {short_value(n, float(requirements.required(spec) or 0.0))}"
        for n, spec in ((n, REQUIREMENTS[n]) for n in names)
    ]
    joined = listed[0] if len(listed) == 1 else ", ".join(listed[:-1]) + " and " + listed[-1]
    verb = {1: "cannot hold", 2: "cannot both hold"}.get(len(listed), "cannot all hold")
    because = _because(causes, design)
    if not because and LEG_LENGTH.name not in names:
        longest = requirements.required(LEG_LENGTH) or 0.0
        because = f"within a leg length of {short_value(LEG_LENGTH.name, longest)}"
    sentence = f"{joined} {verb}" + (f" {because}" if because else "")
    if not relaxations:
        return sentence + "; no one of them relaxed alone is enough"
    offers = " or ".join(short_value(r.name, r.relaxed) for r in relaxations)
    return f"{sentence}; {offers} can"


def _because(causes: Sequence[Cause], design: HexapodDesign) -> str:
    """What binds, in words: "with hip motors of 150 N·m", "without tipping"."""
    phrases: list[str] = []
    for cause in causes:
        if cause.kind == "torque" and cause.joint is not None and design.rated_torques:
            rated = design.rated_torques[LEG_JOINTS.index(cause.joint)]
            phrase = f"with {cause.joint} motors of {rated:g} N·m"
        elif cause.kind == "speed" and cause.joint is not None and design.rated_speeds:
            rated = design.rated_speeds[LEG_JOINTS.index(cause.joint)]
            phrase = f"with {cause.joint} motors of {rated:g} rad/s"
        elif cause.kind in ("tip", "stability"):
            phrase = "without tipping"
        elif cause.kind == "zmp":
            phrase = "with the ZMP inside the standing feet"
        elif cause.kind == "slide":
            phrase = f"without sliding (friction μ = {DEFAULT_FRICTION:g})"
        else:
            continue
        if phrase not in phrases:
            phrases.append(phrase)
    return " and ".join(phrases)


def short_value(name: str, value: float) -> str:
    """A requirement's value in a sentence: slopes in degrees, three significant digits."""
    return REQUIREMENTS[name].metric.short(value)
