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

__all__ = [
    "Conditions",
    "DecideResult",
    "DesignError",
    "Evaluation",
    "FlexibilityResult",
    "FlexibilityWarning",
    "FootSearch",
    "Gait",
    "GaitAnalysis",
    "Ground",
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
    "METRICS",
    "ManipulabilityAnalysis",
    "Material",
    "Metrics",
    "ModelError",
    "Objective",
    "ParameterError",
    "Payload",
    "ReportOptions",
    "Requirements",
    "Robot",
    "RobotImportError",
    "RobotImportWarning",
    "RobotSource",
    "STANCE_LIMITS",
    "SearchSettings",
    "SegmentChange",
    "SimulationResult",
    "StanceGeometry",
    "Structure",
    "StudySpec",
    "TRIPODS",
    "TemplateError",
    "Tube",
    "WORKSPACE_LIMITS",
    "WorkspaceAnalysis",
    "__version__",
    "analyze_gait",
    "analyze_loads",
    "analyze_manipulability",
    "analyze_workspace",
    "best_posture",
    "build_report",
    "decide",
    "default_mounts",
    "design_toml",
    "evaluate",
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
    "resize_robot",
    "run_study",
    "shipped_materials",
    "simulate_gait",
    "size_structure",
    "write_urdf",
]


__getattr__, __dir__ = lazy_exports(__name__)

if TYPE_CHECKING:  # where each name is from: read by type checkers, the docs and lazy_exports
    from hexaleg.design import HexapodDesign, default_mounts
    from hexaleg.design_file import load_design
    from hexaleg.design_text import design_toml
    from hexaleg.evaluation.evaluate import Conditions, Evaluation, evaluate
    from hexaleg.evaluation.goal import Objective
    from hexaleg.evaluation.metrics import METRICS, Metrics
    from hexaleg.evaluation.requirements import Requirements
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
    from hexaleg.leg_structure import Structure, Tube
    from hexaleg.limits import (
        IMPROVED_LIMITS,
        MANIPULABILITY_LIMITS,
        STANCE_LIMITS,
        WORKSPACE_LIMITS,
        JointLimits,
    )
    from hexaleg.materials import Material, shipped_materials
    from hexaleg.output.report import build_report
    from hexaleg.output.report.options import ReportOptions
    from hexaleg.robot.feet import FootSearch
    from hexaleg.robot.imported import ImportedRobot, SegmentChange, import_robot
    from hexaleg.robot.leg_model import LegModel
    from hexaleg.robot.model import HexapodModel
    from hexaleg.robot.recipe import RobotSource
    from hexaleg.robot.resize import resize_robot
    from hexaleg.robot.robot import Robot
    from hexaleg.robot.urdf import render_hexapod, render_leg, write_urdf
    from hexaleg.sim.result import SimulationResult
    from hexaleg.sim.simulate import simulate_gait
    from hexaleg.stance.extremes import FlexibilityResult, FlexibilityWarning
    from hexaleg.stance.flexibility import flexibility
    from hexaleg.stance.geometry import StanceGeometry
    from hexaleg.statics.forces import Payload
    from hexaleg.statics.ground import Ground
    from hexaleg.statics.loads import analyze_loads
    from hexaleg.structure.sizing import size_structure
    from hexaleg.study.decide import DecideResult, decide
    from hexaleg.study.optimize import SearchSettings
    from hexaleg.study.posture import best_posture
    from hexaleg.study.sweep import StudySpec, run_study
    from hexaleg.swing.manipulability import ManipulabilityAnalysis, analyze_manipulability
    from hexaleg.swing.workspace import WorkspaceAnalysis, analyze_workspace
