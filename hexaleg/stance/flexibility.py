"""Body flexibility with the feet planted (paper §6, eq 28–29): the front door of both modes.

``mode="axis"`` is the paper's ADAMS semantics (:mod:`hexaleg.stance.axis_locked`);
``mode="free"`` lets the other five coordinates move (:mod:`hexaleg.stance.free_coupled`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from hexaleg._typing import FlexibilityMode, StanceSet, require_choice
from hexaleg.design import HexapodDesign
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.axis_locked import axis_locked_flexibility
from hexaleg.stance.extremes import FlexibilityResult
from hexaleg.stance.free_coupled import free_flexibility


def flexibility(
    design: HexapodDesign,
    mode: FlexibilityMode = "axis",
    stance: StanceSet | Sequence[str] = "all",
    model: HexapodModel | None = None,
    *,
    collisions: bool = False,
    progress: Callable[[int, int], None] | None = None,
) -> FlexibilityResult:
    """Body flexibility of ``design``: ``mode`` is ``"axis"`` (axis-locked) or ``"free"``.

    With ``collisions``, the body also stops where two of the robot's own parts touch.
    ``progress`` is called ``(done, total)`` after each step of the free-coupled search
    (the axis-locked one is over in milliseconds).
    """
    if require_choice("mode", mode, FlexibilityMode) == "axis":
        return axis_locked_flexibility(design, stance, model, collisions=collisions)
    return free_flexibility(design, stance, model, collisions=collisions, progress=progress)
