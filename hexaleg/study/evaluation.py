"""One design measured for a decision: the metrics its requirements and objective need.

A metric is a number a design has (FB, payload, slope, ...). Requirements bound
metrics (:mod:`hexaleg.study.requirements`), an :class:`Objective` ranks by one.
:func:`evaluate_design` measures every metric a :class:`Goal` needs with the exact
single-design analyses: the improved workspace area (eq 16), the average manipulability
w_A (eq 27) and axis-locked flexibility FB (eq 29) as :mod:`hexaleg.study.metrics`
combines them, the statics' payload capacity (:mod:`hexaleg.statics`), the slope and
payload limits of :mod:`hexaleg.study.standing`, and walking (:mod:`hexaleg.gait`): the
requirements' gait (:attr:`~hexaleg.study.requirements.Requirements.gait`, carrying the
required payload) walked once at its speed gives the max speed at its stride and the peak
torque and cost of transport at that speed. Given a model and a stance template of the
same body (the fast path of searches), it derives the design's own from them in closed
form; the tests prove both paths equal.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from hexaleg._typing import choices
from hexaleg.cause import Cause
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.gait.analysis import analyze_gait
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.axis_locked import axis_locked_flexibility
from hexaleg.stance.extremes import FlexibilityResult
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.statics.capacity import payload_capacity
from hexaleg.statics.forces import Payload, Statics
from hexaleg.study.requirements import KINDS, RequirementCheck, Requirements, check
from hexaleg.study.standing import Standing
from hexaleg.swing.manipulability import average_manipulability, rectangular_and_improved
from hexaleg.swing.workspace import improved_area_closed_form

Sense = Literal["maximize", "minimize"]
"""Which way an objective is better."""

MaximizeObjective = Literal["fb", "w_A", "area", "payload", "speed"]
"""What ``--maximize`` takes: FB [-], w_A [m³], improved area [m²], payload [kg], speed [m/s]."""

MinimizeObjective = Literal["leg_length", "mass", "peak_torque", "cost_of_transport"]
"""What ``--minimize`` takes: l1+l2+l3 [m], total mass [kg], gait peak torque [N·m], CoT [-]."""

METRIC_UNITS: dict[str, str] = {
    "fb": "1",
    "w_A": "m³",
    "area": "m²",
    "payload": "kg",
    "slope": "rad",
    "ground_clearance": "m",
    "leg_length": "m",
    "coxa": "m",
    "mass": "kg",
    "speed": "m/s",
    "peak_torque": "N·m",
    "cost_of_transport": "1",
}
"""Every metric a decision can use, with its unit."""

METRIC_NAMES: dict[str, str] = {
    "fb": "FB",
    "area": "improved area",
    "leg_length": "leg length",
    "ground_clearance": "ground clearance",
    "peak_torque": "peak torque",
    "cost_of_transport": "cost of transport",
}
"""A metric's name in sentences, where it differs from its key."""

GAIT_METRICS = ("speed", "peak_torque", "cost_of_transport")
"""Metrics of a tripod gait (:mod:`hexaleg.gait`)."""

STATICS_METRICS = ("payload", "slope", *GAIT_METRICS)
"""Metrics that need the design's Pinocchio model."""


@dataclass(frozen=True)
class Objective:
    """What the decision makes best.

    Attributes:
        name: The metric: any of :data:`METRIC_UNITS` (the command line offers
            :data:`MaximizeObjective` and :data:`MinimizeObjective`).
        sense: ``"maximize"`` or ``"minimize"``.

    """

    name: str = "fb"
    sense: Sense = "maximize"

    def __post_init__(self) -> None:
        if self.sense not in ("maximize", "minimize") or self.name not in METRIC_UNITS:
            raise HexalegError(
                f"{self.sense} {self.name!r} is not valid: --maximize takes "
                f"{', '.join(choices(MaximizeObjective))}; --minimize takes "
                f"{', '.join(choices(MinimizeObjective))}"
            )

    def cost(self, value: float) -> float:
        """The value as a cost to minimize (its negative when maximizing)."""
        return -value if self.sense == "maximize" else value

    def __str__(self) -> str:
        return f"{self.sense} {self.name}"

    @property
    def label(self) -> str:
        """The metric's name in a sentence (``FB``, ``improved area``)."""
        return METRIC_NAMES.get(self.name, self.name)


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
    def walks(self) -> bool:
        """Whether the designs walk the requirements' gait (a walking metric is needed)."""
        return bool(set(self.metrics) & set(GAIT_METRICS))

    @property
    def metrics(self) -> tuple[str, ...]:
        """The metrics to measure: the requirements' and the objective's."""
        needed = {KINDS[name].metric for name in self.requirements.given}
        return tuple(name for name in METRIC_UNITS if name in needed | {self.objective.name})


