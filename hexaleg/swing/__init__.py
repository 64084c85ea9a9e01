"""Swing phase: one leg in the air — its workspace (paper §4) and manipulability (§5)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

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

__getattr__, __dir__ = lazy_exports(__name__)

if TYPE_CHECKING:  # where each name is from: read by type checkers, the docs and lazy_exports
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
