"""The actuators' ratings as limits of a gait: the max stride and max speed they allow.

A design with ``[actuators]`` keeps every joint within every rating of its actuator
(:mod:`hexaleg.electrical.ratings`: peak and RMS torque, the voltage its motor needs,
speed) at the gait's period for its max stride, and within its continuous torque and
voltage below the speed the peaks allow for its max speed (:mod:`hexaleg.gait.limits`
finds the limits of the motion and of the peaks first; these functions only lower them).
"""

from __future__ import annotations

import math

import numpy as np

from hexaleg._typing import ArrayF, CauseKind
from hexaleg.cause import Cause
from hexaleg.electrical.ratings import RATED, RatingLoads, motor_loads
from hexaleg.gait.limit_results import SPEED_TOLERANCE, STRIDE_TOLERANCE, SpeedLimit, StrideLimit
from hexaleg.gait.walk import Loads, Stride, Walker
from hexaleg.limits import LEG_JOINTS

__all__ = ["REACH_SHARE", "speed_within_motors", "stride_within_motors"]

REACH_SHARE = 1e-4
"""A rating first exceeded this close (a share of it) below a max stride bound by reach is
the straightening leg's, whose joint speeds and torques grow without bound there: the
stride is the rating's, its cause stays the reach [-]."""

RATING_CAUSES: dict[str, CauseKind] = {
    "peak_torque": "torque",
    "continuous_torque": "continuous_torque",
    "voltage": "voltage",
    "speed": "speed",
}
"""The cause kind of each actuator rating (:data:`~hexaleg.electrical.ratings.RATED`)."""


def stride_within_motors(walker: Walker, limit: StrideLimit, scan_steps: int) -> StrideLimit:
    """``limit``, or the first stride below it whose period exceeds an actuator's rating.

    The ratio of value to rating is scanned at ``scan_steps`` strides below ``limit`` and
    its first crossing of 1 bisected to :data:`STRIDE_TOLERANCE`.
    """
    actuators = walker.model.design.actuators
    if actuators is None:
        return limit
    period, legs = walker.gait.period, walker.frames.legs
    bus = walker.model.design.bus_voltage

    def loads(stride: float) -> RatingLoads | None:  # None: a joint's speed is unbounded
        walk = walker.stride(stride)
        torques = walker.loads(stride, walk, period).split.torques(period)
        speeds = walk.motion.velocity / period
        if not (np.isfinite(torques).all() and np.isfinite(speeds).all()):
            return None  # a leg straight at the walkable max stride bound by reach
        return motor_loads(torques, speeds, actuators, legs, bus, walker.safety_factor)

    def over(stride: float) -> bool:
        found = loads(stride)
        return found is None or bool(found.ratios.max() > 1)

    if over(0.0):
        return StrideLimit(0.0, _rating_cause(loads(0.0), limit))
    low, high = 0.0, math.nan
    for stride in np.linspace(0.0, limit.value, scan_steps + 1)[1:]:
        if over(float(stride)):
            high = float(stride)
            break
        low = float(stride)
    if math.isnan(high):
        return limit
    while high - low > STRIDE_TOLERANCE:
        middle = 0.5 * (low + high)
        low, high = (middle, high) if not over(middle) else (low, middle)
    if limit.limited_by.kind == "reach" and limit.value - low <= REACH_SHARE * limit.value:
        return StrideLimit(low, limit.limited_by)  # the straightening leg's torques and speeds
    return StrideLimit(low, _rating_cause(loads(high), limit))


def _rating_cause(loads: RatingLoads | None, limit: StrideLimit) -> Cause:
    """The rating the period exceeds furthest, as a cause (e.g. a hip's continuous torque).

    ``limit``'s own cause when the joint speeds are unbounded there (a leg straight).
    """
    if loads is None:
        return limit.limited_by
    binds = loads.binding()
    return Cause(RATING_CAUSES[binds.quantity], binds.leg, binds.joint)


def speed_within_motors(
    walker: Walker, walk: Stride, limit: SpeedLimit, loads: Loads | None = None
) -> SpeedLimit:
    """``limit``, or a slower one that keeps RMS torques and voltages within the actuators'.

    Args:
        walker: The robot and its gait (its design's actuators, if any, are checked).
        walk: The motion at ``limit.stride``.
        limit: The speed limit of the peak torques and speeds.
        loads: The min-norm loads at that stride (τ = τ_s + τ_i/T²); min-torque forces
            are solved again at each period tried.

    """
    actuators = walker.model.design.actuators
    if actuators is None or limit.value == 0:
        return limit
    rnea = walker.generalized_forces(limit.stride, walk) if loads is None else None
    legs, bus = walker.frames.legs, walker.model.design.bus_voltage

    def ratios(w: float) -> ArrayF:  # (continuous, voltage) ratios (2, L, 3) at w = 1/T²
        if loads is not None:
            torques = loads.split.static_torques + w * loads.split.inertial_torques
        else:
            period = math.inf if w == 0 else 1.0 / math.sqrt(w)
            torques = walker.loads(limit.stride, walk, period, rnea).split.torques(period)
        found: ArrayF = motor_loads(
            torques, walk.motion.velocity * math.sqrt(w), actuators, legs, bus,
            walker.safety_factor,
        ).ratios  # fmt: skip
        return found[1:3]

    high = 1.0 / limit.period**2
    if ratios(high).max() <= 1:
        return limit
    low = 0.0
    if ratios(low).max() > 1:
        high = 0.0
    while high - low > SPEED_TOLERANCE * high:
        middle = 0.5 * (low + high)
        low, high = (middle, high) if ratios(middle).max() <= 1 else (low, middle)
    beyond = ratios(high if high > 0 else 0.0)
    kind, leg, joint = np.unravel_index(int(np.argmax(beyond)), beyond.shape)
    cause = Cause(RATED[1 + kind], legs[leg], LEG_JOINTS[joint])
    period = math.inf if low == 0 else 1.0 / math.sqrt(low)
    value = limit.stride * math.sqrt(low) / walker.phases.duty_factor
    return SpeedLimit(float(value), limit.stride, period, cause)
