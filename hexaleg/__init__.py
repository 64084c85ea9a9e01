"""hexaleg: choose the segment lengths of a hexapod's legs.

A design (coxa l1, femur l2, tibia l3, body, joint limits) becomes a URDF via
Xacro, then a Pinocchio model; hexaleg measures leg workspace, manipulability
and body flexibility on it. SI units and radians everywhere.

The public API below is importable from ``hexaleg`` directly. Names load on first
use (PEP 562), so ``import hexaleg`` and ``hexaleg --help`` stay instant.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports
from hexaleg._version import __version__

_EXPORTS: dict[str, str] = {
    # design and limits
    "HexapodDesign": "hexaleg.design",
    "LEG_NAMES": "hexaleg.layouts",
    "LegMount": "hexaleg.layouts",
    "TRIPODS": "hexaleg.layouts",
    "default_mounts": "hexaleg.design",
    "hexagon_mounts": "hexaleg.layouts",
    "rectangle_mounts": "hexaleg.layouts",
    "design_toml": "hexaleg.design_file",
    "load_design": "hexaleg.design_file",
    "IMPROVED_LIMITS": "hexaleg.limits",
    "JointLimits": "hexaleg.limits",
    "MANIPULABILITY_LIMITS": "hexaleg.limits",
    "STANCE_LIMITS": "hexaleg.limits",
    "WORKSPACE_LIMITS": "hexaleg.limits",
    # errors
    "DesignError": "hexaleg.exceptions",
    "HexalegError": "hexaleg.exceptions",
    "ParameterError": "hexaleg.exceptions",
    "ModelError": "hexaleg.exceptions",
    "TemplateError": "hexaleg.exceptions",
    "RobotImportError": "hexaleg.exceptions",
    "RobotImportWarning": "hexaleg.exceptions",
    # closed forms (the oracle)
    "InverseKinematics": "hexaleg.kinematics",
    "foot_jacobian": "hexaleg.kinematics",
    "foot_position": "hexaleg.kinematics",
    "inverse_kinematics": "hexaleg.kinematics",
    "manipulability": "hexaleg.kinematics",
    "planar_foot_position": "hexaleg.kinematics",
    "LegGeometry": "hexaleg.leg_geometry",
    # robot
    "HexapodModel": "hexaleg.robot.model",
    "LegModel": "hexaleg.robot.model",
    "render_hexapod": "hexaleg.robot.urdf",
    "render_leg": "hexaleg.robot.urdf",
    "write_urdf": "hexaleg.robot.urdf",
    "FootSearch": "hexaleg.robot.feet",
    "ImportedRobot": "hexaleg.robot.imported",
    "import_robot": "hexaleg.robot.imported",
    # swing phase
    "ManipulabilityAnalysis": "hexaleg.swing.manipulability",
    "analyze_manipulability": "hexaleg.swing.manipulability",
    "WorkspaceAnalysis": "hexaleg.swing.workspace",
    "analyze_workspace": "hexaleg.swing.workspace",
    # stance phase
    "StanceGeometry": "hexaleg.stance.geometry",
    "FlexibilityResult": "hexaleg.stance.extremes",
    "FlexibilityWarning": "hexaleg.stance.extremes",
    "flexibility": "hexaleg.stance.flexibility",
    # statics and walking
    "Payload": "hexaleg.statics.forces",
    "analyze_loads": "hexaleg.statics.loads",
    "Gait": "hexaleg.gait.spec",
    "GaitAnalysis": "hexaleg.gait.analysis",
    "analyze_gait": "hexaleg.gait.analysis",
    "SimulationResult": "hexaleg.sim.result",
    "simulate_gait": "hexaleg.sim.simulate",
    # studies and output
    "StudySpec": "hexaleg.study.sweep",
    "run_study": "hexaleg.study.sweep",
    "DecideResult": "hexaleg.study.decide",
    "Objective": "hexaleg.study.evaluation",
    "Requirements": "hexaleg.study.requirements",
    "SearchSettings": "hexaleg.study.optimize",
    "decide": "hexaleg.study.decide",
    "ReportOptions": "hexaleg.output.report.options",
    "build_report": "hexaleg.output.report",
}

__all__ = [
    "DecideResult",
    "DesignError",
    "FlexibilityResult",
    "FlexibilityWarning",
    "FootSearch",
    "Gait",
    "GaitAnalysis",
    "HexalegError",
    "HexapodDesign",
    "HexapodModel",
    "IMPROVED_LIMITS",
    "ImportedRobot",
    "InverseKinematics",
    "JointLimits",
    "LEG_NAMES",
    "LegGeometry",
    "LegModel",
    "LegMount",
    "MANIPULABILITY_LIMITS",
    "ManipulabilityAnalysis",
    "ModelError",
    "Objective",
    "ParameterError",
    "Payload",
    "ReportOptions",
    "Requirements",
    "RobotImportError",
    "RobotImportWarning",
    "STANCE_LIMITS",
    "SearchSettings",
    "SimulationResult",
    "StanceGeometry",
    "StudySpec",
    "TRIPODS",
    "TemplateError",
    "WORKSPACE_LIMITS",
    "WorkspaceAnalysis",
    "__version__",
    "analyze_gait",
    "analyze_loads",
    "analyze_manipulability",
    "analyze_workspace",
    "build_report",
    "decide",
    "default_mounts",
    "design_toml",
    "flexibility",
    "foot_jacobian",
    "foot_position",
    "hexagon_mounts",
    "import_robot",
    "inverse_kinematics",
    "load_design",
    "manipulability",
    "planar_foot_position",
    "rectangle_mounts",
    "render_hexapod",
    "render_leg",
    "run_study",
    "simulate_gait",
    "write_urdf",
]


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

if TYPE_CHECKING:  # the same names, for type checkers and IDEs
    from hexaleg.design import HexapodDesign, default_mounts
    from hexaleg.design_file import design_toml, load_design
    from hexaleg.exceptions import (
        DesignError,
        HexalegError,
        ModelError,
        ParameterError,
        RobotImportError,
        RobotImportWarning,
        TemplateError,
    )
    from hexaleg.gait.analysis import GaitAnalysis, analyze_gait
    from hexaleg.gait.spec import Gait
    from hexaleg.kinematics import (
        InverseKinematics,
        foot_jacobian,
        foot_position,
        inverse_kinematics,
        manipulability,
        planar_foot_position,
    )
    from hexaleg.layouts import LEG_NAMES, TRIPODS, LegMount, hexagon_mounts, rectangle_mounts
    from hexaleg.leg_geometry import LegGeometry
    from hexaleg.limits import (
        IMPROVED_LIMITS,
        MANIPULABILITY_LIMITS,
        STANCE_LIMITS,
        WORKSPACE_LIMITS,
        JointLimits,
    )
    from hexaleg.output.report import build_report
    from hexaleg.output.report.options import ReportOptions
    from hexaleg.robot.feet import FootSearch
    from hexaleg.robot.imported import ImportedRobot, import_robot
    from hexaleg.robot.model import HexapodModel, LegModel
    from hexaleg.robot.urdf import render_hexapod, render_leg, write_urdf
    from hexaleg.sim.result import SimulationResult
    from hexaleg.sim.simulate import simulate_gait
    from hexaleg.stance.extremes import FlexibilityResult, FlexibilityWarning
    from hexaleg.stance.flexibility import flexibility
    from hexaleg.stance.geometry import StanceGeometry
    from hexaleg.statics.forces import Payload
    from hexaleg.statics.loads import analyze_loads
    from hexaleg.study.decide import DecideResult, decide
    from hexaleg.study.evaluation import Objective
    from hexaleg.study.optimize import SearchSettings
    from hexaleg.study.requirements import Requirements
    from hexaleg.study.sweep import StudySpec, run_study
    from hexaleg.swing.manipulability import ManipulabilityAnalysis, analyze_manipulability
    from hexaleg.swing.workspace import WorkspaceAnalysis, analyze_workspace
