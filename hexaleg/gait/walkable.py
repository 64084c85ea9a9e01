"""Refusing a gait that cannot be walked, before anything is written or simulated."""

from __future__ import annotations

from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.gait.analysis import GaitAnalysis
from hexaleg.gait.limits import max_stride
from hexaleg.gait.walk import Walker
from hexaleg.robot.model import HexapodModel

__all__ = ["require_walkable"]


def require_walkable(analysis: GaitAnalysis, model: HexapodModel) -> None:
    """Raise a one-line error if the planned period breaks a constraint.

    A stride beyond the design's max stride is named as such, with the max stride as the
    valid range; a gait no stride makes walkable (too high a step, say) by its first
    violation. ``gait`` refuses such a period before writing anything, ``simulate``
    before simulating.

    Raises:
        ParameterError: ``stride`` beyond the design's max stride.
        HexalegError: The period breaks a constraint at any stride.

    """
    if analysis.walkable:
        return
    gait = analysis.gait
    limit = analysis.max_stride
    if limit is None:
        limit = max_stride(
            Walker(model, gait, analysis.payload, analysis.distribution, analysis.ground,
                   safety_factor=analysis.safety_factor)
        )  # fmt: skip
    if 0 < limit.value < gait.stride:  # at 0 no stride at all is walkable: say why
        raise ParameterError(
            "stride",
            gait.stride,
            f"must be at most {limit.value:.4g} [m], this design's max stride at step height "
            f"{gait.step_height:g} m (beyond it: {limit.limited_by})",
        )
    why = "" if limit.value > 0 else f" (no stride walks at step height {gait.step_height:g} m)"
    raise HexalegError(f"this design cannot walk the gait: {analysis.violations[0]}{why}")
