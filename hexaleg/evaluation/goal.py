"""What a decision measures every design for: its requirements and its objective.

An :class:`Objective` makes one metric (:data:`~hexaleg.evaluation.metrics.METRICS`) best; a
:class:`Goal` pairs it with the requirements (:mod:`hexaleg.evaluation.requirements`), names
the metrics both need and the conditions they are measured under, and measures a design
for them (:meth:`Goal.evaluate`, one :func:`~hexaleg.evaluation.evaluate.evaluate`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace

from hexaleg.design import HexapodDesign
from hexaleg.evaluation.evaluate import Conditions, Evaluation, evaluate, evaluate_many
from hexaleg.evaluation.metrics import (
    METRICS,
    TABLE_WORDS,
    Better,
    DesignTable,
    MetricSpec,
    objectives,
)
from hexaleg.evaluation.requirement_specs import REQUIREMENTS, SLOPE
from hexaleg.evaluation.requirements import RequirementCheck, Requirements, check
from hexaleg.evaluation.walks import walking_grounds
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.extremes import FlexibilityResult
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.statics.forces import Payload


@dataclass(frozen=True)
class Objective:
    """What the decision makes best.

    Attributes:
        name: The metric: any of :data:`~hexaleg.evaluation.metrics.METRICS` (the command line
            offers those declared as objectives, in their better direction).
        sense: ``"maximize"`` or ``"minimize"``.

    """

    name: str = METRICS.fb.name
    sense: Better = "maximize"

    def __post_init__(self) -> None:
        if self.sense not in ("maximize", "minimize") or self.name not in METRICS:
            raise HexalegError(
                f"{self.sense} {self.name!r} is not valid: --maximize takes "
                f"{', '.join(objectives('maximize'))}; --minimize takes "
                f"{', '.join(objectives('minimize'))}"
            )

    def cost(self, value: float) -> float:
        """The value as a cost to minimize (its negative when maximizing)."""
        return -value if self.sense == "maximize" else value

    def __str__(self) -> str:
        return f"{self.sense} {self.name}"

    @property
    def spec(self) -> MetricSpec:
        """The metric's declaration."""
        return METRICS.named(self.name)


@dataclass(frozen=True)
class Goal:
    """What every design of a decision is measured for.

    Attributes:
        requirements: The requirements, resolved (the leg length set).
        objective: What to make best.
        relaxed: Requirements left out of the constraints (their metrics still measured).

    """

    requirements: Requirements
    objective: Objective = field(default_factory=Objective)
    relaxed: tuple[str, ...] = ()

    @property
    def constraints(self) -> tuple[str, ...]:
        """The requirements every design must meet."""
        return tuple(name for name in self.requirements.given if name not in self.relaxed)

    @property
    def metrics(self) -> tuple[MetricSpec, ...]:
        """The metrics to measure: the requirements' and the objective's, in declared order."""
        needed = {REQUIREMENTS[name].metric for name in self.requirements.given}
        needed.add(self.objective.spec)
        return tuple(spec for spec in METRICS if spec in needed)

    @property
    def walks(self) -> bool:
        """Whether the designs walk the requirements' gait (a walking metric is needed)."""
        return any(spec.walks for spec in self.metrics)

    @property
    def conditions(self) -> Conditions:
        """The conditions of the requirements.

        Their payload, the slope stood on, the gait, the grounds it is walked on (the
        walking slope up, down and across) and the motors' safety factor.
        """
        requirements = self.requirements
        payload = Payload(requirements.payload_mass, requirements.payload_at)
        gait = requirements.gait
        return Conditions(
            payload,
            requirements.required(SLOPE),
            gait,
            grounds=walking_grounds(requirements.walking_slope, gait),
            safety_factor=requirements.motor_safety_factor,
        )

    def with_objective(self, objective: Objective, relaxed: tuple[str, ...] = ()) -> Goal:
        """The same requirements for another objective, some of them relaxed."""
        return replace(self, objective=objective, relaxed=relaxed)

    def evaluate(
        self,
        design: HexapodDesign,
        model: HexapodModel | None = None,
        template: StanceGeometry | None = None,
        flexibility: FlexibilityResult | None = None,
    ) -> Evaluation:
        """``design``'s metrics for this goal; an error if its objective has no value.

        The arguments after ``design`` are :func:`~hexaleg.evaluation.evaluate.evaluate`'s.
        """
        found = evaluate(
            design,
            self.metrics,
            self.conditions,
            model=model,
            template=template,
            flexibility=flexibility,
        )
        return self._measured(found)

    def evaluate_many(
        self,
        designs: Sequence[HexapodDesign],
        models: Sequence[HexapodModel],
        template: StanceGeometry | None,
    ) -> list[Evaluation]:
        """:meth:`evaluate` of designs of one robot (see :func:`~.evaluation.evaluate_many`)."""
        found = evaluate_many(designs, self.metrics, self.conditions, models, template)
        return [self._measured(evaluation) for evaluation in found]

    def _measured(self, evaluation: Evaluation) -> Evaluation:
        """The evaluation, or an error when the objective could not be measured."""
        why = evaluation.unmeasured[self.objective.spec]
        return Evaluation(error=why) if why else evaluation

    def measurable(self, design: HexapodDesign, actuators: bool = False) -> Goal:
        """The goal itself, once ``design`` is found to measure all it asks for.

        ``actuators``: motors are being chosen (from a catalog) for every design.

        Raises:
            ParameterError: Before any search, the requirement (or ``maximize`` /
                ``minimize``) whose metric needs a design-file table ``design`` lacks
                (:attr:`~hexaleg.evaluation.metrics.MetricSpec.needs`).

        """
        requirements = self.requirements
        asked: list[tuple[str, MetricSpec, object]] = [
            (spec.name, spec.metric, requirements.required(spec))
            for spec in REQUIREMENTS.values()
            if spec.name in requirements.given
        ]
        asked.append((self.objective.sense, self.objective.spec, self.objective.name))
        for name, metric, value in asked:
            lacking = metric.lacks(design, actuators)
            if lacking:
                raise ParameterError(name, value, _needs(metric, lacking))
        return self

    def checks(self, evaluation: Evaluation) -> tuple[RequirementCheck, ...]:
        """Each requirement checked on an evaluation (its value, margin, what limits it)."""
        return check(self.requirements, evaluation.metrics, evaluation.causes)

    def meets(self, evaluation: Evaluation) -> bool:
        """Whether the design was measured and meets every constraint."""
        if evaluation.error:
            return False
        return all(c.met for c in self.checks(evaluation) if c.name in self.constraints)


def _needs(metric: MetricSpec, lacking: tuple[DesignTable, ...]) -> str:
    """What ``metric`` needs that a design lacks (``lacking``: tables), in words."""
    needed = " and ".join(words for table, words in TABLE_WORDS.items() if table in lacking)
    chosen = " (or --choose-actuators)" if "actuators" in lacking else ""
    return f"{metric.label} needs {needed} in the design file{chosen}: the {metric.text}"
