"""Matplotlib figures of the paper and of the design, one module per part.

Each function draws from results the analyses computed (nothing here computes an
analysis) on matplotlib's object API (``Figure`` with the Agg canvas): no pyplot, no
global state, safe in worker processes. Axes carry units; angles are plotted in
degrees and lengths in metres, as labelled.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

__all__ = [
    "DPI",
    "LIMIT_SET_TITLES",
    "average_manipulability_figure",
    "extremes_figure",
    "fb_figure",
    "l1_series_figure",
    "loads_figure",
    "manipulability_surface_figure",
    "monte_carlo_figure",
    "pareto_figure",
    "planar_workspace_figure",
    "ranges_figure",
    "save",
    "statics_study_figure",
    "table5_surfaces",
    "write_manipulability_figures",
    "write_study_figures",
    "write_workspace_figures",
]

__getattr__, __dir__ = lazy_exports(__name__)

if TYPE_CHECKING:  # where each name is from: read by type checkers, the docs and lazy_exports
    from hexaleg.output.figures.canvas import DPI, LIMIT_SET_TITLES, save
    from hexaleg.output.figures.flexibility import extremes_figure
    from hexaleg.output.figures.manipulability import (
        average_manipulability_figure,
        manipulability_surface_figure,
        table5_surfaces,
        write_manipulability_figures,
    )
    from hexaleg.output.figures.statics import loads_figure, statics_study_figure
    from hexaleg.output.figures.study import (
        fb_figure,
        pareto_figure,
        ranges_figure,
        write_study_figures,
    )
    from hexaleg.output.figures.workspace import (
        l1_series_figure,
        monte_carlo_figure,
        planar_workspace_figure,
        write_workspace_figures,
    )
