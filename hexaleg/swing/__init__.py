"""Swing phase: one leg in the air — its workspace (paper §4) and manipulability (§5)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

_EXPORTS: dict[str, str] = {
    "analyze_manipulability": "hexaleg.swing.manipulability",
    "analyze_workspace": "hexaleg.swing.workspace",
    "average_manipulability": "hexaleg.swing.manipulability",
    "average_manipulability_map": "hexaleg.swing.manipulability",
    "AverageManipulabilityMap": "hexaleg.swing.manipulability",
    "improved_area_closed_form": "hexaleg.swing.workspace",
    "ManipulabilityAnalysis": "hexaleg.swing.manipulability",
    "ManipulabilityIndices": "hexaleg.swing.manipulability",
    "monte_carlo_workspace": "hexaleg.swing.workspace",
    "MonteCarloWorkspace": "hexaleg.swing.workspace",
    "optimum_pose": "hexaleg.swing.manipulability",
    "OptimumPose": "hexaleg.swing.manipulability",
    "planar_workspace": "hexaleg.swing.workspace",
    "PlanarWorkspace": "hexaleg.swing.workspace",
    "pose_indices": "hexaleg.swing.manipulability",
    "WorkspaceAnalysis": "hexaleg.swing.workspace",
}

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

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

if TYPE_CHECKING:  # the same names, for type checkers and IDEs
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
