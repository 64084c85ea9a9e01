"""Swing phase: one leg in the air — its workspace (paper §4) and manipulability (§5)."""

from hexaleg.swing.manipulability import (
    AverageManipulabilityMap,
    ManipulabilityAnalysis,
    ManipulabilityIndices,
    OptimumPose,
    analyze_manipulability,
    average_manipulability,
    average_manipulability_map,
    optimum_pose,
    pose_indices,
)
from hexaleg.swing.workspace import (
    MonteCarloWorkspace,
    PlanarWorkspace,
    WorkspaceAnalysis,
    analyze_workspace,
    improved_area_closed_form,
    monte_carlo_workspace,
    planar_workspace,
)

__all__ = [
    "AverageManipulabilityMap",
    "ManipulabilityAnalysis",
    "ManipulabilityIndices",
    "MonteCarloWorkspace",
    "OptimumPose",
    "PlanarWorkspace",
    "WorkspaceAnalysis",
    "analyze_manipulability",
    "analyze_workspace",
    "average_manipulability",
    "average_manipulability_map",
    "improved_area_closed_form",
    "monte_carlo_workspace",
    "optimum_pose",
    "planar_workspace",
    "pose_indices",
]
