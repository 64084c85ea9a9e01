"""Ranking legs when no requirement is given: what the robot must do first, then one score.

The rule (:data:`RANKING_RULE`) has two steps:

1. **A constraint** (:class:`WalkingConstraint`): what the robot must do comes first. A leg
   is ranked only if it walks the report's gait (the design file's ``[gait]``, else the
   default tripod) carrying the payload (none unless one is required) on the ground it must
   walk (level, or the required walking slope up, down and across) within every
   rating, its ZMP inside the standing feet (:mod:`hexaleg.gait.capacity`: its walking
   payload capacity is at least the payload, and it walks the gait unloaded). A leg that
   does not is not scored, however flexible it is.
2. **An objective**: among the legs that do, a leg's score is the geometric mean of the
   paper's metrics — improved workspace area [m²] (eq 16), average manipulability w_A
   [m³] (eq 27) and axis-locked FB [-] (eq 29) — each divided by the user's design's
   own value. A score of 1.10 is 10 % better than the user's design on that (logarithmic)
   average, and every metric counts alike whatever its unit or its spread over a grid.

A metric whose baseline (the user's design's value) is not positive never enters a ratio:
it is left out of every score, which then averages the others (so no score is 0, inf or
NaN because of it), and the rule says so. A leg with a metric that is not positive has no
score. A score depends on that leg and the user's design alone, so adding or removing other
legs never changes it, and the order of the legs is the same whatever the reference (the
reference only scales every score by one factor).

The recommendation (:mod:`hexaleg.study.recommendation`), the Pareto front's order
(:mod:`hexaleg.study.pareto`) and the report's Decision section all rank by this rule.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from hexaleg._typing import ArrayF
from hexaleg.evaluation.evaluate import Evaluation
from hexaleg.evaluation.metrics import METRICS, Metrics, MetricSpec
from hexaleg.exceptions import ParameterError

RANKED_METRICS: tuple[MetricSpec, ...] = (
    METRICS.improved_area,
    METRICS.average_manipulability,
    METRICS.fb,
)
"""The metrics a score combines [m², m³, -], every one larger-is-better: the paper's."""

WALKING = METRICS.walking_payload_capacity
"""The metric the constraint reads: the payload carried walking the gait within every rating."""

RANKING_RULE = (
    "what the robot must do comes first: a leg is ranked only if it walks the gait (the "
    "design file's [gait], else the default tripod) carrying the payload on the ground it "
    "must walk (level, or the required walking slope up, down and across) within every "
    "rating, its ZMP inside the standing feet; among those, a leg's score is the geometric "
    "mean of its improved workspace area (eq 16), average manipulability w_A (eq 27) and "
    "axis-locked body flexibility FB (eq 29), each divided by your design's own value: your "
    "design scores 1, and 1.10 is 10 % better on that average, every metric counting alike "
    "whatever its unit. A metric your design has no positive value of is left out of every "
    "score rather than divided by. A score depends on that leg and yours alone, so adding "
    "or removing other legs never changes it"
)
"""The rule in one sentence, for reports."""


@dataclass(frozen=True)
class WalkingConstraint:
    """What every ranked leg must do first: walk the gait carrying ``payload``.

    Within every rating and with the ZMP inside the standing feet (the walking payload
    capacity's own conditions, :mod:`hexaleg.gait.capacity`), under the conditions the
    legs are measured in (the gait, the ground).

    Attributes:
        payload: The payload carried [kg] (0: walking unloaded).
        walking_slope: The slope it is walked up, down and across [rad] (0: level ground);
            the legs are measured on it (the study's conditions), this names it.

    """

    payload: float = 0.0
    walking_slope: float = 0.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.payload) and self.payload >= 0):
            raise ParameterError("payload", self.payload, "≥ 0 kg")

    def shortfall(self, capacity: float, walks: bool | None) -> float:
        """How far a leg is from meeting it [-]: 0 met, (0, 1] short of the payload, 1 cannot walk.

        Args:
            capacity: Its walking payload capacity [kg] (NaN: not measured).
            walks: Whether it walks the gait unloaded within every rating.

        """
        if not walks or not math.isfinite(capacity):
            return 1.0
        if capacity >= self.payload:
            return 0.0
        return (self.payload - capacity) / self.payload

    def met(self, capacity: float, walks: bool | None) -> bool:
        """Whether a leg of walking payload ``capacity`` [kg] that ``walks`` meets it."""
        return self.shortfall(capacity, walks) == 0.0

    def meets(self, evaluation: Evaluation) -> bool:
        """Whether a measured leg meets it (one that could not be measured does not)."""
        if evaluation.error:
            return False
        return self.met(evaluation.metrics.value(WALKING), evaluation.walks)

    def met_rows(self, table: pd.DataFrame) -> pd.Series:
        """Which rows of a study table meet it (columns ``walks`` and the walking capacity)."""
        if WALKING.name not in table or "walks" not in table:
            return pd.Series(False, index=table.index)
        walks = table["walks"].fillna(False).astype(bool)
        return walks & (table[WALKING.name].astype(float) >= self.payload)

    def describe(self, plural: bool = False) -> str:
        """The constraint in words: ``"walks the gait unloaded within every rating, …"``.

        ``plural``: for several legs (``"walk the gait …"``).
        """
        carrying = "unloaded" if self.payload == 0 else f"carrying {self.payload:g} kg"
        verb = "walk" if plural else "walks"
        ground = (
            "on level ground"
            if self.walking_slope == 0
            else f"up, down and across a {math.degrees(self.walking_slope):.3g}° slope"
        )
        return (
            f"{verb} the gait {carrying} {ground} within every rating, its ZMP inside the "
            "standing feet"
        )


