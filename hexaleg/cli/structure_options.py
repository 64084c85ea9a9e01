"""The legs' structure on the command line: tubes sized when the file asks, and their rows.

A design file's ``[structure]`` with ``size = true`` has its tubes chosen before a command
measures the design (:func:`size_if_asked`, where the design options resolve): the lightest
on the grid that hold the nominal stance, the twelve extremes and the required slope,
carrying the required payload (the file's ``[requirements]`` ``payload``, ``payload_at`` and
``slope``; none if it has none). :func:`structure_rows` is what the text tables print of a
check.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from hexaleg.cli.options import note
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.requirement_specs import SLOPE
from hexaleg.leg_structure import LEG_SEGMENTS, Structure, segment_masses
from hexaleg.statics.forces import Payload

if TYPE_CHECKING:
    from hexaleg.evaluation.requirements import Requirements
    from hexaleg.structure.check import StructureCheck
    from hexaleg.structure.sizing import SizedStructure

IMPORTED = (
    "[structure] describes hexaleg's own legs' tubes; an imported robot keeps its file's "
    "links (remove [structure] from the design file)"
)


def size_if_asked(
    design: HexapodDesign, requirements: Requirements
) -> tuple[HexapodDesign, SizedStructure | None]:
    """``design`` with its tubes sized if its ``[structure]`` says ``size = true``.

    Called where the design options resolve (:func:`~hexaleg.cli.inputs.inputs_from_args`),
    for the commands that measure the tubes; a robot file's ``[structure]`` is refused
    there (:data:`IMPORTED`).
    """
    structure = design.structure
    if structure is None or not structure.size:
        return design, None
    from hexaleg.structure.sizing import size_structure  # the search: not to parse options

    payload = Payload(requirements.payload_mass, requirements.payload_at)
    sized = size_structure(design, payload=payload, slope=requirements.required(SLOPE) or 0.0)
    if not sized.found:
        note("no tubes on the sizing grid hold every case: the strongest are used (see below)")
    return sized.design, sized


def tube_rows(structure: Structure, lengths: tuple[float, float, float]) -> list[tuple[str, str]]:
    """The material and what it allows, and each segment's tube and mass."""
    material = structure.material
    rows = [
        (
            "structure",
            f"{material.name}: {material.yield_strength / 1e6:.4g} MPa / safety factor "
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
