"""Statics: what holding a pose costs — foot forces, joint torques, stability, slopes, payload.

:mod:`.forces` balances gravity with the stance feet's forces and gives the joint
torques; :mod:`.support` is the support polygon and the stability margin; :mod:`.slopes`
the steepest slope per heading; :mod:`.ground` the plane a gait walks on (slope,
friction); :mod:`.capacity` the largest payload; :mod:`.loads` gathers them at the nominal
stance and at each body extreme.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

__all__ = [
    "DEFAULT_FRICTION",
    "GRAVITY",
    "SLOPE_HEADINGS",
    "ExtremeLoads",
    "Ground",
    "LoadsAnalysis",
    "Payload",
    "PayloadCapacity",
    "SlopeLimit",
    "StaticState",
    "Statics",
    "SupportPolygon",
    "analyze_loads",
    "equilibrium",
    "extreme_configurations",
    "friction_pyramid",
    "ground_point",
    "loads_at_extremes",
    "payload_capacity",
    "slope_gravity",
    "slope_limits",
    "stability_margin",
]

__getattr__, __dir__ = lazy_exports(__name__)

if TYPE_CHECKING:  # where each name is from: read by type checkers, the docs and lazy_exports
    from hexaleg.gravity import GRAVITY, slope_gravity
    from hexaleg.stance.configurations import extreme_configurations
    from hexaleg.statics.capacity import PayloadCapacity, payload_capacity
    from hexaleg.statics.forces import (
        DEFAULT_FRICTION,
        Payload,
        Statics,
        StaticState,
        equilibrium,
        friction_pyramid,
    )
    from hexaleg.statics.ground import Ground
    from hexaleg.statics.loads import (
        ExtremeLoads,
        LoadsAnalysis,
        analyze_loads,
        loads_at_extremes,
    )
    from hexaleg.statics.slopes import SLOPE_HEADINGS, SlopeLimit, slope_limits
    from hexaleg.statics.support import SupportPolygon, ground_point, stability_margin
