"""Report part: body flexibility of the design with the feet planted (paper §6)."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.output.figures import extremes_figure, save
from hexaleg.output.report.document import Figure, Section, table, write_csv
from hexaleg.output.report.part import Part, ReportData, where_legs_are_the_designs
from hexaleg.output.report.yours import YoursRecord
from hexaleg.stance.constraints import TRANSLATIONS
from hexaleg.stance.extremes import FlexibilityResult, FlexibilityWarning
from hexaleg.stance.free_coupled import free_flexibility


@dataclass(frozen=True)
class FlexibilityRecord:
    """The design's twelve extremes in both modes, all six feet down.

    Attributes:
        axis: Axis-locked flexibility (one coordinate moves, the other five held).
        free: Free-coupled flexibility (the other five free to help).

    """

    axis: FlexibilityResult
    free: FlexibilityResult


def compute(data: ReportData) -> FlexibilityRecord:
    """Free-coupled flexibility of the design, beside its axis-locked one (measured once)."""
    design, model, collisions = data.design, data.model, data.options.collisions
    axis = data[YoursRecord].evaluation.flexibility
    assert axis is not None  # the evaluation keeps its analyses
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexibilityWarning)  # reported as "converged"
        free = free_flexibility(design, "all", model, collisions=collisions)
    return FlexibilityRecord(axis, free)


def extremes_rows(record: FlexibilityRecord) -> list[dict[str, Any]]:
    """Both modes' twelve extremes side by side (``extremes.csv``)."""
    rows = []
    for e_axis, e_free in zip(record.axis.extremes, record.free.extremes, strict=True):
        rows.append(
            {
                "direction": e_axis.name,
                "axis": e_axis.axis,
                "sign": e_axis.sign,
                "unit": "m" if e_axis.axis in TRANSLATIONS else "rad",
                "axis_locked": e_axis.value,
                "limited_by": e_axis.description,
                "free_coupled": e_free.value,
                "free_limited_by": e_free.description,
            }
        )
    return rows


def section(data: ReportData) -> Section:
    """Body flexibility of the design in both modes (§6)."""
    record = data[FlexibilityRecord]
    return Section(
        "Body flexibility with the feet planted (paper §6)",
        (
            "All six feet on their nominal footholds. Axis-locked (the paper's ADAMS study: one "
            f"coordinate moves, the other five held) **FB = {record.axis.fb:.4f}**; free-coupled "
            f"(the other five free to help) FB = {record.free.fb:.4f}. Each extreme stops at the "
            "first constraint that breaks, named below; rotations in radians and, as in the "
            "figure, degrees.",
            table(
                ["direction", "axis-locked", "stopped by", "free-coupled", "stopped by"],
                [
                    (
                        r["direction"],
                        _displacement(r["axis_locked"], r["unit"]),
                        r["limited_by"],
                        _displacement(r["free_coupled"], r["unit"]),
                        r["free_limited_by"],
                    )
                    for r in extremes_rows(record)
                ],
            ),
            Figure(
                "flexibility_extremes",
                "How far the body moves along and about each axis with all six feet planted "
                "(axis-locked), and what stops it",
            ),
        ),
    )


def _displacement(value: float, unit: str) -> str:
    if unit == "rad":
        return f"{value:+.4f} rad ({math.degrees(value):+.2f}°)"
    return f"{value:+.4f} {unit}"


def write_files(data: ReportData, out: Path) -> None:
    """The extremes figure and ``extremes.csv``."""
    record = data[FlexibilityRecord]
    save(extremes_figure(record.axis), out / "flexibility_extremes.png", svg=data.options.svg)
    write_csv(out / "extremes.csv", extremes_rows(record))


def to_json(record: FlexibilityRecord) -> dict[str, Any]:
    """``flexibility``: both modes."""
    return {"flexibility": {"axis": record.axis.to_dict(), "free": record.free.to_dict()}}


FREE_COUPLED = where_legs_are_the_designs(
    "Free-coupled flexibility and its statics",
    "not yet in this report of an imported robot: `flexibility --urdf FILE --mode free` "
    "runs it (with `--collisions`, on the file's collision geometry)",
)
"""Where this report's flexibility in both modes and its statics hold (not yet where the
legs are their own: the robot's axis-locked stance section is shown instead)."""

PART = Part(
    FlexibilityRecord,
    compute,
    section,
    needs=(YoursRecord,),
    step="body flexibility",
    files=write_files,
    json=to_json,
    holds=FREE_COUPLED,
)
