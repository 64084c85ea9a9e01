"""The report's parts, in the order the report shows them (one line a part).

One registry for every robot: each part says whether it holds for the robot reported on
(:attr:`~hexaleg.output.report.part.Part.holds`), so a robot file's report runs the parts
that hold for its own legs and names the others with why.
"""

from __future__ import annotations

from typing import Any

import hexaleg.output.report.decision as decision
import hexaleg.output.report.design as design
import hexaleg.output.report.flexibility as flexibility
import hexaleg.output.report.manipulability as manipulability
import hexaleg.output.report.motors as motors
import hexaleg.output.report.pareto as pareto
import hexaleg.output.report.recommendation as recommendation
import hexaleg.output.report.robot as robot
import hexaleg.output.report.sensitivity as sensitivity
import hexaleg.output.report.simulation as simulation
import hexaleg.output.report.statics as statics
import hexaleg.output.report.structure as structure
import hexaleg.output.report.study as study
import hexaleg.output.report.viewer as viewer
import hexaleg.output.report.walking as walking
import hexaleg.output.report.workspace as workspace
import hexaleg.output.report.yours as yours
from hexaleg.output.report.options import ReportOptions
from hexaleg.output.report.part import LeftOut, Part
from hexaleg.robot.robot import Robot

PARTS: tuple[Part[Any], ...] = (
    yours.PART,
    decision.PART,
    robot.DECISION,
    design.PART,
    robot.ROBOT,
    workspace.PART,
    manipulability.PART,
    robot.SWING,
    flexibility.PART,
    robot.STANCE,
    study.PART,
    sensitivity.PART,
    statics.PART,
    structure.PART,
    walking.PART,
    simulation.PART,
    motors.PART,
    viewer.PART,
    recommendation.PART,
    pareto.PART,
)
"""Every part of the report, in reading order; each is computed after the parts it needs."""


def parts_for(robot: Robot, options: ReportOptions) -> tuple[Part[Any], ...]:
    """The parts of :data:`PARTS` that hold for ``robot`` and ``options``, in reading order."""
    return tuple(part for part in PARTS if part.holds(robot, options) is None)


OPTION_PARTS: dict[str, Part[Any]] = {
    "collisions": flexibility.PART,
    "simulate": simulation.PART,
    "sweep": sensitivity.PART,
    "sensitivity_points": sensitivity.PART,
}
"""The part each of :class:`~.options.ReportOptions`' choices is for."""


def refused_options(robot: Robot, options: ReportOptions) -> list[tuple[str, LeftOut]]:
    """The options given whose part does not hold for ``robot`` (option, what is left out).

    An option is given when it differs from :class:`~.options.ReportOptions`' default.
    """
    default = ReportOptions()
    refused = []
    for name, part in OPTION_PARTS.items():
        left = part.holds(robot, options)
        if getattr(options, name) != getattr(default, name) and left is not None:
            refused.append((name, left))
    return refused
