"""One design of a study as a row: its ratios, lengths and every column its table shows.

A :class:`StudyRow` is made in the worker from the design's one
:class:`~hexaleg.evaluation.evaluate.Evaluation` (kept analyses included), so only numbers
travel back: the flexibility (FB, the six ranges, the twelve extremes and what stops
each), the statics at the nominal stance and at the extremes (peak torques, stability
margin, the steepest slope, the payload capacity and what limits it) and the study's gait
(peak torques, positive work, mechanical cost of transport, whether it walks, the max
speed and what limits it). Its :meth:`~StudyRow.to_dict` is the journal's line and the
table's row; :meth:`~StudyRow.from_dict` reads a journal's line back.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from hexaleg.design import HexapodDesign
from hexaleg.evaluation.evaluate import Conditions, Evaluation, evaluate
from hexaleg.evaluation.metrics import METRICS, Metrics, MetricSpec
from hexaleg.exceptions import HexalegError
from hexaleg.gait.analysis import STUDY_GAIT, GaitAnalysis
from hexaleg.gait.spec import Gait
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.extremes import FlexibilityResult

Key = tuple[float, float]
"""(coxa ratio, tibia ratio) of a design [-]."""

Cell = float | str | bool
"""A table cell: a number [its column's unit], a description, or a flag."""

WALKING_METRICS: tuple[MetricSpec, ...] = (
    METRICS.walking_payload_capacity,
    METRICS.max_speed,
    METRICS.gait_peak_torque,
    METRICS.mechanical_cost_of_transport,
    *(spec for spec in METRICS if spec.torque == "peak"),
    *(spec for spec in METRICS if spec.analysis == "motors"),
)
"""The metrics of a study's gait (:attr:`~hexaleg.study.sweep.StudySpec.walked`): the
walking payload capacity, the max speed, the period's peak torques (each joint type's
and the largest) and cost of transport, and those through the motors."""

KEY_COLUMNS = ("l1_ratio", "l3_ratio", "l1", "l2", "l3")
"""The columns every row has: its ratios [-] and lengths [m] (NaN where it failed)."""


@dataclass(frozen=True)
class StudyRow:
    """One design of a study.

    Attributes:
        l1_ratio: Coxa ratio l1/L [-].
        l3_ratio: Tibia ratio l3/L [-].
        lengths: (l1, l2, l3) [m]; NaN where the design cannot exist.
        metrics: Its metrics the study measured (each its own column).
        columns: Every other column, by name [m, rad, N·m, kg, m/s, -], or text: the
            flexibility's ranges and extremes, the statics at them, what limits a metric.
        error: Why the design could not be measured; empty if it was.

    """

    l1_ratio: float
    l3_ratio: float
    lengths: tuple[float, float, float] = (math.nan, math.nan, math.nan)
    metrics: Metrics = field(default_factory=Metrics)
    columns: Mapping[str, Cell] = field(default_factory=dict)
    error: str = ""

    @property
    def key(self) -> Key:
        """(coxa ratio, tibia ratio)."""
        return (self.l1_ratio, self.l3_ratio)

    def to_dict(self) -> dict[str, Any]:
        """The row as a journal line and a table row: key columns first, ``error`` last."""
        key = dict(zip(KEY_COLUMNS, (self.l1_ratio, self.l3_ratio, *self.lengths), strict=True))
        return key | self.metrics.to_dict() | dict(self.columns) | {"error": self.error}

    @classmethod
    def from_dict(cls, record: Mapping[str, Any]) -> StudyRow:
        """A row read back from its :meth:`to_dict` (a journal's line)."""
        lengths = tuple(float(record.get(name, math.nan)) for name in KEY_COLUMNS[2:])
        rest = {k: v for k, v in record.items() if k not in (*KEY_COLUMNS, "error")}
        return cls(
            float(record["l1_ratio"]),
            float(record["l3_ratio"]),
            (lengths[0], lengths[1], lengths[2]),
            Metrics.from_dict({k: v for k, v in rest.items() if k in METRICS}),
            {k: v for k, v in rest.items() if k not in METRICS},
            str(record.get("error", "")),
        )


def study_row(key: Key, design: HexapodDesign, evaluation: Evaluation) -> StudyRow:
    """The row of ``design`` at ratios ``key`` from its evaluation (kept analyses included)."""
    if evaluation.error:
        return StudyRow(*key, error=evaluation.error)
    flexibility = evaluation.flexibility
    assert flexibility is not None  # a study always measures FB, with Conditions.keep
    columns: dict[str, Cell] = {}
    if evaluation.loads is not None:
        columns |= evaluation.loads.study_columns()
    if evaluation.gait is not None:
        columns |= walking_columns(evaluation.gait, evaluation)
    columns |= flexibility_columns(flexibility)
    return StudyRow(*key, design.lengths, evaluation.metrics, columns)


def walking_columns(walked: GaitAnalysis, evaluation: Evaluation) -> dict[str, Cell]:
    """A row's walking columns beside its walking metrics: work [J], feasible, what limits.

    The positive work is NaN when the period cannot be walked (a constraint of its motion
    breaks); ``gait_feasible`` is false then, and also when its ZMP leaves the standing
    feet's polygon (the robot tips over, whatever its torques); what limits the max speed
    and the walking payload capacity; ``walks``: whether it walks the gait unloaded within
    its ratings.
    """
    ok = walked.walkable
    return {
        "gait_positive_work": walked.metrics.positive_work if ok else math.nan,
        "gait_feasible": ok and walked.tipping is None,
        "max_speed_limited_by": _why(evaluation, METRICS.max_speed),
        "walking_payload_limited_by": _why(evaluation, METRICS.walking_payload_capacity),
        "walks": bool(evaluation.walks),
    }


def _why(evaluation: Evaluation, spec: MetricSpec) -> str:
    """What limits metric ``spec``, or why it has no value ("needs a rating")."""
    cause = evaluation.causes[spec]
    return str(cause) if cause is not None else evaluation.unmeasured[spec] or ""


def walking_metrics(design: HexapodDesign) -> tuple[MetricSpec, ...]:
    """:data:`WALKING_METRICS` a design has: those through the motors only with actuators."""
    motors = design.actuators is not None
    return tuple(spec for spec in WALKING_METRICS if motors or spec.analysis != "motors")


def design_walking_row(
    design: HexapodDesign, model: HexapodModel, gait: Gait = STUDY_GAIT, key: Key | None = None
) -> StudyRow:
    """``design``'s walking metrics and columns as a study row has them: ``gait``, no payload.

    ``key``: the row's ratios (default: the design's own).

    Raises:
        HexalegError: the design cannot be measured (its nominal stance cannot stand).

    """
    found = evaluate(design, walking_metrics(design), Conditions(gait=gait, keep=True), model=model)
    if found.error or found.gait is None:
        raise HexalegError(found.error)
    key = key or (design.l1 / design.leg_length, design.l3 / design.leg_length)
    return StudyRow(*key, design.lengths, found.metrics, walking_columns(found.gait, found))


def flexibility_columns(result: FlexibilityResult) -> dict[str, Cell]:
    """The six ranges, the twelve extremes with what stops each, and whether it converged."""
    columns: dict[str, Cell] = {f"range_{axis}": value for axis, value in result.ranges.items()}
    for extreme in result.extremes:
        name = f"{extreme.axis}_{'max' if extreme.sign > 0 else 'min'}"
        columns[name] = extreme.value
        columns[f"{name}_limited_by"] = extreme.description
    return columns | {"converged": result.converged}
