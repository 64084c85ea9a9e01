"""Walking across a study: how much the grid's best leg saves against the paper's, walking.

The sequel to the paper (Liu, Yang, Wang, Feng, *Dynamic Modeling and Dimensional
Optimization of Legged Mechanisms for Construction Robots*) sizes the leg for walking and
reports cutting peak joint torque and energy by over 20 %. :func:`walking_comparison`
asks the same of a study's grid: among the designs that walk the study's gait
(:attr:`~hexaleg.study.sweep.StudySpec.walked`) unloaded within every rating (:func:`walks`,
as the ranking counts them), the one with the least peak joint torque
and the one with the least cost of transport, each against the paper's 0.2/0.4/0.4 leg
(on the study's body, at its total leg length). Pure data; the report presents it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import pandas as pd

from hexaleg.evaluation.metrics import METRICS, Metrics, MetricSpec
from hexaleg.exceptions import HexalegError
from hexaleg.study.rows import StudyRow, design_walking_row
from hexaleg.study.sweep import StudySpec

PAPER_RATIOS = (0.2, 0.4)
"""The paper's leg: coxa and tibia ratios l1/L, l3/L (0.2/0.4/0.4) [-]."""
TORQUE = METRICS.gait_peak_torque
"""What the least-torque design has least."""
ENERGY = METRICS.mechanical_cost_of_transport
"""What the least-energy design has least."""


@dataclass(frozen=True)
class WalkingComparison:
    """The grid's best walking legs against the paper's.

    Attributes:
        reference: The paper's leg's row (its walking columns).
        least_torque: The row of the walking design with the least peak joint torque.
        least_energy: The row of the walking design with the least mechanical cost of
            transport.
        walking: How many of the grid's designs walk the gait within every rating (of
            ``designs``).
        designs: How many designs the grid has.
        gait: The gait walked (JSON-ready).

    """

    reference: StudyRow
    least_torque: StudyRow
    least_energy: StudyRow
    walking: int
    designs: int
    gait: dict[str, Any]

    @property
    def torque_saving(self) -> float:
        """1 − (least peak torque)/(the paper's leg's) [-]; NaN if the paper's leg cannot walk."""
        return _saving(self.least_torque.metrics, self.reference.metrics, TORQUE)

    @property
    def energy_saving(self) -> float:
        """1 − (least cost of transport)/(the paper's leg's) [-]."""
        return _saving(self.least_energy.metrics, self.reference.metrics, ENERGY)

    @property
    def cross_savings(self) -> tuple[float, float]:
        """The energy the least-torque design saves, and the torque the least-energy one saves."""
        return (
            _saving(self.least_torque.metrics, self.reference.metrics, ENERGY),
            _saving(self.least_energy.metrics, self.reference.metrics, TORQUE),
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (savings as fractions, torques N·m, speeds m/s)."""
        return {
            "gait": self.gait,
            "walking_designs": self.walking,
            "designs": self.designs,
            "paper_leg": _kept(self.reference),
            "least_peak_torque": _kept(self.least_torque),
            "least_cost_of_transport": _kept(self.least_energy),
            "peak_torque_saving": self.torque_saving,
            "energy_saving": self.energy_saving,
        }


def _kept(row: StudyRow) -> dict[str, Any]:
    """A row's ratios, peak torque [N·m], cost of transport [-] and max speed [m/s]."""
    metrics = row.metrics
    return {"l1_ratio": row.l1_ratio, "l3_ratio": row.l3_ratio} | {
        spec.name: metrics[spec] for spec in (TORQUE, ENERGY, METRICS.max_speed)
    }


def _saving(metrics: Metrics, reference: Metrics, spec: MetricSpec) -> float:
    """1 − value / the reference's value of metric ``spec`` [-]; NaN without a positive one."""
    value, base = metrics.value(spec), reference.value(spec)
    return 1.0 - value / base if base > 0 and math.isfinite(base) else math.nan


def walks(table: pd.DataFrame) -> pd.Series:
    """Which designs of a study walk its gait: unloaded, within every rating.

    The legs the ranking, the Pareto front and their figures count as walking (``walks``),
    whose period can be walked at all (``gait_feasible``); a table from before the
    ``walks`` column counts the second alone.
    """
    feasible = table["gait_feasible"].fillna(False).astype(bool)
    return feasible & table["walks"].fillna(False).astype(bool) if "walks" in table else feasible


def walking_comparison(
    table: pd.DataFrame, spec: StudySpec, yours: StudyRow | None = None
) -> WalkingComparison:
    """Compare the study's best walking designs with the paper's leg on the same body.

    Args:
        table: The study's table, with its ``gait_*`` columns.
        spec: The study (its base design and total leg length).
        yours: The study's robot's own row, if measured: the paper's leg's when that is
            the robot's design (as a row of the table is, when it is the grid's).

    Raises:
        HexalegError: The table has no gait columns, or no design walks the gait.

    """
    if TORQUE.name not in table:
        raise HexalegError("the study has no walking columns (StudySpec.gait was off)")
    walking = table[walks(table)]
    if walking.empty:
        raise HexalegError(f"no design of the study walks {spec.walked.named}")
    return WalkingComparison(
        reference=paper_row(table, spec, yours),
        least_torque=_least(walking, TORQUE),
        least_energy=_least(walking, ENERGY),
        walking=len(walking),
        designs=len(table),
        gait=spec.walked.to_dict(),
    )


def paper_row(table: pd.DataFrame, spec: StudySpec, yours: StudyRow | None) -> StudyRow:
    """The paper's leg on the study's body as a row: measured once.

    The robot's own row when the paper's leg is its design, the table's row when it is a
    design of the grid; otherwise walked here.
    """
    paper = spec.robot.at_ratios(*PAPER_RATIOS, spec.total)
    if yours is not None and paper.design == spec.robot.design:
        return replace(yours, l1_ratio=PAPER_RATIOS[0], l3_ratio=PAPER_RATIOS[1])
    on_grid = np.isclose(table["l1_ratio"], PAPER_RATIOS[0]) & np.isclose(
        table["l3_ratio"], PAPER_RATIOS[1]
    )
    if on_grid.any():
        return StudyRow.from_dict(table[on_grid].iloc[0].to_dict())
    return design_walking_row(paper.design, paper.model, spec.walked, PAPER_RATIOS)


def _least(table: pd.DataFrame, spec: MetricSpec) -> StudyRow:
    """The row of ``table`` with the least value of metric ``spec``."""
    return StudyRow.from_dict(table.loc[table[spec.name].idxmin()].to_dict())


def walking_or_none(
    table: pd.DataFrame, spec: StudySpec, yours: StudyRow | None = None
) -> WalkingComparison | None:
    """:func:`walking_comparison`, or None when the study has no walking design to compare."""
    try:
        return walking_comparison(table, spec, yours)
    except HexalegError:
        return None