@dataclass(frozen=True)
class Evaluation:
    """One design's metrics, or why it could not be measured.

    Attributes:
        values: Each metric's value [its unit].
        causes: What limits a metric, where something does (payload, slope, speed).
        error: Why the design cannot exist or stand; empty if it was measured.

    """

    values: Mapping[str, float] = field(default_factory=dict)
    causes: Mapping[str, Cause] = field(default_factory=dict)
    error: str = ""

    def checks(self, requirements: Requirements) -> tuple[RequirementCheck, ...]:
        """Each requirement checked on this design (its value, margin and what limits it)."""
        return check(requirements, self.values, self.causes)

    def meets(self, goal: Goal) -> bool:
        """Whether the design was measured and meets every constraint of ``goal``."""
        if self.error:
            return False
        return all(c.met for c in self.checks(goal.requirements) if c.name in goal.constraints)


def evaluate_design(
    design: HexapodDesign,
    goal: Goal,
    model: HexapodModel | None = None,
    template: StanceGeometry | None = None,
    flexibility: FlexibilityResult | None = None,
) -> Evaluation:
    """Measure every metric ``goal`` needs on ``design``.

    Args:
        design: The design.
        goal: What to measure it for.
        model: The design's Pinocchio model; built from its URDF if omitted.
        template: A stance geometry of the same body and mounts (fast path); read from
            the model if omitted.
        flexibility: The design's axis-locked flexibility, if already computed (a
            search computes a batch of designs' at once).

    A design whose analyses fail (its nominal stance cannot stand) is returned with
    ``error`` set and no values.

    """
    try:
        return _measure(design, goal, model, template, flexibility)
    except HexalegError as err:
        return Evaluation(error=str(err))


def _measure(
    design: HexapodDesign,
    goal: Goal,
    model: HexapodModel | None,
    template: StanceGeometry | None,
    flexibility: FlexibilityResult | None,
) -> Evaluation:
    wanted = goal.metrics
    values: dict[str, float] = {
        "leg_length": design.leg_length,
        "coxa": design.l1,
        "mass": design.total_mass,
    }
    causes: dict[str, Cause] = {}
    if template is None and {"fb", "ground_clearance"} & set(wanted):
        model = HexapodModel(design) if model is None else model
        template = StanceGeometry.from_model(model)  # the design's own: exact
    if "fb" in wanted:
        if flexibility is None:
            flexibility = axis_locked_flexibility(design, "all", geometry=template)
        values["fb"] = flexibility.fb
    if "area" in wanted:
        values["area"] = improved_area_closed_form(design.l2, design.l3)
    if "w_A" in wanted:
        _, improved = rectangular_and_improved(design.manipulability_limits)
        values["w_A"] = float(average_manipulability(design.lengths, improved))
    if "ground_clearance" in wanted and template is not None:
        geometry = template.with_design(design)
        values["ground_clearance"] = float(
            geometry.lowest_body_height(np.eye(3), [0.0, 0.0, geometry.nominal_height])
        )
    if {"payload", "slope"} & set(wanted):
        model = HexapodModel(design) if model is None else model  # the exact path
        _standing_metrics(model, goal.requirements, values, causes)
    if goal.walks:
        model = HexapodModel(design) if model is None else model
        _walking_metrics(model, goal, values, causes)
    return Evaluation({name: values[name] for name in wanted}, causes)


def _walking_metrics(
    model: HexapodModel, goal: Goal, values: dict[str, float], causes: dict[str, Cause]
) -> None:
    """Max speed [m/s] at the gait's stride; peak torque [N·m] and CoT [-] at its speed.

    Raises:
        HexalegError: the objective is a walking metric and the gait's stride cannot
            be walked (the metric has no value).

    """
    requirements = goal.requirements
    payload = Payload(requirements.payload_mass, requirements.payload_at)
    walked = analyze_gait(
        model.design, requirements.gait, payload, model=model, limits=False, speed=True
    )
    assert walked.max_speed is not None  # speed=True
    values["speed"], causes["speed"] = walked.max_speed.value, walked.max_speed.limited_by
    if goal.objective.name in ("peak_torque", "cost_of_transport") and not walked.feasible:
        raise HexalegError(f"cannot walk the gait: {walked.violations[0]}")
    values["peak_torque"] = max(walked.metrics.peak_torque.values())
    values["cost_of_transport"] = walked.metrics.cost_of_transport


def _standing_metrics(
    model: HexapodModel,
    requirements: Requirements,
    values: dict[str, float],
    causes: dict[str, Cause],
) -> None:
    """Payload [kg] on the required slope and slope [rad] with the required payload."""
    payload = Payload(requirements.payload_mass, requirements.payload_at)
    statics = Statics(model, model.leg_names, payload)
    standing = Standing.of(statics)
    if requirements.slope is None:  # level ground: the statics' own payload capacity
        capacity = payload_capacity(statics, model.nominal_configuration())
        values["payload"], causes["payload"] = capacity.mass, capacity.limited_by
    else:
        values["payload"], causes["payload"] = standing.max_payload(requirements.slope)
    values["slope"], causes["slope"] = standing.max_slope(requirements.payload_mass)
