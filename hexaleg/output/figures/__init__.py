"""Matplotlib figures of the paper and of the design, one module per part.

Each function draws from results the analyses computed (nothing here computes an
analysis) on matplotlib's object API (``Figure`` with the Agg canvas): no pyplot, no
global state, safe in worker processes. Axes carry units; angles are plotted in
degrees and lengths in metres, as labelled.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

_EXPORTS: dict[str, str] = {
    "average_manipulability_figure": "hexaleg.output.figures.manipulability",
    "DPI": "hexaleg.output.figures.canvas",
    "extremes_figure": "hexaleg.output.figures.flexibility",
    "fb_figure": "hexaleg.output.figures.study",
    "l1_series_figure": "hexaleg.output.figures.workspace",
    "LIMIT_SET_TITLES": "hexaleg.output.figures.canvas",
    "loads_figure": "hexaleg.output.figures.statics",
    "manipulability_surface_figure": "hexaleg.output.figures.manipulability",
    "monte_carlo_figure": "hexaleg.output.figures.workspace",
    "pareto_figure": "hexaleg.output.figures.study",
    "planar_workspace_figure": "hexaleg.output.figures.workspace",
    "ranges_figure": "hexaleg.output.figures.study",
    "save": "hexaleg.output.figures.canvas",
    "statics_study_figure": "hexaleg.output.figures.statics",
    "table5_surfaces": "hexaleg.output.figures.manipulability",
    "write_manipulability_figures": "hexaleg.output.figures.manipulability",
    "write_study_figures": "hexaleg.output.figures.study",
    "write_workspace_figures": "hexaleg.output.figures.workspace",
}

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

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

if TYPE_CHECKING:  # the same names, for type checkers and IDEs
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
