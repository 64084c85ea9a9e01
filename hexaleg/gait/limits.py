"""How far and how fast a design can walk a gait: its max stride and its max speed.

- Max stride: the largest S (at the gait's step height, pattern, heading and the design's
  posture) for which the period is feasible (:mod:`hexaleg.gait.feasibility`). Joint
  angles depend on the phase only, not on the period, so neither does the max stride. It
  is the first crossing from S = 0 (:func:`~hexaleg.numerics.bracketing.first_crossings`):
  strides are scanned up to one no foot reaches (:func:`_out_of_reach`), and each
  constraint that breaks in the first broken bracket is solved on its own worst sample's
  margin to :data:`STRIDE_TOLERANCE`.
- Max speed: the largest v = S/(β·T) at which every joint's peak |τ| and |q̇| stays within
  its rating and the period is feasible, at the gait's stride (a shorter period) or at the
  max stride, whichever is faster. With minimum-norm forces every torque is τ_s + τ_i/T²
  and every speed θ'/T exactly, so the shortest period is solved joint by joint in closed
  form; min-torque forces are bisected on 1/T² to :data:`SPEED_TOLERANCE`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.cause import Cause
from hexaleg.gait.feasibility import TOLERANCE, feasible, leg_causes
from hexaleg.gait.walk import Loads, Stride, Walker
from hexaleg.kinematics import leg_solution
from hexaleg.numerics.bracketing import first_crossings
from hexaleg.robot.model import LEG_JOINTS

STRIDE_TOLERANCE = 1e-9
"""Width of the max stride's final bracket [m]: the value is feasible, value + this is not."""
SPEED_TOLERANCE = 1e-6
"""Relative width of the final bracket of a min-torque max speed, on 1/T² [-]."""
SCAN_STEPS = 32
"""Strides scanned up to where no foot reaches (10 cm apart for a 1 m leg) before refining."""
SCAN_CHUNKS = 4
"""The scan runs in this many rounds of strides tried at once, stopping at the first break."""


@dataclass(frozen=True)
class StrideLimit:
    """The largest feasible stride.

    Attributes:
        value: S_max [m] (0 if even a stride of :data:`STRIDE_TOLERANCE` breaks a constraint).
        limited_by: The constraint that breaks just beyond it.

    """

    value: float
    limited_by: Cause

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: ``value`` [m] and what limits it."""
        return {"value": self.value, "limited_by": self.limited_by.to_dict()}


@dataclass(frozen=True)
class SpeedLimit:
    """The fastest the design walks the gait's pattern within its ratings.

    Attributes:
        value: v_max [m/s] (0 if no period works).
        stride: The stride it is reached at [m].
        period: The period it is reached at [s] (infinite if v_max = 0).
        limited_by: What binds there: a joint's torque or speed at its rating, or the
            constraint that makes the period infeasible.

    """

    value: float
    stride: float
    period: float
    limited_by: Cause

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form: ``value`` [m/s] and what limits it."""
        return {"value": self.value, "limited_by": self.limited_by.to_dict()}


def max_stride(walker: Walker) -> StrideLimit:
    """The largest feasible stride of ``walker``'s gait (see the module docstring)."""
    if not feasible(_margins(walker, np.array([0.0]))).all():
        return StrideLimit(0.0, _first_cause(walker, 0.0))

    def worst(_: ArrayF, strides: ArrayF) -> ArrayF:  # broken below −TOLERANCE
        every = _margins(walker, strides) + TOLERANCE
        return every.reshape(len(strides), -1).min(axis=1, keepdims=True)

    reach = _out_of_reach(walker)
    found = first_crossings(
        worst, np.array([reach]), SCAN_STEPS, SCAN_CHUNKS, STRIDE_TOLERANCE / reach, False
    )
    if found.which[0] < 0:
        return StrideLimit(reach, Cause("range"))
    value = float(found.t[0])
    return StrideLimit(value, _first_cause(walker, value + STRIDE_TOLERANCE))


def _out_of_reach(walker: Walker) -> float:
    """A stride [m] no gait reaches: a standing foot ends S/2 from its nominal foothold, at
    least S/2 − d from its leg's root (d the foothold's distance from the root), which
    must stay within l1 + l2 + l3; the leg nearest its foothold bounds S by 2·(d + l)."""
    frames = walker.frames
    offsets = np.linalg.norm(frames.footholds - frames.root_positions, axis=1)
    return float(2.0 * (offsets.min() + sum(frames.lengths)))


def _margins(walker: Walker, strides: ArrayF) -> ArrayF:
    """Every constraint's margin (M, N, 6, 9) at each stride, the joint angles of all at once."""
    shapes, frames = walker.shapes, walker.frames
    along = strides[:, None, None, None] * shapes.along[None, ..., None] * walker.heading
    lift = walker.gait.step_height * shapes.lift[..., None] * np.array([0.0, 0.0, 1.0])
    angles, reach = leg_solution(frames.lengths, frames.to_roots(frames.footholds + along + lift))
    return walker.margins(angles, reach)


def _feasible(walker: Walker, strides: ArrayF) -> ArrayF:
    """Whether each stride's period is feasible (M,)."""
    return feasible(_margins(walker, strides))


