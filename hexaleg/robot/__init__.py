"""The robot: Xacro → URDF (:mod:`.urdf`) → Pinocchio model (:mod:`.model`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

__all__ = [
    "LEG_JOINTS",
    "HexapodModel",
    "LegModel",
    "foot_frame_name",
    "joint_name",
    "model_of",
    "per_body",
    "render_hexapod",
    "render_leg",
    "root_frame_name",
    "validate_urdf",
    "write_urdf",
]

__getattr__, __dir__ = lazy_exports(__name__)

if TYPE_CHECKING:  # where each name is from: read by type checkers, the docs and lazy_exports
    from hexaleg.robot.leg_model import LegModel
    from hexaleg.robot.model import (
        LEG_JOINTS,
        HexapodModel,
        foot_frame_name,
        joint_name,
        root_frame_name,
    )
    from hexaleg.robot.model_cache import model_of, per_body
    from hexaleg.robot.urdf import render_hexapod, render_leg, validate_urdf, write_urdf
