"""How far and how fast a design can walk a gait: its max stride and its max speed.

- Max stride: the largest S (at the gait's step height, pattern, heading and the design's
  posture) for which the period's motion is feasible (:mod:`hexaleg.gait.feasibility`:
  reach, joint limits, the ground; the ZMP, which depends on the period and the payload,
  bounds the max speed and the walking payload capacity instead). Joint
  angles depend on the phase only, not on the period, so neither does the max stride. It
  is the first crossing from S = 0 (:func:`~hexaleg.numerics.bracketing.first_crossings`):
  strides are scanned up to one no foot reaches (:func:`_out_of_reach`), and each
  constraint that breaks in the first broken bracket is solved on its own worst sample's
  margin to :data:`STRIDE_TOLERANCE`. A design with actuators also keeps every joint
  within its actuator's every rating at the gait's period (peak and RMS torque, voltage,
  speed: :mod:`hexaleg.electrical.ratings`, what makes its period feasible): below that
  stride, the largest ratio of value to rating is scanned at :data:`SCAN_STEPS` strides
  and its first crossing of 1 bisected to :data:`STRIDE_TOLERANCE`; the rating that
  binds is named (e.g. "hip continuous torque"), unless it binds within
  :data:`REACH_SHARE` of a stride where a foot runs out of
  reach (that reach is named).
- Max speed: the largest v = S/(β·T) at which every joint's peak |τ| and |q̇| stays within
  its rating, the zero-moment point within the standing feet's polygon (each edge's side is
  affine in 1/T², :func:`~hexaleg.gait.stability.zmp_sides`: solved in closed form,
  ``"zmp"`` when it binds), every standing foot's force within the friction cone (|f_t| ≤
  μ·f_n with f = f_s + f_i/T²: the end of an interval of 1/T², a root of a quadratic,
  :func:`~hexaleg.gait.friction.cone_limit`; ``"slide"`` with the foot's leg when it binds)
  and the period is feasible: a shorter period at the gait's stride S, or, if that stride is
  infeasible, at the max stride. (Not the faster of the two: at a max stride bound by reach
  a leg straightens, its joint speeds are unbounded and the speed there is zero; the search
  would cost more than the walk.) With minimum-norm forces every torque is τ_s + τ_i/T² and
  every speed θ'/T exactly, so the shortest period is solved joint by joint in closed form;
  min-torque forces are bisected on 1/T² to :data:`SPEED_TOLERANCE` (their grip too). On a
  slope gravity is tilted in the body frame (:class:`~hexaleg.statics.ground.Ground`), and
  the ratings are divided by the walker's safety factor F
  (:meth:`~hexaleg.gait.walk.Walker.rated`). A design with actuators also keeps every
  joint's RMS torque within its continuous torque and the voltage its motor needs within the
  bus voltage (:mod:`hexaleg.electrical`): below the speed the peaks allow, 1/T² is bisected
  on the larger of those two ratios.

The actuators' ratings lower the limits of the motion and of the peaks last
(:func:`stride_within_motors`, :func:`speed_within_motors`): a design with ``[actuators]``
keeps every joint within every rating of its actuator (:mod:`hexaleg.electrical.ratings`:
peak and RMS torque, the voltage its motor needs, speed) at the gait's period for its max
stride, and within its continuous torque and voltage below the speed the peaks allow for
its max speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg._typing import ArrayF, CauseKind
from hexaleg.cause import Cause
from hexaleg.electrical.ratings import RATED, RatingLoads, motor_loads
from hexaleg.gait.dynamics import GeneralizedForces
from hexaleg.gait.feasibility import TOLERANCE, feasible, leg_causes
from hexaleg.gait.friction import cone_limit, friction_ratios
from hexaleg.gait.walk import Loads, Stride, Walker
from hexaleg.kinematics import leg_solution
from hexaleg.limits import LEG_JOINTS
from hexaleg.numerics.bracketing import TIE_TOLERANCE, IndexArray, first_crossings

STRIDE_TOLERANCE = 1e-9
"""Width of the max stride's final bracket [m]: the value is feasible, value + this is not."""
SPEED_TOLERANCE = 1e-6
"""Relative width of the final bracket of a min-torque max speed, on 1/T² [-]."""


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

