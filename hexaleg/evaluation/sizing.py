"""The legs' tubes sized for what the robot must do: its payload and the slope it stands on.

A design whose ``[structure]`` says ``size = true`` has its tubes chosen before it is
measured: the lightest on the sizing grid (:func:`~hexaleg.structure.sizing.size_structure`)
that hold the nominal stance, the twelve axis-locked extremes and every heading of the slope,
carrying the payload. :func:`size_tubes` is that choice, made the same way for whoever
measures the design: :func:`~hexaleg.evaluation.evaluate.evaluate` sizes every candidate of a
decision, a study, the report and the explorer for its conditions, and the single-design
commands size the design for the design file's requirements (:func:`sized_for`, the
``sizing`` of :func:`hexaleg.evaluation.inputs.resolve_inputs`), so a command run at a
decision's answer chooses the same tubes.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence

from hexaleg.design import HexapodDesign
from hexaleg.evaluation.requirement_specs import SLOPE
from hexaleg.evaluation.requirements import Requirements
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.extremes import Extreme
from hexaleg.statics.forces import Payload
from hexaleg.structure.sizing import SizedStructure, SizingWarning, size_structure

__all__ = ["NOT_FOUND", "sized_for", "size_tubes"]

NOT_FOUND = "no tubes on the sizing grid hold every case: the strongest are used"
"""What sizing says when no tubes of its grid hold (the structure's rows show by how much)."""


def size_tubes(
    design: HexapodDesign,
    payload: Payload,
    slope: float | None,
    *,
    model: HexapodModel | None = None,
    extremes: Sequence[Extreme] | None = None,
) -> SizedStructure | None:
    """``design``'s tubes sized if its ``[structure]`` says ``size = true``; else ``None``.

    Args:
        design: The design.
        payload: The payload carried in every standing case.
        slope: The slope stood on in every heading [rad] (``None``: level ground only).
        model: ``design``'s model (hexaleg's template), if already built or derived.
        extremes: Its axis-locked flexibility extremes with every leg standing, if found.

    """
    structure = design.structure
    if structure is None or not structure.size:
        return None
    return size_structure(
        design, payload=payload, slope=slope or 0.0, model=model, extremes=extremes
    )


def sized_for(design: HexapodDesign, requirements: Requirements) -> SizedStructure | None:
    """``design``'s tubes sized for ``requirements`` if its ``[structure]`` asks; else ``None``.

    Their payload (``payload`` at ``payload_at``) and ``slope`` (none if they give none), as
    a decision's conditions are. Warns (:class:`SizingWarning`) when no tubes of the grid
    hold every case: the strongest are then used.
    """
    payload = Payload(requirements.payload_mass, requirements.payload_at)
    sized = size_tubes(design, payload, requirements.required(SLOPE))
    if sized is not None and not sized.found:
        warnings.warn(NOT_FOUND, SizingWarning, stacklevel=2)
    return sized
