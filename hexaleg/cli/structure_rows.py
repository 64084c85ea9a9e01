"""The legs' structure as the commands print it: the material, each tube, its checks.

The tubes are sized, where a design file's ``[structure]`` asks, before a command measures
the design (:func:`hexaleg.evaluation.inputs.sized_for`); these are the text tables' rows.
"""

from __future__ import annotations

import math

from hexaleg.leg_structure import LEG_SEGMENTS, Structure, segment_masses
from hexaleg.structure.check import StructureCheck
from hexaleg.structure.sizing import SizedStructure


def tube_rows(structure: Structure, lengths: tuple[float, float, float]) -> list[tuple[str, str]]:
    """The material and what it allows, and each segment's tube and mass."""
    material = structure.material
    rows = [
        (
            "structure",
            f"{material.name}: {material.yield_strength / 1e6:.4g} MPa / the tubes' safety factor "
            f"{structure.safety_factor:g} = {structure.allowed_stress / 1e6:.4g} MPa allowed",
        )
    ]
    masses = segment_masses(structure, lengths, math.nan)
    for segment, tube, mass in zip(LEG_SEGMENTS, structure.tubes, masses, strict=True):
        if tube is None:
            rows.append((f"{segment} tube", "to be sized"))
            continue
        solid = " (solid)" if 2 * tube.wall >= tube.outer_diameter else ""
        rows.append(
            (
                f"{segment} tube",
                f"D {tube.outer_diameter * 1e3:.4g} mm, wall {tube.wall * 1e3:.4g} mm{solid}, "
                f"{mass:.4g} kg",
            )
        )
    return rows


def structure_rows(
    check: StructureCheck | None, sized: SizedStructure | None = None
) -> list[tuple[str, str]]:
    """A check's rows: material, tubes, how they were sized, worst ratio, deflection, flags."""
    if check is None:
        return []
    rows = tube_rows(check.structure, check.lengths)
    if sized is not None:
        settled = "" if sized.settled else ", NOT SETTLED"
        rounds = f"{sized.iterations} rounds of loads and tubes{settled}"
        rows.append(("tubes sized", f"the lightest on the grid that hold, after {rounds}"))
    worst = check.worst
    flag = ", OVER STRENGTH" if check.worst_ratio > 1 else ""
    rows.append(
        (
            "worst stress ratio",
            f"{check.worst_ratio:.3f}: {worst['leg']} {worst['segment']} ({worst['case']}){flag}",
        )
    )
    if check.deflection_at is not None and not math.isnan(check.deflection):
        over = ", OVER LIMIT" if check.over_deflection else ""
        where = check.deflection_at
        rows.append(
            (
                "foot deflection",
                f"{check.deflection * 1e3:.3g} mm ({where['leg']}, {where['case']}), limit "
                f"{check.limit * 1e3:.3g} mm{over}",
            )
        )
    return rows + [("OVER STRENGTH", str(over)) for over in check.over_strength]
