"""A robot file's designs for the study, the decision and the report (until they take a Robot)."""

from __future__ import annotations

from hexaleg.robot.robot import Robot
from hexaleg.study.robot_designs import RobotDesigns, RobotFile


def robot_designs(robot: Robot) -> RobotDesigns | None:
    """A robot file's designs over the design it was built over; ``None`` for the template."""
    source = robot.source
    if source.path is None:
        return None
    segments = tuple((s.leg, s.segment, s.length) for s in source.segments)
    file = RobotFile(
        source.path,
        source.xacro_args,
        source.packages,
        source.foot_offset,
        source.foot_frame,
        segments,
    )
    return RobotDesigns(file, robot.over)
