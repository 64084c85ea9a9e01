"""Walking: the torques, speeds, power and energy of a gait period, per design.

:class:`Gait` says what is walked (:mod:`.spec`, patterns in :mod:`.pattern`);
:func:`analyze_gait` measures one design walking it (:mod:`.analysis`): foot paths and
joint motion (:mod:`.trajectory`), constraints (:mod:`.feasibility`), inverse dynamics
and the feet's forces (:mod:`.dynamics`), the ZMP (:mod:`.stability`), the metrics
(:mod:`.metrics`), and the max stride and max speed (:mod:`.limits`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

__all__ = [
    "GROUPS",
    "Gait",
    "GaitAnalysis",
    "GaitMetrics",
    "Slip",
    "SpeedLimit",
    "StrideLimit",
    "Violation",
    "Walker",
    "analyze_gait",
    "duty_factor",
    "gait_phases",
    "legs_around",
    "max_speed",
    "max_stride",
]

__getattr__, __dir__ = lazy_exports(__name__)

if TYPE_CHECKING:  # where each name is from: read by type checkers, the docs and lazy_exports
    from hexaleg.gait.analysis import GaitAnalysis, analyze_gait
    from hexaleg.gait.feasibility import Violation
    from hexaleg.gait.friction import Slip
    from hexaleg.gait.limits import SpeedLimit, StrideLimit, max_speed, max_stride
    from hexaleg.gait.metrics import GaitMetrics
    from hexaleg.gait.pattern import GROUPS, duty_factor, gait_phases, legs_around
    from hexaleg.gait.spec import Gait
    from hexaleg.gait.walk import Walker
