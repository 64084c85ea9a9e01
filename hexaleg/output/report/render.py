"""Step 3 of the report: write :class:`ReportData` and its sections into a folder.

The folder is built beside the target and swapped in only when complete, so a
failed or interrupted run leaves the previous report (or nothing) in place.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path
from typing import Any

import markdown
import pandas as pd

from hexaleg._io import atomic_write_text, retired_folder, staging_folder
from hexaleg.exceptions import HexalegError
from hexaleg.output.figures import (
    extremes_figure,
    loads_figure,
    pareto_figure,
    save,
    statics_study_figure,
    write_manipulability_figures,
    write_study_figures,
    write_workspace_figures,
)
from hexaleg.output.report.compute import ReportData
from hexaleg.output.report.sections import (
    average_manipulability_rows,
    extremes_rows,
    report_markdown,
)
from hexaleg.output.report.walking import walking_section, write_walking_figure
from hexaleg.output.viewer.scene import write_static_html
from hexaleg.study.sweep import write_journal, write_table

REPORT_MD = "report.md"
REPORT_HTML = "report.html"
REPORT_JSON = "report.json"
STUDY_FOLDER = "study"

_STYLE = (
    "body{font-family:sans-serif;max-width:72rem;margin:2rem auto;padding:0 1rem;"
    "line-height:1.45}table{border-collapse:collapse;margin:1rem 0}"
    "td,th{border:1px solid #bbb;padding:.25rem .5rem}th{background:#eee}"
    "img{max-width:min(100%,52rem);display:block}figcaption{color:#555;font-size:.9rem}"
)


def render_report(data: ReportData, out_dir: str | os.PathLike[str]) -> Path:
    """Write the report folder for ``data`` atomically; return its path."""
    out = Path(out_dir)
    check_target(out)
    staging = staging_folder(out)
    try:
        _write_files(data, staging)
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


def _write_files(data: ReportData, out: Path) -> None:
    atomic_write_text(out / "hexapod.urdf", data.model.urdf)
    write_workspace_figures(data.workspace, out)
    _write_csv(out / "table5.csv", data.table5)
    write_manipulability_figures(data.manipulability, data.average_map, out)
    _write_csv(out / "table6.csv", data.table6)
    _write_csv(out / "average_manipulability.csv", average_manipulability_rows(data))
    save(extremes_figure(data.axis), out / "flexibility_extremes.png")
    _write_csv(out / "extremes.csv", extremes_rows(data))
    study = out / STUDY_FOLDER
    write_journal(study, data.study_spec, data.study)
    write_table(data.study_spec, data.study, study)
    write_study_figures(data.study, out)
    save(statics_study_figure(data.study), out / "study_statics.png")
    write_walking_figure(data.study, out)
    save(loads_figure(data.loads), out / "loads.png")
    save(pareto_figure(data.study, data.pareto), out / "pareto_front.png")
    _write_csv(out / "pareto_front.csv", data.pareto.to_dict(orient="records"))
    atomic_write_text(out / "sensitivity.csv", data.sensitivity.to_csv(index=False))
    write_static_html(
        data.model, data.axis, out / "viewer.html", data.model.leg_names[0], data.loads
    )
    _write_csv(
        out / "recommendation_scores.csv",
        data.recommendation.scores.to_dict(orient="records"),
    )
    text = report_markdown(data) + "\n" + walking_section(data.walking).markdown() + "\n"
    atomic_write_text(out / REPORT_MD, text)
    atomic_write_text(out / REPORT_HTML, _html(text))
    atomic_write_text(out / REPORT_JSON, json.dumps(data.to_json(), indent=1, allow_nan=True))


def _write_csv(path: Path, rows: list[dict[str, Any]]) -> None:
    atomic_write_text(path, pd.DataFrame(rows).to_csv(index=False))


def _html(text: str) -> str:
    body = markdown.markdown(text, extensions=["tables"])
    return (
        "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
        f"<title>hexaleg report</title><style>{_STYLE}</style></head><body>\n"
        f"{body}\n</body></html>\n"
    )


def _swap_in(staging: Path, out: Path) -> None:
    old = None
    if out.exists():
        old = retired_folder(out)
        out.rename(old)
    staging.rename(out)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
