"""The robot: Xacro → URDF (:mod:`.urdf`) → Pinocchio model (:mod:`.model`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

_EXPORTS: dict[str, str] = {
    "foot_frame_name": "hexaleg.robot.model",
    "HexapodModel": "hexaleg.robot.model",
    "joint_name": "hexaleg.robot.model",
    "LEG_JOINTS": "hexaleg.robot.model",
    "LegModel": "hexaleg.robot.model",
    "render_hexapod": "hexaleg.robot.urdf",
    "render_leg": "hexaleg.robot.urdf",
    "root_frame_name": "hexaleg.robot.model",
    "validate_urdf": "hexaleg.robot.urdf",
    "write_urdf": "hexaleg.robot.urdf",
}

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

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

if TYPE_CHECKING:  # the same names, for type checkers and IDEs
    from hexaleg.robot.model import (
        LEG_JOINTS,
        HexapodModel,
        LegModel,
        foot_frame_name,
        joint_name,
        root_frame_name,
    )
    from hexaleg.robot.urdf import render_hexapod, render_leg, validate_urdf, write_urdf
