"""One evaluation of a design: every metric anyone asks for, each analysis run at most once.

:func:`evaluate` measures the metrics of :data:`~hexaleg.study.metrics.METRICS` that a
caller names — a study's row, a decision's candidate, the report's recommendation, the
user's own design — under one set of :class:`Conditions` (payload, slope, gait, stance
legs, collisions), into one frozen :class:`Evaluation`. Each metric's analysis runs once
however many of its metrics are asked for: the improved workspace area in closed form
(eq 16), the average manipulability w_A on the improved domain (eq 27), the axis-locked
or free-coupled flexibility FB (eq 29), the ground clearance of the nominal stance, the
statics' payload capacity and steepest slope (:mod:`hexaleg.study.standing_limits`), and
one gait period (:func:`~hexaleg.gait.analysis.analyze_gait`) for the max speed, peak
torque and cost of transport.

Given a model and a stance template of the same body (the fast path of sweeps and
searches), a design's own are derived from them in closed form; without, they are built
from its URDF. :func:`evaluate_many` evaluates designs of one body together, searching
their axis-locked flexibility in one batch.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Collection, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import pinocchio as pin

from hexaleg._typing import FlexibilityMode, StanceSet
from hexaleg.cause import Cause
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.gait.analysis import GaitAnalysis, analyze_walker
from hexaleg.gait.capacity import walker_capacity
from hexaleg.gait.spec import Gait
from hexaleg.gait.walk import Walker
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.model_cache import model_of
from hexaleg.stance.axis_locked import axis_locked_flexibility, axis_locked_flexibility_many
from hexaleg.stance.extremes import FlexibilityResult, FlexibilityWarning
from hexaleg.stance.free_coupled import free_flexibility
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.statics.capacity import payload_capacity
from hexaleg.statics.forces import Payload, Statics
from hexaleg.statics.loads import LoadsAnalysis, loads_at_extremes
from hexaleg.study.metrics import METRICS, Analysis, missing_tables
from hexaleg.study.standing_limits import Standing
from hexaleg.swing.manipulability import average_manipulability, rectangular_and_improved
from hexaleg.swing.workspace import improved_area_closed_form

__all__ = ["Conditions", "Evaluation", "evaluate", "evaluate_many"]


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
        keep: Keep the flexibility, the statics at its extremes and the gait period in
            the evaluation (a study's row shows them).

    """

    payload: Payload = field(default_factory=Payload)
    slope: float | None = None
    gait: Gait = field(default_factory=Gait)
    stance: StanceSet = "all"
    mode: FlexibilityMode = "axis"
    collisions: bool = False
    keep: bool = False


@dataclass(frozen=True)
class Evaluation:
    """One design's metrics, or why it could not be measured.

    Attributes:
        values: Each metric asked for [its unit] (NaN where :attr:`unmeasured` says why).
        causes: What limits a metric, where something does (payload, slope, speed).
        error: Why the design cannot exist or stand; empty if it was measured.
        unmeasured: Metrics without a value, and why (a gait it cannot walk).
        flexibility: Its flexibility, when kept (:attr:`Conditions.keep`).
        loads: The statics at the nominal stance and at the extremes, when kept.
        gait: The gait period walked, when kept.
        walks: Whether the design walks the gait unloaded within its ratings (``None``
            unless the walking payload capacity was measured).

    """

    values: Mapping[str, float] = field(default_factory=dict)
    causes: Mapping[str, Cause] = field(default_factory=dict)
    error: str = ""
    unmeasured: Mapping[str, str] = field(default_factory=dict)
    flexibility: FlexibilityResult | None = None
    loads: LoadsAnalysis | None = None
    gait: GaitAnalysis | None = None
    walks: bool | None = None

    def __getitem__(self, name: str) -> float:
        """The value of metric ``name``."""
        return self.values[name]


def evaluate(
    design: HexapodDesign,
    metrics: Collection[str],
    conditions: Conditions | None = None,
    *,
    model: HexapodModel | None = None,
    template: StanceGeometry | None = None,
    flexibility: FlexibilityResult | None = None,
) -> Evaluation:
    """Measure ``metrics`` of ``design`` under ``conditions``.

    Args:
        design: The design.
        metrics: Names of :data:`~hexaleg.study.metrics.METRICS` to measure.
        conditions: What it is measured under (level ground, no payload, the default gait).
        model: The design's Pinocchio model (one derived from a model of the same body by
            :meth:`~hexaleg.robot.model.HexapodModel.with_design` is exact); when an
            analysis needs it and it is omitted, :func:`~hexaleg.robot.model_cache.model_of`
            derives it from a model of its body built before, or builds it from its URDF.
        template: A stance geometry of the same body and mounts (fast path); the
            design's own is read from the model if omitted.
        flexibility: The design's flexibility, if already computed (a batch's).

    A design whose analyses fail (its nominal stance cannot stand) is returned with
    ``error`` set and no values.

    """
    unknown = [name for name in metrics if name not in METRICS]
    if unknown:
        raise HexalegError(f"unknown metric {unknown[0]!r}: known are {', '.join(METRICS)}")
    measuring = _Measuring(design, conditions or Conditions(), model, template, flexibility)
    try:
        return measuring.evaluation(metrics)
    except HexalegError as err:
        return Evaluation(error=str(err))