SCAN_STEPS = 32
"""Strides scanned up to where no foot reaches (10 cm apart for a 1 m leg) before refining."""
SCAN_CHUNKS = 4
"""The scan runs in this many rounds of strides tried at once, stopping at the first break."""
SCAN_SAMPLES = 20_000
"""Most stride-samples whose margins are held at once (strides × samples per period): the
scan's memory stays bounded at any sampling, and is all at once at the default 200."""


def max_stride(walker: Walker) -> StrideLimit:
    """The largest feasible stride of ``walker``'s gait (see the module docstring)."""
    return stride_within_motors(walker, _walkable_stride(walker), SCAN_STEPS)


def _walkable_stride(walker: Walker) -> StrideLimit:
    """The largest stride that breaks no constraint of the motion (reach, limits, ground)."""
    if not feasible(_margins(walker, np.array([0.0]))).all():
        return StrideLimit(0.0, _first_cause(walker, 0.0))

    def worst(_: IndexArray, strides: ArrayF) -> ArrayF:  # broken below −TOLERANCE
        # a few strides at a time: the margins of all of them at every sample at once would
        # take memory in proportion to both
        group = max(1, SCAN_SAMPLES // walker.gait.samples)
        smallest = [
            _margins(walker, part).reshape(len(part), -1).min(axis=1)
            for part in np.split(strides, range(group, len(strides), group))
        ]
        return np.concatenate(smallest)[:, None] + TOLERANCE

    reach = _out_of_reach(walker)
    found = first_crossings(
        worst, np.array([reach]), SCAN_STEPS, SCAN_CHUNKS, STRIDE_TOLERANCE / reach, False
    )
    if found.which[0] < 0:
        return StrideLimit(reach, Cause("range"))
    value = float(found.t[0])
    return StrideLimit(value, _first_cause(walker, value + STRIDE_TOLERANCE))


def _out_of_reach(walker: Walker) -> float:
    """A stride [m] no gait reaches.

    A standing foot ends S/2 from its nominal foothold, at least S/2 − d from its leg's
    root (d the foothold's distance from the root), which must stay within the leg's
    reach l = a1 + l2 + l3 + |h| + |e|: the leg nearest its foothold bounds S by 2·(d + l).
    """
    frames = walker.frames
    offsets = np.linalg.norm(frames.footholds - frames.root_positions, axis=1)
    reach = np.abs(frames.parameters).sum(axis=1)
    return float(2.0 * (offsets + reach).min())


def _margins(walker: Walker, strides: ArrayF) -> ArrayF:
    """Every constraint's margin (M, N, 6, 9) at each stride, the joint angles of all at once."""
    shapes, frames = walker.shapes, walker.frames
    along = strides[:, None, None, None] * shapes.along[None, ..., None] * walker.heading
    lift = walker.gait.step_height * shapes.lift[..., None] * np.array([0.0, 0.0, 1.0])
    targets = frames.to_roots(frames.footholds + along + lift)
    angles, reach = leg_solution(frames.parameters, targets)
    return walker.margins(angles, reach)


def _first_cause(walker: Walker, stride: float) -> Cause:
    """The first constraint, in leg and constraint order, that stride S [m] breaks anywhere.

    None broken yet (a margin that leaves zero tangentially, a hair past the max stride):
    the one nearest its bound.
    """
    margins = _margins(walker, np.array([stride]))[0].min(axis=0).ravel()  # (6·9,)
    broken = margins < -TOLERANCE
    causes = [cause for leg in walker.frames.legs for cause in leg_causes(leg)]
    return causes[int(np.argmax(broken) if broken.any() else np.argmin(margins))]


def max_speed(
    walker: Walker,
    stride_limit: StrideLimit | None = None,
    at_gait_stride: tuple[Stride, Loads] | None = None,
    fallback: bool = True,
) -> SpeedLimit:
    """The fastest walk within the ratings, at the gait's stride or at the max stride.

    The max stride only if the gait's own stride is infeasible (see the module docstring).

    Args:
        walker: The robot and its gait.
        stride_limit: The gait's max stride, if already known (needed only when the
            gait's own stride is infeasible).
        at_gait_stride: The motion and min-norm loads at the gait's stride, if already known.
        fallback: Walk the max stride when the gait's stride is infeasible; if false, the
            speed is then zero, limited by the stride's first violation.

    """
    stride = walker.gait.stride
    walk = walker.stride(stride) if at_gait_stride is None else at_gait_stride[0]
    found = walk.violations
    if found and not fallback:
        return SpeedLimit(0.0, stride, math.inf, found[0].cause)
    if found:
        stride_limit = max_stride(walker) if stride_limit is None else stride_limit
        if stride_limit.value == 0:
            return SpeedLimit(0.0, stride, math.inf, found[0].cause)
        stride, walk, at_gait_stride = stride_limit.value, walker.stride(stride_limit.value), None
        found = walk.violations
        if found:  # the max stride is feasible by construction; kept for round-off
            return SpeedLimit(0.0, stride, math.inf, found[0].cause)
    speed_room = _speed_room(walker, walk)
    known = None if at_gait_stride is None else at_gait_stride[1]
    rnea = walker.generalized_forces(stride, walk) if known is None else known.rnea
    upright = _zmp_room(walker, walk, rnea)
    if upright < 0:  # the ZMP is outside even walking infinitely slowly
        return SpeedLimit(0.0, stride, math.inf, Cause("zmp"))
    if walker.distribution != "min-norm":
        limit = _bisected_speed(walker, stride, walk, speed_room, rnea, upright)
        limit = _bisected_grip(walker, walk, rnea, _upright(walker, limit, upright))
        return speed_within_motors(walker, walk, limit)
    loads = walker.loads(stride, walk, 1.0, rnea) if known is None else known
    limit = _upright(walker, _closed_form_speed(walker, stride, loads, speed_room), upright)
    return speed_within_motors(walker, walk, _gripping(walker, loads, limit), loads)


def _zmp_room(walker: Walker, walk: Stride, rnea: GeneralizedForces) -> float:
    """The largest w = 1/T² keeping the ZMP inside the standing feet's polygon (< 0: none).

    Each edge's F_z·cross(edge, ZMP − vertex) is affine in w
    (:meth:`~hexaleg.gait.walk.Walker.zmp_sides`): the largest w keeping all ≥ 0 is exact.
    """
    static, inertial = walker.zmp_sides(walk, rnea)
    if (static < 0).any():
        return -1.0
    shrinking = inertial < 0
    return float((static[shrinking] / -inertial[shrinking]).min()) if shrinking.any() else math.inf


def _upright(walker: Walker, limit: SpeedLimit, room: float) -> SpeedLimit:
    """``limit``, or the slower one at w = ``room`` where the ZMP reaches the polygon's edge."""
    return _slower(walker, limit, room, Cause("zmp"))


def _slower(walker: Walker, limit: SpeedLimit, room: float, cause: Cause) -> SpeedLimit:
    """``limit``, or the slower one at w = 1/T² = ``room`` (≥ 0), where ``cause`` binds."""
    if room >= 1.0 / limit.period**2:
        return limit
    value = limit.stride * math.sqrt(room) / walker.phases.duty_factor
    period = math.inf if room == 0 else 1.0 / math.sqrt(room)
    return SpeedLimit(float(value), limit.stride, period, cause)


def _gripping(walker: Walker, loads: Loads, limit: SpeedLimit) -> SpeedLimit:
    """``limit``, or the slower one where a standing foot's force reaches the friction cone.

    Min-norm forces are f_s + w·f_i (w = 1/T²): the cone bounds w in closed form.
    """
    split, legs = loads.split, walker.frames.legs
    found = cone_limit(
        split.static_forces, split.inertial_forces, walker.phases.stance, walker.friction
    )
    if found is None:
        return limit
    room, index = found
    return _slower(walker, limit, max(room, 0.0), Cause("slide", legs[index % len(legs)]))


def _bisected_grip(
    walker: Walker, walk: Stride, rnea: GeneralizedForces, limit: SpeedLimit
) -> SpeedLimit:
    """Min-torque forces: ``limit``, or the slower one (bisected on w = 1/T²) that grips."""
    stance, legs = walker.phases.stance, walker.frames.legs

    def worst(w: float) -> tuple[float, int]:  # the largest |f_t|/(μ f_n), and its foot
        period = math.inf if w == 0 else 1.0 / math.sqrt(w)
        forces = walker.loads(limit.stride, walk, period, rnea).split.forces(period)
        ratios = friction_ratios(forces, stance) / walker.friction
        return float(ratios.max()), int(np.argmax(ratios))

    high = 0.0 if math.isinf(limit.period) else 1.0 / limit.period**2
    if worst(high)[0] <= 1:
        return limit
    low = 0.0
    if worst(low)[0] > 1:
        return _slower(walker, limit, 0.0, Cause("slide", legs[worst(low)[1] % len(legs)]))
    while high - low > SPEED_TOLERANCE * high:
        middle = 0.5 * (low + high)
        low, high = (middle, high) if worst(middle)[0] <= 1 else (low, middle)
    return _slower(walker, limit, low, Cause("slide", legs[worst(high)[1] % len(legs)]))


def _speed_room(walker: Walker, walk: Stride) -> ArrayF:
    """Each joint's largest w = 1/T² with |θ'|·√w ≤ q̇_rated (N, 6, 3) [1/s²]."""
    _, rated_speed = walker.rated()
    with np.errstate(divide="ignore", invalid="ignore"):
        return (rated_speed / np.abs(walk.motion.velocity)) ** 2


def _closed_form_speed(
    walker: Walker, stride: float, loads: Loads, speed_room: ArrayF
) -> SpeedLimit:
    """Largest w = 1/T² with |τ_s + w·τ_i| ≤ τ_rated and |θ'|·√w ≤ q̇_rated, joint by joint."""
    static, inertial = loads.split.static_torques, loads.split.inertial_torques
    rated = np.tile(walker.rated()[0], (*static.shape[:-1], 1))  # each joint's, every sample
    with np.errstate(divide="ignore", invalid="ignore"):
        room = np.where(inertial > 0, (rated - static) / inertial, (rated + static) / -inertial)
    room = np.where(inertial != 0, room, np.inf)
    room = np.where(np.abs(static) > rated, 0.0, room)
    return _limit(walker, stride, room, speed_room)


def _limit(walker: Walker, stride: float, torque_room: ArrayF, speed_room: ArrayF) -> SpeedLimit:
    """The speed limit from each joint's largest w = 1/T² (N, 6, 3) by torque and by speed."""
    rooms = np.nan_to_num(np.stack((torque_room, speed_room)), copy=False, nan=0.0)
    rooms = rooms.transpose(0, 2, 3, 1)  # (kind, leg, joint, sample): ties go in leg order
    least = float(rooms.min())
    tied = rooms <= least + TIE_TOLERANCE * max(abs(least), 1e-300)  # mirror legs tie
    kind, leg, joint, _ = np.unravel_index(int(np.argmax(tied)), rooms.shape)
    w = max(least, 0.0)
    cause = Cause(("torque", "speed")[kind], walker.frames.legs[leg], LEG_JOINTS[joint])
    period = float("inf") if w == 0 else float(1.0 / np.sqrt(w))
    return SpeedLimit(float(stride * np.sqrt(w) / walker.phases.duty_factor), stride, period, cause)


def _bisected_speed(
    walker: Walker,
    stride: float,
    walk: Stride,
    speed_room: ArrayF,
    rnea: GeneralizedForces,
    upright: float,
) -> SpeedLimit:
    """Min-torque forces: bisect w = 1/T² between 0 and the speed ratings' bound.

    Never beyond ``upright``, the ZMP's bound on w: past it no foot forces hold the robot.
    """
    rated_torque, _ = walker.rated()
    bound = min(float(np.nan_to_num(np.min(speed_room), nan=0.0)), upright)

    def ratios(w: float) -> ArrayF:
        period = math.inf if w == 0 else 1.0 / math.sqrt(w)
        torques = walker.loads(stride, walk, period, rnea).split.torques(period)
        return np.abs(torques) / rated_torque

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
            torques,
            walk.motion.velocity * math.sqrt(w),
            actuators,
            legs,
            bus,
            walker.safety_factor,
        ).ratios
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
