"""``hexaleg report``: everything hexaleg can tell a leg designer, in one folder.

Data first, then presentation: :func:`compute_report` runs every analysis into a
frozen :class:`ReportData`; :mod:`~hexaleg.output.report.sections` turns it into
markdown; :func:`render_report` writes md, html, json, csv, figures, the URDF and
a static viewer, and swaps the folder in only when complete.
"""

from __future__ import annotations

import os
from typing import Any

from hexaleg.design import HexapodDesign
from hexaleg.output.report.compute import ReportData, ReportOptions, compute_report
from hexaleg.output.report.render import (
    REPORT_HTML,
    REPORT_JSON,
    REPORT_MD,
    check_target,
    render_report,
)

__all__ = [
    "REPORT_HTML",
    "REPORT_JSON",
    "REPORT_MD",
    "ReportData",
    "ReportOptions",
    "build_report",
    "compute_report",
    "render_report",
]


def build_report(
    out_dir: str | os.PathLike[str],
    design: HexapodDesign | None = None,
    options: ReportOptions | None = None,
) -> dict[str, Any]:
    """Run every analysis and write the report folder; return the report's numbers."""
    check_target(out_dir)  # before the minutes of computing, not after
    data = compute_report(design or HexapodDesign(), options or ReportOptions())
    render_report(data, out_dir)
    return data.to_json()
