"""The designs every study figure of the report marks: yours and the recommended one."""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg.limits import LEG_JOINTS
from hexaleg.output.figures.marks import Mark, your_and_recommended

if TYPE_CHECKING:
    from hexaleg.output.report.part import ReportData


def study_marks(data: ReportData) -> list[Mark]:
    """Your design and the recommended one (if any), each as the study measures its designs."""
    from hexaleg.output.report.recommendation import RecommendationRecord
    from hexaleg.output.report.study import StudyRecord

    yours = data[StudyRecord].yours.to_dict()
    recommended = data.records.get(RecommendationRecord)
    if recommended is None:  # a robot whose own legs the report recommends nothing for
        return [Mark("your design", yours)]
    return your_and_recommended(yours, recommended.recommended.to_dict())


def rated_torques(data: ReportData) -> dict[str, float]:
    """The design's rated torque per joint type [N·m]; none where it gives none."""
    given = data.design.rated_torques
    return {} if given is None else dict(zip(LEG_JOINTS, given, strict=True))
