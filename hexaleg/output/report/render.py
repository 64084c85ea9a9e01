"""Step 3 of the report: write :class:`ReportData` into a folder, atomically.

The folder is built beside the target and swapped in only when complete, so a
failed or interrupted run leaves the previous report (or nothing) in place; only a
report folder hexaleg wrote is ever replaced (see :mod:`hexaleg._folders`).
"""

from __future__ import annotations

import os
from pathlib import Path

from hexaleg._folders import check_replaceable_folder, replace_folder
from hexaleg.output.report.content import REPORT_HTML, REPORT_JSON, REPORT_MD, write_content
from hexaleg.output.report.part import ReportData

FOLDER_KIND = "report"
"""What the folder's marker says it is: hexaleg replaces only a folder it wrote."""

__all__ = [
    "FOLDER_KIND",
    "REPORT_HTML",
    "REPORT_JSON",
    "REPORT_MD",
    "check_target",
    "render_report",
]


def render_report(data: ReportData, out_dir: str | os.PathLike[str]) -> Path:
    """Write the report folder for ``data`` atomically; return its path."""
    with replace_folder(out_dir, FOLDER_KIND) as staging:
        write_content(data, staging)
    return Path(out_dir)


def check_target(out: str | os.PathLike[str]) -> None:
    """Refuse, before computing, an output folder that is not a hexaleg report."""
    check_replaceable_folder(out, FOLDER_KIND)