def _first_cause(walker: Walker, stride: float) -> Cause:
    """The first constraint, in leg and constraint order, that stride S [m] breaks anywhere."""
    margins = _margins(walker, np.array([stride]))[0]  # (N, 6, 9)
    broken = (margins < -TOLERANCE).any(axis=0).ravel()
    if not broken.any():
        return Cause("range")
    causes = [cause for leg in walker.frames.legs for cause in leg_causes(leg)]
    return causes[int(np.argmax(broken))]


def max_speed(
    walker: Walker,
    stride_limit: StrideLimit | None = None,
    at_gait_stride: tuple[Stride, Loads] | None = None,
) -> SpeedLimit:
    """The fastest feasible walk within the ratings, at the gait's stride or the max stride.

    Args:
        walker: The robot and its gait.
        stride_limit: The gait's max stride, if already known.
        at_gait_stride: The motion and min-norm loads at the gait's stride, if already known.

    """
    stride_limit = max_stride(walker) if stride_limit is None else stride_limit
    best = _speed_at(walker, walker.gait.stride, at_gait_stride)
    if 0 < stride_limit.value != walker.gait.stride:
        best = max(best, _speed_at(walker, stride_limit.value, None, best.value), key=_value)
    return best


def _value(limit: SpeedLimit) -> float:
    return limit.value


def _speed_at(
    walker: Walker, stride: float, known: tuple[Stride, Loads] | None, beat: float = 0.0
) -> SpeedLimit:
    """The speed limit at stride S [m]; the torques are skipped if the speed ratings alone
    keep it at or below ``beat`` [m/s]."""
    walk = walker.stride(stride) if known is None else known[0]
    found = walker.violations(walk)
    if found:
        return SpeedLimit(0.0, stride, float("inf"), found[0].cause)
    speed_room = _speed_room(walker, walk)
    by_speed = _limit(walker, stride, np.full_like(speed_room, np.inf), speed_room)
    if by_speed.value <= beat:
        return by_speed
    if walker.distribution != "min-norm":
        return _bisected_speed(walker, stride, walk, speed_room)
    loads = walker.loads(stride, walk, 1.0) if known is None else known[1]
    return _closed_form_speed(walker, stride, loads, speed_room)


def _speed_room(walker: Walker, walk: Stride) -> ArrayF:
    """Each joint's largest w = 1/T² with |θ'|·√w ≤ q̇_rated (N, 6, 3) [1/s²]."""
    _, rated_speed = walker.rated()
    with np.errstate(divide="ignore", invalid="ignore"):
        return (rated_speed / np.abs(walk.motion.velocity)) ** 2


def _closed_form_speed(
    walker: Walker, stride: float, loads: Loads, speed_room: ArrayF
) -> SpeedLimit:
    """Largest w = 1/T² with |τ_s + w·τ_i| ≤ τ_rated and |θ'|·√w ≤ q̇_rated, joint by joint."""
    rated_torque, _ = walker.rated()
    static, inertial = loads.split.static_torques, loads.split.inertial_torques
    with np.errstate(divide="ignore", invalid="ignore"):
        room = np.where(
            inertial > 0, (rated_torque - static) / inertial, (rated_torque + static) / -inertial
        )
    room = np.where(inertial != 0, room, np.inf)
    room = np.where(np.abs(static) > rated_torque, 0.0, room)
    return _limit(walker, stride, room, speed_room)


def _limit(walker: Walker, stride: float, torque_room: ArrayF, speed_room: ArrayF) -> SpeedLimit:
    """The speed limit from each joint's largest w = 1/T² (N, 6, 3) by torque and by speed."""
    rooms = np.nan_to_num(np.stack((torque_room, speed_room)), nan=0.0)  # (2, N, 6, 3)
    index = np.unravel_index(int(np.argmin(rooms)), rooms.shape)
    w = max(float(rooms[index]), 0.0)
    kind = "torque" if index[0] == 0 else "speed"
    cause = Cause(kind, walker.frames.legs[int(index[2])], LEG_JOINTS[int(index[3])])
    period = float("inf") if w == 0 else float(1.0 / np.sqrt(w))
    return SpeedLimit(float(stride * np.sqrt(w) / walker.phases.duty_factor), stride, period, cause)


def _bisected_speed(walker: Walker, stride: float, walk: Stride, speed_room: ArrayF) -> SpeedLimit:
    """Min-torque forces: bisect w = 1/T² between 0 and the speed ratings' bound."""
    rated_torque, _ = walker.rated()
    bound = float(np.nan_to_num(np.min(speed_room), nan=0.0))

    def ratios(w: float) -> ArrayF:
        period = float("inf") if w == 0 else 1.0 / np.sqrt(w)
        return np.abs(walker.loads(stride, walk, period).split.torques(period)) / rated_torque

    if ratios(bound).max() <= 1:
        return _limit(walker, stride, np.full_like(speed_room, np.inf), speed_room)
    low, high = 0.0, bound
    if ratios(low).max() > 1:
        high = 0.0
    while high - low > SPEED_TOLERANCE * bound:
        middle = 0.5 * (low + high)
        low, high = (middle, high) if ratios(middle).max() <= 1 else (low, middle)
    beyond = ratios(high)
    room = np.where(beyond >= beyond.max(), low, np.inf)  # the joint that breaks first
    return _limit(walker, stride, room, np.full_like(speed_room, np.inf))
