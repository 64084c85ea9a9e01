"""What a simulated walk shows: distance, tilt, height, falls, tracking, slip, torques.

Pure NumPy over a recorded :class:`Trace`; no MuJoCo here. Every measure except
``fell`` covers the cycles after the first, t ∈ [T, cycles·T], so the start from
rest does not count; a fall counts wherever it happens.

- distance: the body's travel along the heading u (the body's heading at the start,
  in the world) over the measured cycles [m], against the planned v·T per cycle;
- roll and pitch: Pinocchio's rpy of the body's orientation (R = Rz·Ry·Rx) [rad];
  ``max_tilt`` is the larger of max |roll| and max |pitch|;
- fell: |roll| or |pitch| over :data:`FALL_TILT`, or the body below
  :data:`FALL_HEIGHT_SHARE` of its nominal height, at any time;
- tracking RMS: root mean square of q_ref − q over every leg joint and step [rad];
- slip: the largest horizontal distance a planned standing foot moves from where it
  stood when its stance began, over every stance interval [m];
- internal force: the largest force on a standing foot that the other standing feet's
  forces cancel — the feet pushed against (or away from) each other: each step's forces
  less the least forces giving the same resultant force and moment [N], over the steps
  where the feet touching the ground are the plan's standing feet (the plan's forces are
  the least ones: its internal force is zero);
- peak torque: the largest |τ| any servo applies, per joint type [N·m];
- over rating: each servo whose largest |τ| exceeds its rated torque, with when it peaks
  (:mod:`hexaleg.statics.ratings`, as ``loads`` and ``gait`` flag them).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy.spatial.transform import Rotation

from hexaleg._typing import ArrayF
from hexaleg.exceptions import HexalegError
from hexaleg.limits import LEG_JOINTS
from hexaleg.statics.forces import equilibrium
from hexaleg.statics.ratings import OverRating, at_times, over_rating_at

FALL_TILT = math.radians(30.0)
"""A body rolled or pitched further than this has fallen [rad]."""
FALL_HEIGHT_SHARE = 0.5
"""A body lower than this share of its nominal height has fallen [-]."""


@dataclass(frozen=True)
class Trace:
    """A simulated run, one row per simulation step (K steps, L legs).

    Attributes:
        time: Simulated time (K,) [s].
        base_position: Body origin (K, 3), world frame [m].
        base_quaternion: Body orientation (K, 4), (w, x, y, z), world frame.
        joint_angles: Leg joint angles (K, L, 3) [rad].
        reference: The plan's joint angles (K, L, 3) [rad].
        joint_torques: Servo torques (K, L, 3) [N·m].
        foot_positions: Foot frame origins (K, L, 3), world frame [m].
        standing: Whether the plan has each foot standing (K, L).
        foot_forces: The floor's force on each foot (K, L, 3), world frame [N], if recorded.

    """

    time: ArrayF
    base_position: ArrayF
    base_quaternion: ArrayF
    joint_angles: ArrayF
    reference: ArrayF
    joint_torques: ArrayF
    foot_positions: ArrayF
    standing: npt.NDArray[np.bool_]
    foot_forces: ArrayF | None = None

    def window(self, start: float) -> Trace:
        """The rows from time ``start`` [s] on."""
        return self.rows(self.time >= start - 1e-9)

    def rows(self, index: slice | npt.NDArray[np.bool_]) -> Trace:
        """The rows ``index`` selects (a slice or a mask over the steps)."""
        picked: dict[str, Any] = {}
        for name in self.__dataclass_fields__:
            value = getattr(self, name)
            picked[name] = None if value is None else value[index]
        return Trace(**picked)


@dataclass(frozen=True)
class WalkMetrics:
    """The measures of a simulated walk (see the module docstring).

    Attributes:
        planned_distance: v·T times the measured cycles [m].
        distance: Body travel along the heading over the measured cycles [m].
        max_roll: Largest |roll| [rad].
        max_pitch: Largest |pitch| [rad].
        min_height: Lowest body height above the ground [m].
        fell: Whether the robot fell at any time.
        tracking_rms: RMS joint tracking error [rad].
        slip: Largest standing-foot slip [m].
        peak_torque: Largest |τ| per joint type (root, hip, knee) [N·m].
        over_rating: Each servo whose largest |τ| exceeds its rated torque, leg then
            joint order, with the time of its peak.
        internal_force: Largest internal force between the standing feet [N] (NaN if
            the floor's forces were not recorded).

    """

    planned_distance: float
    distance: float
    max_roll: float
    max_pitch: float
    min_height: float
    fell: bool
    tracking_rms: float
    slip: float
    peak_torque: dict[str, float]
    over_rating: tuple[OverRating, ...]
    internal_force: float = math.nan

    @property
    def max_tilt(self) -> float:
        """The larger of max |roll| and max |pitch| [rad]."""
        return max(self.max_roll, self.max_pitch)

    @property
    def distance_ratio(self) -> float:
        """Distance travelled over distance planned [-]."""
        return self.distance / self.planned_distance if self.planned_distance > 0 else math.nan


def roll_pitch(quaternions: npt.ArrayLike) -> ArrayF:
    """Roll and pitch (K, 2) [rad] of orientations (K, 4) given as (w, x, y, z)."""
    wxyz = np.asarray(quaternions, dtype=float).reshape(-1, 4)
    # extrinsic x, y, z = Pinocchio's rpy; SciPy's quaternions are (x, y, z, w)
    angles = Rotation.from_quat(wxyz[:, [1, 2, 3, 0]]).as_euler("xyz")
    return np.asarray(angles[:, :2], dtype=float)


def fell(trace: Trace, nominal_height: float) -> bool:
    """Whether the body ever tilts past :data:`FALL_TILT` or sinks below half its height."""
    tilted = np.abs(roll_pitch(trace.base_quaternion)).max(initial=0.0) > FALL_TILT
    low = trace.base_position[:, 2].min(initial=math.inf) < FALL_HEIGHT_SHARE * nominal_height
    return bool(tilted or low)


def foot_slip(foot_xy: npt.ArrayLike, standing: npt.ArrayLike) -> float:
    """Largest distance a standing foot moves from where its stance began [m].

    Args:
        foot_xy: Horizontal foot positions (K, L, 2) [m].
        standing: Whether each foot stands (K, L); each run of True is one stance.

    """
    mask = np.asarray(standing, dtype=bool)
    worst, _ = _slip_part(
        np.asarray(foot_xy, dtype=float), mask, np.full((mask.shape[1], 2), np.nan)
    )
    return worst


def _slip_part(xy: ArrayF, standing: npt.NDArray[np.bool_], anchor: ArrayF) -> tuple[float, ArrayF]:
    """:func:`foot_slip` over one part of a run, the stances open before it carried in.

    Args:
        xy: Horizontal foot positions (K, L, 2) [m].
        standing: Whether each foot stands (K, L).
        anchor: Where each foot's stance open at the part's start began (L, 2) [m];
            NaN for a foot not standing then.

    Returns:
        The largest slip in the part, and the anchors open at its end (NaN where none).

    """
    legs = standing.shape[1]
    # row 0 stands for the part before: a stance still open began at its anchor
    xy = np.concatenate((anchor[None], xy))
    stands = np.concatenate((~np.isnan(anchor[None, :, 0]), standing))
    begins = stands.copy()
    begins[1:] &= ~stands[:-1]
    rows = np.where(begins, np.arange(len(stands))[:, None], 0)
    start = xy[np.maximum.accumulate(rows, axis=0), np.arange(legs)]  # each row's stance start
    moved = np.where(stands, np.linalg.norm(xy - start, axis=-1), 0.0)
    worst = float(moved.max(initial=0.0))
    return worst, np.where(stands[-1][:, None], start[-1], np.nan)


def internal_forces(forces: npt.ArrayLike, feet: npt.ArrayLike, standing: npt.ArrayLike) -> ArrayF:
    """The largest internal force between the standing feet at each step (K,) [N].

    At each step where the feet touching the ground are the plan's standing feet (not
    while a lifting foot still touches or a landing one already does: the load is then
    handed over, as the plan does in no time), their forces less the least-norm forces
    with the same resultant force and moment (the pseudo-inverse of the equilibrium rows,
    about the feet's centre): what is left sums to zero — the feet pushing on each other
    through the ground. Other steps, and a foot standing alone: zero.

    Args:
        forces: The floor's force on each foot (K, L, 3) [N] (zero: not touching).
        feet: Where each foot is (K, L, 3) [m], in the same frame.
        standing: Whether the plan has each foot standing (K, L).

    """
    forces, feet = np.asarray(forces, dtype=float), np.asarray(feet, dtype=float)
    touching = np.linalg.norm(forces, axis=-1) > 0
    touching[(touching != np.asarray(standing, dtype=bool)).any(axis=1)] = False
    found = np.zeros(len(forces))
    for mask in np.unique(touching, axis=0):
        rows, count = np.all(touching == mask, axis=1), int(mask.sum())
        if count < 2:
            continue
        at = feet[rows][:, mask]
        rows_a, _ = equilibrium(at, at.mean(axis=1), 0.0, np.zeros(3))  # (K, 6, 3n)
        flat = forces[rows][:, mask].reshape(len(at), -1)
        resultant = np.einsum("kij,kj->ki", rows_a, flat)
        least = np.einsum("kij,kj->ki", np.linalg.pinv(rows_a), resultant)
        found[rows] = np.linalg.norm((flat - least).reshape(len(at), count, 3), axis=-1).max(1)
    return found


def peak_torques(torques: npt.ArrayLike) -> dict[str, float]:
    """Largest |τ| over steps and legs per joint type (root, hip, knee) [N·m]."""
    peaks = np.abs(np.asarray(torques, dtype=float)).reshape(-1, 3).max(axis=0)
    return {joint: float(p) for joint, p in zip(LEG_JOINTS, peaks, strict=True)}


def measure_walk(
    trace: Trace,
    period: float,
    cycles: int,
    velocity: npt.ArrayLike,
    nominal_height: float,
    *,
    legs: Sequence[str],
    rated_torques: npt.ArrayLike | None,
) -> WalkMetrics:
    """The measures of a walk of ``cycles`` periods, over the cycles after the first.

    Args:
        trace: The recorded run, starting at t = 0.
        period: Gait period T [s].
        cycles: Periods simulated (at least 2).
        velocity: Planned body velocity (vx, vy), world frame [m/s].
        nominal_height: The body's nominal height above the ground [m].
        legs: The legs' names, in the trace's leg order.
        rated_torques: Rated torque of the root, hip and knee servos (3,) [N·m].

    """
    meter = WalkMeter(period, velocity, nominal_height, legs=legs, rated_torques=rated_torques)
    meter.add(trace)
    return meter.metrics(cycles)


class WalkMeter:
    """:func:`measure_walk` fed a run part by part, in time order: memory bounded by a part.

    A long run (an hour of walking is 3.6 million steps) is measured as it is simulated,
    never held whole: each measure is a running extreme, sum or first/last value, and
    a stance open at a part's end carries its start into the next. The measures equal
    :func:`measure_walk`'s on the whole run.
    """

    def __init__(
        self,
        period: float,
        velocity: npt.ArrayLike,
        nominal_height: float,
        *,
        legs: Sequence[str],
        rated_torques: npt.ArrayLike | None,
    ) -> None:
        planned = np.asarray(velocity, dtype=float)[:2]
        self._speed = float(np.linalg.norm(planned))
        self._heading = planned / self._speed if self._speed > 0 else np.array([1.0, 0.0])
        self._period, self._nominal_height = period, nominal_height
        self._legs = tuple(legs)
        self._rated = None if rated_torques is None else np.asarray(rated_torques, dtype=float)
        self._first: ArrayF | None = None  # body position at the first measured step
        self._last: ArrayF | None = None
        self._tilt = np.zeros(2)
        self._min_height = math.inf
        self._fell = False
        self._squares, self._count = 0.0, 0
        self._slip = 0.0
        self._anchor = np.full((len(self._legs), 2), np.nan)
        self._peaks = np.full((len(self._legs), 3), -math.inf)
        self._peak_times = np.zeros((len(self._legs), 3))
        self._internal = math.nan

    def add(self, part: Trace) -> None:
        """Measure the next part of the run (its rows follow the previous part's)."""
        self._fell = self._fell or fell(part, self._nominal_height)
        measured = part.window(self._period)
        if len(measured.time) == 0:
            return
        position = measured.base_position
        if self._first is None:
            self._first = position[0, :2].copy()
        self._last = position[-1, :2].copy()
        self._tilt = np.maximum(
            self._tilt, np.abs(roll_pitch(measured.base_quaternion)).max(axis=0)
        )
        self._min_height = min(self._min_height, float(position[:, 2].min()))
        error = measured.reference - measured.joint_angles
        self._squares += float(np.sum(error**2))
        self._count += error.size
        slip, self._anchor = _slip_part(
            measured.foot_positions[..., :2], measured.standing, self._anchor
        )
        self._slip = max(self._slip, slip)
        magnitude = np.abs(measured.joint_torques)
        worst = magnitude.argmax(axis=0)  # the first of equal peaks, as over one whole run
        peaks = magnitude.max(axis=0)
        higher = peaks > self._peaks
        self._peaks = np.where(higher, peaks, self._peaks)
        self._peak_times = np.where(higher, measured.time[worst], self._peak_times)
        if measured.foot_forces is not None:
            found = internal_forces(
                measured.foot_forces, measured.foot_positions, measured.standing
            )
            self._internal = float(np.fmax(self._internal, found.max()))

    def metrics(self, cycles: int) -> WalkMetrics:
        """The measures of the run added so far, ``cycles`` periods long."""
        if self._first is None or self._last is None:
            raise HexalegError("no step of the run was measured: it ends within the first period")
        where = [at_times(row) for row in self._peak_times]
        return WalkMetrics(
            planned_distance=self._speed * self._period * (cycles - 1),
            distance=float((self._last - self._first) @ self._heading),
            max_roll=float(self._tilt[0]),
            max_pitch=float(self._tilt[1]),
            min_height=self._min_height,
            fell=self._fell,
            tracking_rms=math.sqrt(self._squares / self._count),
            slip=self._slip,
            peak_torque=peak_torques(self._peaks),
            over_rating=over_rating_at(self._legs, self._peaks, self._rated, where),
            internal_force=self._internal,
        )