def evaluate_many(
    designs: Sequence[HexapodDesign],
    metrics: Collection[str],
    conditions: Conditions,
    base: HexapodModel,
    template: StanceGeometry,
) -> list[Evaluation]:
    """:func:`evaluate` of designs of one body (``base``'s), their flexibility searched together.

    Args:
        designs: Designs differing from ``base``'s only in their legs, ratings and posture.
        metrics: What to measure.
        conditions: What they are measured under.
        base: A model of that body: each design's is derived from it.
        template: The body's stance geometry (``conditions.stance``'s legs).

    """
    models = [base.with_design(design) for design in designs]
    found: Sequence[FlexibilityResult | None] = [None] * len(designs)
    if "fb" in metrics and conditions.mode == "axis" and designs:
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


PERIOD_METRICS = ("max_speed", "gait_peak_torque", "mechanical_cost_of_transport")
ELECTRICAL_METRICS = (
    "energy_per_km", "electrical_cost_of_transport", "continuous_load", "battery_range",
)  # fmt: skip
"""The metrics of the period through the design's motors (:mod:`hexaleg.electrical`)."""
PERIOD_DETAILS = (
    *ELECTRICAL_METRICS,
    "mechanical_energy_per_km",
    "min_zmp_margin",
    *(f"gait_{kind}_{joint}_torque" for joint in LEG_JOINTS for kind in ("peak", "rms")),
)
"""The metrics of one period of the gait (:func:`~hexaleg.gait.analysis.analyze_gait`)."""

ANALYSES: tuple[Analysis, ...] = (
    "geometry", "workspace", "manipulability", "flexibility", "clearance", "standing", "walking",
)  # fmt: skip
"""The analyses, in the order an evaluation runs them."""


