"""Report part: the legs' structure — each segment's tube, mass, worst stress ratio, deflection.

Shown when the design file has a ``[structure]`` table with its tubes (given or sized by the
command line before the report measures the design). Every number is your design's one
evaluation's (:mod:`.yours`): the statics at the nominal stance and the extremes of its
axis-locked flexibility, which check the tubes (:class:`~hexaleg.structure.check.StructureCheck`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.leg_structure import LEG_SEGMENTS, segment_masses
from hexaleg.output.report.document import Section, table
from hexaleg.output.report.options import ReportOptions
from hexaleg.output.report.part import LeftOut, Part, ReportData
from hexaleg.output.report.yours import YoursRecord
from hexaleg.robot.robot import Robot
from hexaleg.structure.check import StructureCheck


@dataclass(frozen=True)
class StructureRecord:
    """Your design's tubes as its one evaluation checked them.

    Attributes:
        check: The tubes under every standing load case of the statics (``None``: the
            evaluation checked none, e.g. a segment has no tube yet).

    """

    check: StructureCheck | None


def holds(robot: Robot, options: ReportOptions) -> LeftOut | None:
    """The section holds for a design with a ``[structure]`` table."""
    return None if robot.design.structure is not None else LeftOut()


def compute(data: ReportData) -> StructureRecord:
    """The structure check of your design's one evaluation."""
    loads = data[YoursRecord].evaluation.loads
    return StructureRecord(None if loads is None else loads.structure)


def segment_rows(check: StructureCheck) -> list[tuple[str, ...]]:
    """Each segment: its tube, its mass, its worst stress ratio and where (leg, load case)."""
    masses = segment_masses(check.structure, check.lengths, math.nan)
    ratios = check.ratios  # (cases, legs, segments)
    rows: list[tuple[str, ...]] = []
    for j, (segment, tube) in enumerate(zip(LEG_SEGMENTS, check.structure.tubes, strict=True)):
        case, leg = np.unravel_index(int(ratios[:, :, j].argmax()), ratios.shape[:2])
        worst = float(ratios[case, leg, j])
        shape = "—" if tube is None else (
            f"D {tube.outer_diameter * 1e3:.4g} mm, wall {tube.wall * 1e3:.4g} mm"
        )  # fmt: skip
        rows.append(
            (
                segment,
                shape,
                f"{masses[j]:.4g}",
                f"{worst:.3f}" + (" (OVER STRENGTH)" if worst > 1 else ""),
                f"{check.legs[leg]}, {check.cases[case]}",
            )
        )
    return rows


def section(data: ReportData) -> Section:
    """The tubes, their masses, worst ratios and cases, and the foot's deflection."""
    check = data[StructureRecord].check
    title = "Leg structure: tubes, stresses and deflection"
    if check is None:
        return Section(title, ("No tube was checked: give every segment a tube, or `size`.",))
    structure = check.structure
    material = structure.material
    blocks: list[str] = [
        f"Each leg segment is a tube of {material.name} (yield {material.yield_strength / 1e6:.4g}"
        f" MPa, safety factor {structure.safety_factor:g}: {structure.allowed_stress / 1e6:.4g} "
        "MPa allowed), checked at its proximal joint under every load case of the statics "
        "(the nominal stance and the extremes of the axis-locked flexibility): the worst "
        "von Mises stress over what is allowed, over the six legs.",
        table(
            ["segment", "tube", "mass [kg]", "worst stress ratio", "where (leg, case)"],
            segment_rows(check),
        ),
    ]
    where = check.deflection_at
    if where is not None and not math.isnan(check.deflection):
        over = " — OVER THE LIMIT" if check.over_deflection else ""
        blocks.append(
            f"Largest foot deflection {check.deflection * 1e3:.3g} mm ({where['leg']}, "
            f"{where['case']}), limit {check.limit * 1e3:.3g} mm{over}."
        )
    return Section(title, tuple(blocks))


def to_json(record: StructureRecord) -> dict[str, Any]:
    """``structure``: the check (SI: N, N·m, Pa, m, kg), or null."""
    return {"structure": None if record.check is None else record.check.to_dict()}


PART = Part(
    StructureRecord,
    compute,
    section,
    needs=(YoursRecord,),
    step="leg structure",
    json=to_json,
    level=2,
    holds=holds,
)
