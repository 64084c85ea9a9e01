"""The legs' tubes sized for what the robot must do: the requirements' payload and slope.

A design whose ``[structure]`` says ``size = true`` has its tubes chosen before it is
measured: the lightest on the sizing grid (:func:`~hexaleg.structure.sizing.size_structure`)
that hold the nominal stance, the twelve extremes and the required slope, carrying the
required payload. The commands that measure the tubes size them so
(:func:`hexaleg.evaluation.inputs.resolve_inputs`' ``sizing``).
"""

from __future__ import annotations

import warnings

from hexaleg.design import HexapodDesign
from hexaleg.evaluation.requirement_specs import SLOPE
from hexaleg.evaluation.requirements import Requirements
from hexaleg.statics.forces import Payload
from hexaleg.structure.sizing import SizedStructure, SizingWarning, size_structure

__all__ = ["NOT_FOUND", "sized_for"]

NOT_FOUND = "no tubes on the sizing grid hold every case: the strongest are used"
"""What sizing says when no tubes of its grid hold (the structure's rows show by how much)."""


def sized_for(design: HexapodDesign, requirements: Requirements) -> SizedStructure | None:
    """``design``'s tubes sized if its ``[structure]`` says ``size = true``; else ``None``.

    The lightest on the sizing grid that hold the nominal stance, the twelve extremes and the
    required slope, carrying the required payload (``payload``, ``payload_at`` and ``slope``
    of ``requirements``; none if they give none). Warns (:class:`SizingWarning`) when no
    tubes of the grid hold every case: the strongest are then used.
    """
    structure = design.structure
    if structure is None or not structure.size:
        return None
    payload = Payload(requirements.payload_mass, requirements.payload_at)
    sized = size_structure(design, payload=payload, slope=requirements.required(SLOPE) or 0.0)
    if not sized.found:
        warnings.warn(NOT_FOUND, SizingWarning, stacklevel=2)
    return sized