class _Measuring:
    """One design's evaluation under way: each analysis and model made once, on demand."""

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
        self.metrics: set[str] = set()
        self.values: dict[str, float] = {}
        self.causes: dict[str, Cause] = {}
        self.unmeasured: dict[str, str] = {}
        self.loads: LoadsAnalysis | None = None
        self.walked: GaitAnalysis | None = None
        self.walks: bool | None = None

    def evaluation(self, metrics: Collection[str]) -> Evaluation:
        self.metrics = set(metrics)
        wanted = {METRICS[name].analysis for name in metrics}
        for analysis in ANALYSES:
            if analysis in wanted:
                getattr(self, f"_measure_{analysis}")()
        kept = self.conditions.keep
        return Evaluation(
            values={name: self.values[name] for name in METRICS if name in metrics},
            causes={name: cause for name, cause in self.causes.items() if name in metrics},
            unmeasured={k: v for k, v in self.unmeasured.items() if k in metrics},
            flexibility=self.flexibility if kept and "flexibility" in wanted else None,
            loads=self.loads if kept else None,
            gait=self.walked if kept else None,
            walks=self.walks,
        )

    # -- what the analyses share -----------------------------------------------------------

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
        # an imported robot's geometry is its model's own: the searches read it from there
        geometry = None if getattr(self._model, "general_legs", False) else self.geometry
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

    # -- the analyses ------------------------------------------------------------------

    def _measure_geometry(self) -> None:
        design, model = self.design, self._model
        mass, height = design.total_mass, design.nominal_height
        if model is not None and getattr(model, "general_legs", False):  # the file's, not ours
            mass, height = pin.computeTotalMass(model.model), self.geometry.nominal_height
        self.values |= {"leg_length": design.leg_length, "coxa_length": design.l1,
                        "robot_mass": mass, "nominal_height": height}  # fmt: skip

    def _measure_workspace(self) -> None:
        self.values["improved_area"] = improved_area_closed_form(self.design.l2, self.design.l3)

    def _measure_manipulability(self) -> None:
        _, improved = rectangular_and_improved(self.design.manipulability_limits)
        value = average_manipulability(self.design.lengths, improved)
        self.values["average_manipulability"] = float(value)

    def _measure_flexibility(self) -> None:
        self.values["fb"] = self.flexibility.fb

    def _measure_clearance(self) -> None:
        geometry = self.geometry
        lowest = geometry.lowest_body_height(np.eye(3), [0.0, 0.0, geometry.nominal_height])
        self.values["ground_clearance"] = float(lowest)

    def _measure_standing(self) -> None:
        conditions, model = self.conditions, self.model
        if conditions.keep:
            self.loads = loads_at_extremes(model, self.flexibility, conditions.payload)
        statics = Statics(model, model.leg_names, conditions.payload)
        if "stability_margin" in self.metrics:
            nominal = statics.state(model.nominal_configuration())
            self.values["stability_margin"] = nominal.stability_margin
        if conditions.slope is None:  # level ground: the statics' own payload capacity
            capacity = (
                self.loads.capacity
                if self.loads is not None
                else payload_capacity(statics, model.nominal_configuration())
            )
            self.values["payload_capacity"] = capacity.mass
            self.causes["payload_capacity"] = capacity.limited_by
        if conditions.slope is None and "max_slope" not in self.metrics:
            return
        standing = Standing.of(statics)
        if conditions.slope is not None:
            found = standing.max_payload(conditions.slope)
            self.values["payload_capacity"], self.causes["payload_capacity"] = found
        found = standing.max_slope(conditions.payload.mass)
        self.values["max_slope"], self.causes["max_slope"] = found

    def _measure_walking(self) -> None:
        conditions, empty = self.conditions, self.conditions.payload.with_mass(0.0)
        walker = Walker(self.model, conditions.gait, conditions.payload)  # one walk for both
        if "walking_payload_capacity" in self.metrics:
            same = walker.payload == empty  # the capacity walks the gait unloaded
            found = walker_capacity(walker if same else Walker(self.model, conditions.gait, empty))
            self.values["walking_payload_capacity"] = found.mass
            self.causes["walking_payload_capacity"] = found.limited_by
            self.walks = found.walks
        if not (self.metrics & {*PERIOD_METRICS, *PERIOD_DETAILS} or conditions.keep):
            return
        walked = analyze_walker(walker, limits=False, speed=True)
        self.walked = walked
        assert walked.max_speed is not None  # speed=True
        self.values["max_speed"] = walked.max_speed.value
        self.causes["max_speed"] = walked.max_speed.limited_by
        if walked.walkable:
            self.values |= _period_values(walked)
            self.unmeasured |= _unmeasured_electrical(walked)
            return
        why = f"cannot walk the gait: {walked.violations[0]}"
        for name in (*PERIOD_METRICS[1:], *PERIOD_DETAILS):
            self.values[name], self.unmeasured[name] = math.nan, why


def _electrical_values(walked: GaitAnalysis) -> dict[str, float]:
    """The period's metrics through the motors: energy, cost, continuous load, range."""
    electrical = walked.electrical
    if electrical is None:
        return dict.fromkeys(ELECTRICAL_METRICS, math.nan)
    ratios = electrical.ratings.ratios[1]  # RMS over continuous torque (L, 3)
    battery = electrical.battery
    return {
        "energy_per_km": electrical.energy_per_km,
        "electrical_cost_of_transport": electrical.cost_of_transport,
        "continuous_load": float(ratios.max()),
        "battery_range": math.nan if battery is None else battery.range,
    }


def _unmeasured_electrical(walked: GaitAnalysis) -> dict[str, str]:
    """Why a metric through the motors has no value: no actuators, or no battery."""
    missing = {name: missing_tables(name, walked.design) for name in ELECTRICAL_METRICS}
    return {name: f"the design has no [{found[0]}]" for name, found in missing.items() if found}


def _period_values(walked: GaitAnalysis) -> dict[str, float]:
    """The metrics of a feasible gait period: peaks, RMS, cost, energy per km, ZMP margin."""
    metrics = walked.metrics
    distance = walked.gait.speed * walked.gait.period  # per period [m]
    values = {
        "gait_peak_torque": max(metrics.peak_torque.values()),
        "mechanical_cost_of_transport": metrics.cost_of_transport,
        "mechanical_energy_per_km": metrics.positive_work / distance * 1000 / 3600,
        "min_zmp_margin": walked.min_zmp_margin,
        **_electrical_values(walked),
    }
    for joint in LEG_JOINTS:
        values[f"gait_peak_{joint}_torque"] = metrics.peak_torque[joint]
        values[f"gait_rms_{joint}_torque"] = metrics.rms_torque[joint]
    return values
