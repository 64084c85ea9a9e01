"""One evaluation of a design: every metric anyone asks for, each analysis run at most once.

:func:`evaluate` measures the metrics of :data:`~hexaleg.evaluation.metrics.METRICS` that a
caller names — a study's row, a decision's candidate, the report's recommendation, the
user's own design — under one set of :class:`Conditions` (payload, slope stood on, gait,
the grounds it is walked on, the motors' safety factor, stance legs, collisions), into one
frozen :class:`Evaluation`. Each metric's analysis runs once however many of its metrics
are asked for: the improved workspace area in closed form (eq 16), the average
manipulability w_A on the improved domain (eq 27), the axis-locked or free-coupled
flexibility FB (eq 29), the ground clearance of the nominal stance, the statics' payload
capacity and steepest slope (:mod:`hexaleg.statics.standing_limits`), the gait walked on
each ground for the walking payload capacity and one period for the max speed, peak torque
and cost of transport (:mod:`.walks`: each the worst over the grounds), and the legs' tubes
(:mod:`hexaleg.structure`). A design whose ``[structure]`` says ``size = true`` has its
tubes sized first (:mod:`.sizing`): every metric is the sized design's.

Given a model and a stance template of the same body (the fast path of sweeps and
searches), a design's own are derived from them in closed form; without, they are built
from its URDF. :func:`evaluate_many` evaluates designs of one body together, searching
their axis-locked flexibility in one batch.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Collection, Iterable, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import TypeVar, cast, get_args

import numpy as np

from hexaleg._typing import FlexibilityMode, StanceSet
from hexaleg.cause import Cause
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.metrics import (
    METRICS,
    WALKING,
    Analysis,
    Causes,
    Metrics,
    MetricSpec,
    Reasons,
)
from hexaleg.evaluation.sizing import size_tubes
from hexaleg.evaluation.walks import Walks
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.gait.analysis import GaitAnalysis
from hexaleg.gait.spec import Gait
from hexaleg.ratings import NEEDS_RATING
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.model_cache import model_of
from hexaleg.stance.axis_locked import axis_locked_flexibility, axis_locked_flexibility_many
from hexaleg.stance.extremes import FlexibilityResult, FlexibilityWarning
from hexaleg.stance.flexibility import flexibility
from hexaleg.stance.free_coupled import free_flexibility
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.statics.capacity import payload_capacity
from hexaleg.statics.forces import Payload, Statics
from hexaleg.statics.ground import LEVEL, Ground
from hexaleg.statics.loads import LoadsAnalysis, loads_at_extremes
from hexaleg.statics.ratings import check_safety_factor
from hexaleg.statics.standing_limits import Standing
from hexaleg.structure.check import StructureCheck
from hexaleg.structure.sizing import SizedStructure
from hexaleg.structure.standing import check_standing, standing_cases
from hexaleg.swing.manipulability import average_manipulability, rectangular_and_improved
from hexaleg.swing.workspace import improved_area_closed_form

__all__ = ["Conditions", "Evaluation", "evaluate", "evaluate_many"]

Table = TypeVar("Table", Metrics, Causes, Reasons)
"""A per-metric record of an evaluation: its values, their causes, why some have none."""


@dataclass(frozen=True)
class Conditions:
    """What a design is measured under.

    Attributes:
        payload: The payload carried, standing and walking.
        slope: The slope the payload capacity holds on, in every heading [rad]
            (``None``: level ground).
        gait: The gait walked for the walking metrics.
        stance: The stance legs of the flexibility.
        mode: Axis-locked or free-coupled flexibility.
        collisions: The robot's own parts touching also stop the body (FB).
        keep: Keep the flexibility, the statics at its extremes and the gait periods in
            the evaluation (a study's row shows them).
        grounds: The grounds the gait is walked on (:func:`~.walks.walking_grounds`: a
            walking slope uphill, downhill and across); each walking metric is its worst
            over them.
        safety_factor: The motors' safety factor F ≥ 1 [-]: every peak joint torque and
            speed held within its rating / F, standing and walking (the tubes' own is
            their ``[structure]``'s).

    """

    payload: Payload = field(default_factory=Payload)
    slope: float | None = None
    gait: Gait = field(default_factory=Gait)
    stance: StanceSet = "all"
    mode: FlexibilityMode = "axis"
    collisions: bool = False
    keep: bool = False
    grounds: tuple[Ground, ...] = (LEVEL,)
    safety_factor: float = 1.0

    def __post_init__(self) -> None:
        grounds = tuple(self.grounds) if isinstance(self.grounds, Sequence) else ()
        if not grounds or not all(isinstance(g, Ground) for g in grounds):
            raise ParameterError("grounds", self.grounds, "one Ground or more")
        object.__setattr__(self, "grounds", grounds)
        object.__setattr__(self, "safety_factor", check_safety_factor(self.safety_factor))


@dataclass(frozen=True)
class Evaluation:
    """One design's metrics, or why it could not be measured.

    Attributes:
        metrics: Each metric asked for [its unit]; ``None`` where not asked for, NaN where
            :attr:`unmeasured` says why it has no value.
        causes: What limits a metric, where something does (payload, slope, speed).
        error: Why the design cannot exist or stand; empty if it was measured.
        unmeasured: Why a metric asked for has no value (a gait it cannot walk; a rating
            the design does not give: :data:`~hexaleg.ratings.NEEDS_RATING`).
        flexibility: Its flexibility, when kept (:attr:`Conditions.keep`).
        loads: The statics at the nominal stance and at the extremes, when kept.
        gait: The gait period walked on the first ground, when kept.
        gaits: The gait period walked on each ground, when kept.
        walks: Whether the design walks the gait unloaded within its ratings (``None``
            unless the walking payload capacity was measured).
        sized: The legs' tubes sized for the conditions' payload and slope, when the
            design's ``[structure]`` says ``size = true`` (every metric is the sized
            design's: :attr:`design`).
        structure: The legs' tubes checked standing (the sizing's check, or the given
            tubes'), when sized or when the structure was measured.

    """

    metrics: Metrics = field(default_factory=Metrics)
    causes: Causes = field(default_factory=Causes)
    error: str = ""
    unmeasured: Reasons = field(default_factory=Reasons)
    flexibility: FlexibilityResult | None = None
    loads: LoadsAnalysis | None = None
    gait: GaitAnalysis | None = None
    walks: bool | None = None
    sized: SizedStructure | None = None
    gaits: tuple[GaitAnalysis, ...] = ()
    structure: StructureCheck | None = None

    def design(self, given: HexapodDesign) -> HexapodDesign:
        """The design measured: ``given`` (the one evaluated), with its tubes if sized."""
        return given if self.sized is None else self.sized.design


def evaluate(
    design: HexapodDesign,
    metrics: Collection[MetricSpec],
    conditions: Conditions | None = None,
    *,
    model: HexapodModel | None = None,
    template: StanceGeometry | None = None,
    flexibility: FlexibilityResult | None = None,
) -> Evaluation:
    """Measure ``metrics`` of ``design`` under ``conditions``.

    Args:
        design: The design.
        metrics: Declarations of the metrics to measure (``METRICS.fb``, ...).
        conditions: What it is measured under (level ground, no payload, the default gait).
        model: The design's Pinocchio model (one derived from a model of the same body by
            :meth:`~hexaleg.robot.model.HexapodModel.with_design` is exact); when an
            analysis needs it and it is omitted, :func:`~hexaleg.robot.model_cache.model_of`
            derives it from a model of its body built before, or builds it from its URDF.
        template: A stance geometry of the same body and mounts (fast path); the
            design's own is read from the model if omitted.
        flexibility: The design's flexibility, if already computed (a batch's).

    A design whose ``[structure]`` says ``size = true`` has its tubes sized first, for the
    conditions' payload and slope (:func:`~hexaleg.evaluation.sizing.size_tubes`): their
    masses enter every metric. A design whose analyses fail (its nominal stance cannot
    stand) is returned with ``error`` set and no values.

    """
    measuring = _Measuring(design, conditions or Conditions(), model, template, flexibility)
    try:
        return measuring.evaluation(metrics)
    except HexalegError as err:
        return Evaluation(error=str(err))


def evaluate_many(
    designs: Sequence[HexapodDesign],
    metrics: Collection[MetricSpec],
    conditions: Conditions,
    models: Sequence[HexapodModel],
    template: StanceGeometry | None,
) -> list[Evaluation]:
    """:func:`evaluate` of designs of one robot, their flexibility searched together.

    Args:
        designs: Designs of one body, differing only in their legs, ratings and posture.
        metrics: What to measure.
        conditions: What they are measured under.
        models: Each design's model (derived from its body's, or its own).
        template: The body's stance geometry (``conditions.stance``'s legs), from which each
            design's derives in closed form; ``None`` where the legs are their own
            (:meth:`~hexaleg.stance.geometry.StanceGeometry.template_of`): each design is
            then read and searched on its own model.

    """
    found: Sequence[FlexibilityResult | None] = [None] * len(designs)
    batched = template is not None and METRICS.fb in metrics and conditions.mode == "axis"
    if batched and designs:
        assert template is not None
        try:
            found = axis_locked_flexibility_many(
                designs, template, models, collisions=conditions.collisions
            )
        except HexalegError:
            pass  # one design spoils the batch: each is searched on its own below
    return [
        evaluate(design, metrics, conditions, model=model, template=template, flexibility=result)
        for design, model, result in zip(designs, models, found, strict=True)
    ]


ANALYSES: tuple[Analysis, ...] = cast(tuple[Analysis, ...], get_args(Analysis))
"""The analyses, in the order an evaluation runs them (as :data:`Analysis` lists them)."""


class _Measuring:
    """One design's evaluation under way: each analysis and model made once, on demand.

    Each ``_measure_<analysis>`` step returns the metrics it measured; the evaluation keeps
    those asked for.
    """

    def __init__(
        self,
        design: HexapodDesign,
        conditions: Conditions,
        model: HexapodModel | None,
        template: StanceGeometry | None,
        flexibility: FlexibilityResult | None,
    ) -> None:
        self.design, self.conditions = design, conditions
        self._model, self._template, self._flexibility = model, template, flexibility
        self.asked: frozenset[str] = frozenset()
        self.wanted: set[Analysis] = set()
        self.causes = Causes()
        self.unmeasured = Reasons()
        self.loads: LoadsAnalysis | None = None
        self.walks: bool | None = None
        self.sized: SizedStructure | None = None
        self.structure: StructureCheck | None = None

    def evaluation(self, metrics: Collection[MetricSpec]) -> Evaluation:
        self.asked = frozenset(spec.name for spec in metrics)
        self._size()
        wanted = self.wanted = {spec.analysis for spec in metrics}
        if self.conditions.keep and wanted & WALKING:
            wanted.add("period")  # the period walked is kept
        measured: dict[str, float | None] = {}
        for analysis in ANALYSES:
            if analysis in wanted:
                found: Metrics = getattr(self, f"_measure_{analysis}")()
                measured |= found.to_dict()
        kept = self.conditions.keep
        periods = self.walking.periods if kept and "period" in wanted else ()
        return Evaluation(
            metrics=self._asked_only(Metrics(**measured)),
            causes=self._asked_only(self.causes),
            unmeasured=self._asked_only(self.unmeasured),
            flexibility=self.flexibility if kept and "flexibility" in wanted else None,
            loads=self.loads if kept else None,
            gait=periods[0] if periods else None,
            walks=self.walks,
            sized=self.sized,
            structure=self.structure,
            gaits=periods,
        )

    def _asked(self, spec: MetricSpec) -> bool:
        return spec.name in self.asked

    def _asked_only(self, table: Table) -> Table:
        """``table``'s fields of the metrics asked for (the others ``None``)."""
        return type(table)(**{k: v for k, v in table.to_dict().items() if k in self.asked})

    # -- what the analyses share -----------------------------------------------------------

    def _size(self) -> None:
        """Size the legs' tubes where the design's ``[structure]`` asks: every metric is theirs.

        The axis-locked extremes of every leg are the evaluation's own when it searches
        those (they depend on the geometry only, which the tubes leave).
        """
        structure = self.design.structure
        if structure is None or not structure.size:
            return
        conditions = self.conditions
        same = conditions.mode == "axis" and conditions.stance == "all"
        extremes = self.flexibility.extremes if same else None
        sized = size_tubes(
            self.design, conditions.payload, conditions.slope, model=self.model, extremes=extremes
        )
        if sized is None:
            return
        self.sized, self.structure, self.design = sized, sized.check, sized.design
        self._model = self.model.with_design(sized.design)

    @property
    def model(self) -> HexapodModel:
        if self._model is None:
            self._model = model_of(self.design)
        return self._model

    @cached_property
    def geometry(self) -> StanceGeometry:
        """The design's stance geometry: from the template in closed form, else its model."""
        if self._template is not None:
            return self._template.with_design(self.design)
        return StanceGeometry.from_model(self.model, self.conditions.stance)

    @property
    def flexibility(self) -> FlexibilityResult:
        if self._flexibility is None:
            self._flexibility = self._search_flexibility()
        return self._flexibility

    def _search_flexibility(self) -> FlexibilityResult:
        conditions, design = self.conditions, self.design
        geometry = self._template  # the body's, if given; else the searches read the model
        if conditions.mode == "axis":
            return axis_locked_flexibility(
                design,
                conditions.stance,
                self._model,
                geometry=geometry,
                collisions=conditions.collisions,
            )
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", FlexibilityWarning)  # the result's "converged"
            return free_flexibility(
                design,
                conditions.stance,
                self.model,
                geometry=geometry,
                collisions=conditions.collisions,
            )

    @cached_property
    def walking(self) -> Walks:
        """The conditions' gait walked with their payload on each of their grounds."""
        conditions = self.conditions
        return Walks(
            self.model, conditions.gait, conditions.payload, conditions.grounds,
            conditions.safety_factor,
        )  # fmt: skip

    def _walked(self, analysis: Analysis) -> Metrics:
        """The metrics ``analysis`` measures walking, each its worst over the grounds."""
        found = self.walking.measure(analysis)
        causes, reasons = found.causes.to_dict(), found.unmeasured.to_dict()
        if causes:
            self.causes = replace(self.causes, **causes)
        if reasons:
            self.unmeasured = replace(self.unmeasured, **reasons)
        return found.metrics

    # -- the analyses ------------------------------------------------------------------

    def _measure_geometry(self) -> Metrics:
        design, model = self.design, self._model  # without a model, the design's own
        return Metrics(
            leg_length=design.leg_length,
            coxa_length=design.l1,
            robot_mass=design.total_mass if model is None else model.total_mass,
            nominal_height=design.nominal_height if model is None else model.nominal_height,
        )

    def _measure_workspace(self) -> Metrics:
        return Metrics(improved_area=improved_area_closed_form(self.design.l2, self.design.l3))

    def _measure_manipulability(self) -> Metrics:
        _, improved = rectangular_and_improved(self.design.manipulability_limits)
        return Metrics(
            average_manipulability=float(average_manipulability(self.design.lengths, improved))
        )

    def _measure_flexibility(self) -> Metrics:
        return Metrics(fb=self.flexibility.fb)

    def _measure_clearance(self) -> Metrics:
        geometry = self.geometry
        lowest = geometry.lowest_body_height(np.eye(3), [0.0, 0.0, geometry.nominal_height])
        return Metrics(ground_clearance=float(lowest))

    def _measure_standing(self) -> Metrics:
        conditions, model = self.conditions, self.model
        factor = conditions.safety_factor
        if conditions.keep:
            self.loads = loads_at_extremes(
                model, self.flexibility, conditions.payload, safety_factor=factor
            )
        statics = Statics(model, model.leg_names, conditions.payload, safety_factor=factor)
        found = Metrics()
        if self._asked(METRICS.stability_margin):  # the kept statics' stance legs, if kept
            nominal = (
                self.loads.nominal
                if self.loads is not None
                else statics.state(model.nominal_configuration())
            )
            found = replace(found, stability_margin=nominal.stability_margin)
        if model.design.rated_torques is None:  # within ratings the design does not give
            return self._without((METRICS.payload_capacity, METRICS.max_slope), NEEDS_RATING, found)
        if conditions.slope is None:  # level ground: the statics' own payload capacity
            capacity = (
                self.loads.capacity
                if self.loads is not None and self.loads.capacity is not None
                else payload_capacity(statics, model.nominal_configuration())
            )
            found = replace(found, payload_capacity=capacity.mass)
            self.causes = replace(self.causes, payload_capacity=capacity.limited_by)
        if conditions.slope is None and not self._asked(METRICS.max_slope):
            return found
        standing = Standing.of(statics)
        if conditions.slope is not None:
            mass, cause = standing.max_payload(conditions.slope)
            found = replace(found, payload_capacity=mass)
            self.causes = replace(self.causes, payload_capacity=cause)
        slope, cause = standing.max_slope(conditions.payload.mass)
        self.causes = replace(self.causes, max_slope=cause)
        return replace(found, max_slope=slope)

    def _measure_walking(self) -> Metrics:
        found = self._walked("walking")
        self.walks = self.walking.walks
        return found

    def _measure_speed(self) -> Metrics:
        return self._walked("speed")

    def _measure_period(self) -> Metrics:
        return self._walked("period")

    def _measure_motors(self) -> Metrics:
        return self._walked("motors")

    def _measure_structure(self) -> Metrics:
        """The legs' tubes standing (the sizing's check, or the given tubes' own)."""
        if self.structure is None:
            structure = self.design.structure
            if structure is None or None in structure.tubes:
                why = "the design's [structure] neither sizes its tubes nor gives every one"
                return self._without((METRICS.structure_load,), why)
            self.structure = self._standing_structure()
        checks = [self.structure]
        if self.wanted & WALKING:  # the robot must walk: its tubes, walking the periods too
            checks += [p.structure for p in self.walking.periods if p.structure is not None]
        load, cause = max((structure_load(check) for check in checks), key=lambda lc: lc[0])
        self.causes = replace(self.causes, structure_load=cause)
        return Metrics(structure_load=load)

    def _standing_structure(self) -> StructureCheck:
        """The given tubes in every standing case of the conditions (every leg standing)."""
        conditions, model = self.conditions, self.model
        same = conditions.mode == "axis" and conditions.stance == "all"
        found = self.flexibility if same else flexibility(self.design, "axis", "all", self._model)
        cases = standing_cases(
            model, model.leg_names, found.extremes, conditions.payload, conditions.slope or 0.0
        )
        return check_standing(model, cases)

    def _without(
        self, specs: Iterable[MetricSpec], why: str, found: Metrics | None = None
    ) -> Metrics:
        """``found`` (if any) with ``specs`` without a value (NaN), and ``why`` they have none."""
        names = [spec.name for spec in specs]
        self.unmeasured = replace(self.unmeasured, **dict.fromkeys(names, why))
        return replace(Metrics() if found is None else found, **dict.fromkeys(names, math.nan))


def structure_load(check: StructureCheck) -> tuple[float, Cause]:
    """A check's structure load [-] and what sets it (the larger of the two).

    The worst stress ratio (von Mises over strength / safety factor), and standing the
    largest foot deflection over its limit.
    """
    worst = check.worst
    strength = (check.worst_ratio, Cause("strength", leg=worst["leg"], segment=worst["segment"]))
    at = check.deflection_at
    if at is None:
        return strength
    bent = (check.deflection / check.limit, Cause("deflection", leg=at["leg"]))
    return max(strength, bent, key=lambda found: found[0])
