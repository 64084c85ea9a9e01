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
from hexaleg.evaluation.evaluate import (
    ELECTRICAL_METRICS,
    PERIOD_METRICS,
    Conditions,
    Evaluation,
    evaluate,
)
from hexaleg.exceptions import HexalegError
from hexaleg.gait.analysis import STUDY_GAIT, GaitAnalysis
from hexaleg.gait.spec import Gait
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.extremes import FlexibilityResult

Key = tuple[float, float]
"""(coxa ratio, tibia ratio) of a design [-]."""

Cell = float | str | bool
"""A table cell: a number [its column's unit], a description, or a flag."""

WALKING_METRICS = (*PERIOD_METRICS, *ELECTRICAL_METRICS, "walking_payload_capacity")
"""The metrics of a study's gait (:attr:`~hexaleg.study.sweep.StudySpec.walked`)."""

KEY_COLUMNS = ("l1_ratio", "l3_ratio", "l1", "l2", "l3")
"""The columns every row has: its ratios [-] and lengths [m] (NaN where it failed)."""


@dataclass(frozen=True)
class StudyRow:
    """One design of a study.

    Attributes:
        l1_ratio: Coxa ratio l1/L [-].
        l3_ratio: Tibia ratio l3/L [-].
        lengths: (l1, l2, l3) [m]; NaN where the design cannot exist.
        columns: Every other column, by name [m, rad, N·m, kg, m/s, -], or text.
        error: Why the design could not be measured; empty if it was.

    """

    l1_ratio: float
    l3_ratio: float
    lengths: tuple[float, float, float] = (math.nan, math.nan, math.nan)
    columns: Mapping[str, Cell] = field(default_factory=dict)
    error: str = ""

    @property
    def key(self) -> Key:
        """(coxa ratio, tibia ratio)."""
        return (self.l1_ratio, self.l3_ratio)

    def __getitem__(self, column: str) -> Cell:
        """The value of ``column`` (a key column or another)."""
        return self.to_dict()[column]

    def to_dict(self) -> dict[str, Any]:
        """The row as a journal line and a table row: key columns first, ``error`` last."""
        key = dict(zip(KEY_COLUMNS, (self.l1_ratio, self.l3_ratio, *self.lengths), strict=True))
        return key | dict(self.columns) | {"error": self.error}

    @classmethod
    def from_dict(cls, record: Mapping[str, Any]) -> StudyRow:
        """A row read back from its :meth:`to_dict` (a journal's line)."""
        lengths = tuple(float(record.get(name, math.nan)) for name in KEY_COLUMNS[2:])
        columns = {k: v for k, v in record.items() if k not in (*KEY_COLUMNS, "error")}
        return cls(
            float(record["l1_ratio"]),
            float(record["l3_ratio"]),
            (lengths[0], lengths[1], lengths[2]),
            columns,
            str(record.get("error", "")),
        )


def study_row(key: Key, design: HexapodDesign, evaluation: Evaluation) -> StudyRow:
    """The row of ``design`` at ratios ``key`` from its evaluation (kept analyses included)."""
    if evaluation.error:
        return StudyRow(*key, error=evaluation.error)
    flexibility = evaluation.flexibility
    assert flexibility is not None  # a study always measures FB, with Conditions.keep
    columns: dict[str, Cell] = {"fb": flexibility.fb}
    if evaluation.loads is not None:
        columns |= evaluation.loads.study_columns()
    if evaluation.gait is not None:
        columns |= walking_columns(evaluation.gait, evaluation)
    return StudyRow(*key, design.lengths, columns | flexibility_columns(flexibility))


def walking_columns(walked: GaitAnalysis, evaluation: Evaluation) -> dict[str, Cell]:
    """A row's walking columns: peaks per joint and overall [N·m], work [J], CoT [-], speed.

    Peak torques, positive work and cost of transport are NaN when the period cannot be
    walked (a constraint of its motion breaks); ``gait_feasible`` is false then, and also
    when its ZMP leaves the standing feet's polygon (the robot tips over, whatever its
    torques); the max speed [m/s] is given either way, at the
    gait's stride (zero if it is infeasible), and the walking payload capacity [kg], each
    with what limits it; ``walks``: whether it walks the gait unloaded within its ratings.
    """
    metrics, ok = walked.metrics, walked.walkable
    columns: dict[str, Cell] = {
        f"gait_peak_{joint}_torque": value if ok else math.nan
        for joint, value in metrics.peak_torque.items()
    }
    return columns | {
        "gait_peak_torque": evaluation["gait_peak_torque"],
        "gait_positive_work": metrics.positive_work if ok else math.nan,
        "mechanical_cost_of_transport": evaluation["mechanical_cost_of_transport"],
        "gait_feasible": ok and walked.tipping is None,
        "max_speed": evaluation["max_speed"],
        "max_speed_limited_by": str(evaluation.causes["max_speed"]),
        "walking_payload_capacity": evaluation["walking_payload_capacity"],
        "walking_payload_limited_by": str(evaluation.causes["walking_payload_capacity"]),
        "walks": bool(evaluation.walks),
        **_electrical_columns(walked, evaluation),
    }


def _electrical_columns(walked: GaitAnalysis, evaluation: Evaluation) -> dict[str, Cell]:
    """The columns through the motors (energy per km, cost, continuous load, range), if any."""
    if walked.electrical is None:
        return {}
    return {name: evaluation[name] for name in ELECTRICAL_METRICS}


def design_walking_columns(
    design: HexapodDesign, model: HexapodModel, gait: Gait = STUDY_GAIT
) -> dict[str, Cell]:
    """``design``'s walking columns as a study row has them: walking ``gait``, no payload.

    Raises:
        HexalegError: the design cannot be measured (its nominal stance cannot stand).

    """
    found = evaluate(design, WALKING_METRICS, Conditions(gait=gait, keep=True), model=model)
    if found.error or found.gait is None:
        raise HexalegError(found.error)
    return walking_columns(found.gait, found)


def flexibility_columns(result: FlexibilityResult) -> dict[str, Cell]:
    """The six ranges, the twelve extremes with what stops each, and whether it converged."""
    columns: dict[str, Cell] = {f"range_{axis}": value for axis, value in result.ranges.items()}
    for extreme in result.extremes:
        name = f"{extreme.axis}_{'max' if extreme.sign > 0 else 'min'}"
        columns[name] = extreme.value
        columns[f"{name}_limited_by"] = extreme.description
    return columns | {"converged": result.converged}
