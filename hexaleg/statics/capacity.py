"""Payload capacity: the largest payload the nominal stance holds within ratings, upright."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF, Distribution
from hexaleg.cause import Cause
from hexaleg.exceptions import HexalegError
from hexaleg.limits import LEG_JOINTS
from hexaleg.statics.forces import PAYLOAD_SEARCH_LIMIT, Statics, StaticState
from hexaleg.statics.support import Tipping


@dataclass(frozen=True)
class PayloadCapacity:
    """The largest payload the robot holds at its nominal stance.

    Attributes:
        mass: The payload [kg].
        limited_by: What binds: a joint's torque at its rating (kind ``"torque"``, with
            its leg and joint), ``"stability"`` (the centre of mass leaves the support
            polygon), or ``"search limit"`` if nothing binds below
            :data:`PAYLOAD_SEARCH_LIMIT`.

    """

    mass: float
    limited_by: Cause


STABILITY = Cause("stability")
SEARCH_LIMIT = Cause("search limit")


def payload_capacity(
    statics: Statics,
    q: npt.ArrayLike,
    distribution: Distribution = "min-norm",
    at: StaticState | None = None,
) -> PayloadCapacity:
    """The largest payload at the statics' payload point that the nominal stance holds.

    Every stance joint's |τ| must stay within its rating and the stability margin
    positive. With min-norm forces every torque is affine in the payload (the six
    equilibrium equations about a fixed point are affine in it), so each joint's limit
    is solved exactly; min-torque forces are found by bisection, to 1e-6 relative.

    Args:
        statics: The robot on its stance legs, with the payload's point.
        q: The stance configuration (the nominal one).
        distribution: ``"min-norm"`` or ``"min-torque"``.
        at: ``statics.state(q)`` if already computed (saves one evaluation).

    """
    if distribution == "min-norm":
        return _affine_capacity(statics, q, at)

    def check(mass: float) -> tuple[bool, Cause]:
        try:
            state = statics.state(q, distribution, payload=statics.payload.with_mass(mass))
        except HexalegError:
            return False, STABILITY
        ratios = state.torque_ratios(statics.rated)
        if ratios.max() > 1.0:
            return False, _torque_cause(statics, *first_lowest(-ratios))
        if state.stability_margin <= 0:
            return False, STABILITY
        return True, SEARCH_LIMIT

    ok, cause = check(0.0)
    if not ok:
        return PayloadCapacity(0.0, cause)
    ok, cause = check(PAYLOAD_SEARCH_LIMIT)
    if ok:
        return PayloadCapacity(PAYLOAD_SEARCH_LIMIT, SEARCH_LIMIT)
    lo, hi = 0.0, PAYLOAD_SEARCH_LIMIT
    while hi - lo > 1e-6 * max(hi, 1.0):
        mid = 0.5 * (lo + hi)
        ok, why = check(mid)
        if ok:
            lo = mid
        else:
            hi, cause = mid, why
    return PayloadCapacity(lo, cause)


def _affine_capacity(statics: Statics, q: npt.ArrayLike, at: StaticState | None) -> PayloadCapacity:
    """Payload capacity with min-norm forces: τ(m) = τ(0) + m·τ1, solved joint by joint.

    Two evaluations fix the line (the payload's own state and one kilogram more or
    less); the centre of mass moves along the segment from the robot's own toward the
    payload's point.
    """
    m0 = statics.payload.mass
    at = statics.state(q) if at is None else at
    m1 = m0 + 1.0 if m0 + 1.0 <= PAYLOAD_SEARCH_LIMIT else m0 - 1.0
    other = statics.state(q, payload=statics.payload.with_mass(m1))
    slope = (other.joint_torques - at.joint_torques) / (m1 - m0)
    base = at.joint_torques - m0 * slope
    point = (other.com * other.mass - at.com * at.mass) / (m1 - m0)  # the payload's place
    robot_mass = at.mass - m0
    robot_com = (at.com * at.mass - m0 * point) / robot_mass
    rated = np.broadcast_to(statics.rated, base.shape)
    support = statics.support
    if np.any(np.abs(base) > rated) or support.signed_distance(robot_com) <= 0:
        ratios = np.abs(base) / rated
        cause = STABILITY if ratios.max() <= 1 else _torque_cause(statics, *first_lowest(-ratios))
        return PayloadCapacity(0.0, cause)
    with np.errstate(divide="ignore", invalid="ignore"):  # slope 0: that joint never binds
        limit = np.where(slope > 0, (rated - base) / slope, (-rated - base) / slope)
    limit = np.where(np.abs(slope) > 0, limit, np.inf)
    leg, joint = first_lowest(limit)
    mass, cause = float(limit[leg, joint]), _torque_cause(statics, leg, joint)
    tipping = Tipping(robot_mass, robot_com, point, support).payload()
    if tipping < mass:
        mass, cause = tipping, STABILITY
    if mass >= PAYLOAD_SEARCH_LIMIT:
        return PayloadCapacity(PAYLOAD_SEARCH_LIMIT, SEARCH_LIMIT)
    return PayloadCapacity(mass, cause)


def _torque_cause(statics: Statics, leg: int, joint: int) -> Cause:
    """Stance leg ``leg``'s joint ``joint`` (indices) at its rated torque."""
    return Cause("torque", statics.legs[leg], LEG_JOINTS[joint])


def first_lowest(values: ArrayF, tolerance: float = 1e-9) -> tuple[int, int]:
    """(leg, joint) of the smallest value, the first in leg order among near-equal ones.

    Mirror-image legs tie, and round-off must not choose between them.
    """
    leg, joint = np.unravel_index(first_lowest_index(values, tolerance), values.shape)
    return int(leg), int(joint)


def first_lowest_index(values: ArrayF, tolerance: float = 1e-9) -> int:
    """The flat index of the smallest value, the first (C order) among near-equal ones.

    Within ``tolerance`` of it (relative, at least absolute) a value ties: mirror-image
    legs do, and the order of the axes decides between them, never round-off.
    """
    flat = values.ravel()
    lowest = float(flat.min())
    slack = tolerance * max(1.0, abs(lowest)) if math.isfinite(lowest) else 0.0
    return int(np.flatnonzero(flat <= lowest + slack)[0])
