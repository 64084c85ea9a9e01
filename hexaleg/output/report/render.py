"""Step 3 of the report: write :class:`ReportData` into a folder, atomically.

The folder is built beside the target and swapped in only when complete, so a
failed or interrupted run leaves the previous report (or nothing) in place.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

from hexaleg._io import retired_folder, staging_folder
from hexaleg.exceptions import HexalegError
from hexaleg.output.report.content import REPORT_HTML, REPORT_JSON, REPORT_MD, write_content
from hexaleg.output.report.part import ReportData

__all__ = ["REPORT_HTML", "REPORT_JSON", "REPORT_MD", "check_target", "render_report"]


def render_report(data: ReportData, out_dir: str | os.PathLike[str]) -> Path:
    """Write the report folder for ``data`` atomically; return its path."""
    out = Path(out_dir)
    check_target(out)
    staging = staging_folder(out)
    try:
        write_content(data, staging)
        _swap_in(staging, out)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return out


def check_target(out: Path) -> None:
    """Refuse an output folder that holds something other than a hexaleg report."""
    if out.exists() and (
        not out.is_dir() or (any(out.iterdir()) and not (out / REPORT_MD).exists())
    ):
        raise HexalegError(
            f"-o {out} exists and is not a hexaleg report: choose a new or empty folder"
        )


def _swap_in(staging: Path, out: Path) -> None:
    old = None
    if out.exists():
        old = retired_folder(out)
        out.rename(old)
    staging.rename(out)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
