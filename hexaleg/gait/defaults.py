"""The gait a robot walks when none is given: hexaleg's, or one sized to the robot.

:class:`~hexaleg.gait.spec.Gait`'s defaults (stride 0.3 m, step height 0.1 m, 0.3 m/s) are
sized for hexaleg's template, the paper's 1 m leg; a 0.2 m robot cannot take them. A model
whose default gait is its own (:attr:`~hexaleg.robot.model.HexapodModel.own_default_gait`:
a robot file's) walks one scaled to it instead, by the same proportions:

- step height H = :data:`STEP_PER_LEG` × its leg length L (the template's 0.1 m of 1 m);
- stride S = :data:`STRIDE_OF_MAX` × its max stride at that step height
  (:func:`~hexaleg.gait.limits.max_stride`: the template's 0.3 m is about 0.6 of its own);
- the default pattern and duty factor, and the body speed per leg length of the template,
  v = :data:`SPEED_PER_LEG` × L, which sets the period T = S / (β·v).

A design file's ``[gait]`` table (or the gait options) overrides it, key by key.
"""

from __future__ import annotations

from hexaleg.gait.limits import max_stride
from hexaleg.gait.spec import Gait
from hexaleg.gait.walk import Walker
from hexaleg.robot.model import HexapodModel

__all__ = ["SPEED_PER_LEG", "STEP_PER_LEG", "STRIDE_OF_MAX", "default_gait", "fitted_gait"]


STEP_PER_LEG = 0.1
"""Default step height over leg length [-]: the template's 0.1 m step of its 1 m leg."""

STRIDE_OF_MAX = 0.5
"""Default stride over the robot's max stride at its default step height [-]: half, so that
every leg keeps room inside its limits (the template's 0.3 m is 0.63 of its 0.47 m)."""

SPEED_PER_LEG = 0.3
"""Default body speed over leg length [1/s]: the template's 0.3 m/s on its 1 m leg."""

SCALED_SAMPLES = Gait().samples
"""Samples per period of a scaled gait: the default's."""


def default_gait(model: HexapodModel) -> Gait:
    """The gait ``model`` walks when none is given (see the module docstring).

    Hexaleg's :class:`Gait` for a model whose default gait is not its own (the template);
    else one scaled to it. If no stride at all walks at the scaled step height, the
    stride is :data:`SPEED_PER_LEG` × L, which ``gait`` then refuses, saying why.
    """
    if not model.own_default_gait:
        return Gait()
    leg = model.design.leg_length
    base = Gait()
    step = STEP_PER_LEG * leg
    probe = base.replace(step_height=step)
    longest = max_stride(Walker(model, probe)).value
    stride = STRIDE_OF_MAX * longest if longest > 0 else SPEED_PER_LEG * leg
    return probe.replace(stride=stride).with_speed(SPEED_PER_LEG * leg)


def fitted_gait(gait: Gait | None, model: HexapodModel) -> Gait:
    """``gait``, or :func:`default_gait` of ``model`` where it is not given.

    Not given: ``None``, or :class:`Gait`'s defaults (what a design file without a
    ``[gait]`` table reads as).
    """
    return default_gait(model) if gait is None or gait == Gait() else gait
