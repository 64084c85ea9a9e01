"""The robot: Xacro → URDF (:mod:`.urdf`) → Pinocchio model (:mod:`.model`)."""

from hexaleg.robot.model import (
    LEG_JOINTS,
    HexapodModel,
    LegModel,
    foot_frame_name,
    joint_name,
    root_frame_name,
)
from hexaleg.robot.urdf import render_hexapod, render_leg, validate_urdf, write_urdf

__all__ = [
    "LEG_JOINTS",
    "HexapodModel",
    "LegModel",
    "foot_frame_name",
    "joint_name",
    "render_hexapod",
    "render_leg",
    "root_frame_name",
    "validate_urdf",
    "write_urdf",
]
