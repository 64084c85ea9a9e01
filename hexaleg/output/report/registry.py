"""The report's parts, in the order the report shows them (one line a part)."""

from __future__ import annotations

from typing import Any

from hexaleg.output.report import (
    decision,
    design,
    flexibility,
    manipulability,
    motors,
    pareto,
    recommendation,
    robot,
    robot_study,
    sensitivity,
    simulation,
    statics,
    study,
    viewer,
    walking,
    workspace,
)
from hexaleg.output.report.options import ReportOptions
from hexaleg.output.report.part import Part

PARTS: tuple[Part[Any], ...] = (
    decision.PART,
    design.PART,
    workspace.PART,
    manipulability.PART,
    flexibility.PART,
    study.PART,
    sensitivity.PART,
    statics.PART,
    walking.PART,
    motors.PART,
    viewer.PART,
    recommendation.PART,
    pareto.PART,
)
"""Every part of the report, in reading order; each is computed after the parts it needs."""


ROBOT_PARTS: tuple[Part[Any], ...] = (
    robot_study.DECISION,
    robot.DESIGN,
    robot.ROBOT,
    robot.SWING,
    robot.STANCE,
    robot_study.STUDY,
    robot.VIEWER,
)
"""The parts of an imported robot's report (:mod:`.robot`, :mod:`.robot_study`), in order."""


def parts_for(options: ReportOptions) -> tuple[Part[Any], ...]:
    """:data:`PARTS`, with the simulated walk after the walking when ``options.simulate``.

    An imported robot's report has its own parts (:data:`~.robot.ROBOT_PARTS`).
    """
    if options.robot is not None:
        return ROBOT_PARTS
    if not options.simulate:
        return PARTS
    after = PARTS.index(walking.PART) + 1
    return (*PARTS[:after], simulation.PART, *PARTS[after:])
