"""hexaleg: choose the segment lengths of a hexapod's legs.

A design (coxa l1, femur l2, tibia l3, body, joint limits) becomes a URDF via
Xacro, then a Pinocchio model; hexaleg measures leg workspace, manipulability
and body flexibility on it. SI units and radians everywhere.
"""

from hexaleg._version import __version__
from hexaleg.design import LEG_NAMES, TRIPODS, HexapodDesign, LegMount, default_mounts
from hexaleg.exceptions import DesignError, HexalegError, ModelError, TemplateError
from hexaleg.kinematics import (
    InverseKinematics,
    foot_jacobian,
    foot_position,
    inverse_kinematics,
    manipulability,
    planar_foot_position,
)
from hexaleg.limits import (
    IMPROVED_LIMITS,
    MANIPULABILITY_LIMITS,
    STANCE_LIMITS,
    WORKSPACE_LIMITS,
    JointLimits,
)
from hexaleg.model import HexapodModel, LegModel
from hexaleg.urdf import render_hexapod, render_leg, write_urdf

__all__ = [
    "DesignError",
    "HexalegError",
    "HexapodDesign",
    "HexapodModel",
    "IMPROVED_LIMITS",
    "InverseKinematics",
    "JointLimits",
    "LEG_NAMES",
    "LegModel",
    "LegMount",
    "MANIPULABILITY_LIMITS",
    "ModelError",
    "STANCE_LIMITS",
    "TRIPODS",
    "TemplateError",
    "WORKSPACE_LIMITS",
    "__version__",
    "default_mounts",
    "foot_jacobian",
    "foot_position",
    "inverse_kinematics",
    "manipulability",
    "planar_foot_position",
    "render_hexapod",
    "render_leg",
    "write_urdf",
]
