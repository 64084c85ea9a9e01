"""Stance phase: the body on planted feet — closed-chain kinematics and body flexibility (§6).

:mod:`.geometry` reads the stance from the model and solves the closed chain;
:mod:`.constraints` gives every constraint's margin (NumPy, the reference) and
:mod:`.margin_kernel` the same compiled; :mod:`.axis_locked` and :mod:`.free_coupled`
(with :mod:`.climb`, :mod:`.paths`, :mod:`.free_problem`) find the twelve extremes;
:mod:`.flexibility` is the front door.
"""

from hexaleg.cause import Cause
from hexaleg.stance.axis_locked import axis_locked_extremes, axis_locked_flexibility
from hexaleg.stance.constraints import AXES, DIRECTIONS, direction_poses, stance_margins
from hexaleg.stance.extremes import (
    Extreme,
    FlexibilityResult,
    FlexibilityWarning,
    SearchEvidence,
    flexibility_index,
)
from hexaleg.stance.flexibility import flexibility
from hexaleg.stance.free_coupled import free_flexibility
from hexaleg.stance.geometry import (
    StanceGeometry,
    mobility,
    rigid_fit,
    stance_configuration,
    stance_forward_kinematics,
    stance_inverse_kinematics,
    stance_legs,
)

__all__ = [
    "AXES",
    "DIRECTIONS",
    "Cause",
    "Extreme",
    "FlexibilityResult",
    "FlexibilityWarning",
    "SearchEvidence",
    "StanceGeometry",
    "axis_locked_extremes",
    "axis_locked_flexibility",
    "direction_poses",
    "flexibility",
    "flexibility_index",
    "free_flexibility",
    "mobility",
    "rigid_fit",
    "stance_configuration",
    "stance_forward_kinematics",
    "stance_inverse_kinematics",
    "stance_legs",
    "stance_margins",
]