def scored_metrics(reference: Metrics) -> tuple[MetricSpec, ...]:
    """The ranked metrics that enter a score: those the reference has a positive value of."""
    return tuple(spec for spec in RANKED_METRICS if _positive(reference.value(spec)))


def left_out(reference: Metrics) -> tuple[MetricSpec, ...]:
    """The ranked metrics left out of every score: the reference has no positive value."""
    return tuple(spec for spec in RANKED_METRICS if not _positive(reference.value(spec)))


def _positive(value: float) -> bool:
    return math.isfinite(value) and value > 0


def ranked_values(metrics: Metrics) -> ArrayF:
    """One design's :data:`RANKED_METRICS` (M,), in that order (NaN where one is missing)."""
    return np.array([metrics.value(spec) for spec in RANKED_METRICS])


def relative_values(values: ArrayF, reference: Metrics) -> ArrayF:
    """Each metric of ``values`` (..., M) over the reference's; NaN where that is not positive."""
    scale = ranked_values(reference)
    usable = np.isfinite(scale) & (scale > 0)
    relative: ArrayF = np.asarray(values, dtype=float) / np.where(usable, scale, np.nan)
    return relative


def scores(values: ArrayF, reference: Metrics) -> ArrayF:
    """The score of each design by :data:`RANKING_RULE` (NaN: it has no score).

    Args:
        values: The :data:`RANKED_METRICS` of each design (..., M), last axis in that order.
        reference: The user's design's metrics; a metric it has no positive value of is
            left out of every score (:func:`left_out`).

    A design with a scored metric that is missing or not positive has no score; the
    constraint is the caller's (:class:`WalkingConstraint`).

    """
    relative = relative_values(values, reference)
    used = np.array([spec in scored_metrics(reference) for spec in RANKED_METRICS])
    if not used.any():
        return np.full(np.shape(relative)[:-1], np.nan)
    kept = relative[..., used]
    bad = ~np.isfinite(kept).all(axis=-1) | (kept <= 0).any(axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        found: ArrayF = np.exp(np.log(kept).mean(axis=-1))
    return np.where(bad, np.nan, found)


def score(metrics: Metrics, reference: Metrics) -> float:
    """One design's score by :data:`RANKING_RULE` (NaN if it has none)."""
    return float(scores(ranked_values(metrics), reference))


def ranking_scores(table: pd.DataFrame, reference: Metrics) -> pd.Series:
    """Each row's score by :data:`RANKING_RULE` (NaN where it has none).

    Args:
        table: One row per design, a column for each of :data:`RANKED_METRICS`.
        reference: The user's design's metrics.

    """
    values = table[ranked_columns()].to_numpy(dtype=float)
    return pd.Series(scores(values, reference), index=table.index, name="score")


def ranked_columns() -> list[str]:
    """The table columns of :data:`RANKED_METRICS`: their names."""
    return [spec.name for spec in RANKED_METRICS]


def rule_note(reference: Metrics) -> str:
    """What the rule leaves out for this reference, in a sentence (empty: nothing)."""
    missing = left_out(reference)
    if not missing:
        return ""
    names = " and ".join(spec.label for spec in missing)
    return (
        f"Your design has no positive {names}, so it is left out of every score (a ratio to "
        "zero would make every score 0 or infinite); the others are averaged."
    )
