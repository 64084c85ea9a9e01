"""Report part: your design measured once, for every section that shows a number of it.

One :func:`~hexaleg.evaluation.evaluate.evaluate` of the robot reported on measures every
metric it can have (:func:`report_metrics`) under the conditions of the report's study
(:func:`report_study`: level ground, no payload, the report's gait, all six feet down,
axis-locked), keeping its analyses: the flexibility, the statics at its extremes and the
gait period through its motors. The flexibility, statics, motors, walking, decision,
recommendation and study sections all read this one record, so no quantity of your
design can print two values. It shows no section of its own.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from hexaleg.design import HexapodDesign, l3_ratio_grid
from hexaleg.evaluation.evaluate import Evaluation, evaluate
from hexaleg.evaluation.metrics import METRICS, Metrics, MetricSpec
from hexaleg.exceptions import HexalegError
from hexaleg.output.report.part import Part, ReportData
from hexaleg.study.rows import Key, StudyRow, study_row
from hexaleg.study.sweep import StudySpec


def report_metrics(design: HexapodDesign) -> tuple[MetricSpec, ...]:
    """Every metric ``design`` can have.

    Those through its motors only with actuators, the tubes' load only with a ``[structure]``.
    """
    tubes = design.structure is not None
    return tuple(
        spec
        for spec in METRICS
        if not spec.lacks(design) and (tubes or spec is not METRICS.structure_load)
    )


def report_study(data: ReportData) -> StudySpec:
    """The report's study: the swept coxa ratios × the report's tibia ratios, on its robot.

    Its conditions are those every design of the report is measured under: walking the
    report's gait up, down and across the requirements' walking slope (level ground
    without one), within the ratings over the requirements' motor safety factor.
    """
    options = data.options
    required = options.requirements
    return StudySpec(
        options.swept_l1_ratios,
        tuple(l3_ratio_grid(options.l3_points)),
        data.design.leg_length,
        base=data.design,
        collisions=options.collisions,
        walked=options.gait,
        robot=data.robot,
        walking_slope=0.0 if required is None else required.walking_slope,
        safety_factor=1.0 if required is None else required.motor_safety_factor,
    )


def standing_text(spec: StudySpec) -> str:
    """The posture and ground every leg of the study stands and walks at, in words.

    ``"standing at your posture θ = (0.000, 0.000, -1.571) rad on level ground"``.
    """
    angles = ", ".join(f"{a:.3f}" for a in spec.robot.design.nominal_angles)
    slope = spec.walking_slope
    ground = (
        "on level ground"
        if not slope
        else f"on level ground, walking up, down and across a {math.degrees(slope):.3g}° slope"
    )
    return f"standing at your posture θ = ({angles}) rad {ground}"


def ratio_key(design: HexapodDesign) -> Key:
    """(coxa ratio, tibia ratio) of ``design`` [-]."""
    return (design.l1 / design.leg_length, design.l3 / design.leg_length)


@dataclass(frozen=True)
class YoursRecord:
    """Your design, measured once.

    Attributes:
        spec: The report's study: what every design is measured under.
        evaluation: Every metric of :func:`report_metrics`, its flexibility, its statics at
            the extremes and its gait period kept.

    """

    spec: StudySpec
    evaluation: Evaluation

    @property
    def row(self) -> StudyRow:
        """Your design as a row of the study: the study's metrics and columns of it."""
        design = self.spec.robot.design
        row = study_row(ratio_key(design), design, self.evaluation)
        kept = {spec.name: row.metrics[spec] for spec in self.spec.metrics}
        return replace(row, metrics=Metrics(**kept))


def compute(data: ReportData) -> YoursRecord:
    """Your design's one evaluation.

    Raises:
        HexalegError: It cannot be measured (its nominal stance cannot stand).

    """
    spec = report_study(data)
    found = evaluate(data.design, report_metrics(data.design), spec.conditions, model=data.model)
    if found.error:
        raise HexalegError(f"{data.robot.name}: {found.error}")
    return YoursRecord(spec, found)


PART = Part(YoursRecord, compute, None, step="your design", level=0)
"""Shows no section: every section that shows your design reads its record."""
