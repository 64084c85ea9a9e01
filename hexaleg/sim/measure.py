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
- peak torque: the largest |τ| any servo applies, per joint type [N·m].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy.spatial.transform import Rotation

from hexaleg._typing import ArrayF
from hexaleg.limits import LEG_JOINTS

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

    """

    time: ArrayF
    base_position: ArrayF
    base_quaternion: ArrayF
    joint_angles: ArrayF
    reference: ArrayF
    joint_torques: ArrayF
    foot_positions: ArrayF
    standing: npt.NDArray[np.bool_]

    def window(self, start: float) -> Trace:
        """The rows from time ``start`` [s] on."""
        rows = self.time >= start - 1e-9
        return Trace(*(getattr(self, name)[rows] for name in self.__dataclass_fields__))


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
    xy = np.asarray(foot_xy, dtype=float)
    mask = np.asarray(standing, dtype=bool)
    worst = 0.0
    for leg in range(mask.shape[1]):
        column = mask[:, leg].astype(np.int8)
        edges = np.flatnonzero(np.diff(np.concatenate(([0], column, [0]))))
        for begin, end in zip(edges[0::2], edges[1::2], strict=True):
            moved = np.linalg.norm(xy[begin:end, leg] - xy[begin, leg], axis=1)
            worst = max(worst, float(moved.max()))
    return worst


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
) -> WalkMetrics:
    """The measures of a walk of ``cycles`` periods, over the cycles after the first.

    Args:
        trace: The recorded run, starting at t = 0.
        period: Gait period T [s].
        cycles: Periods simulated (at least 2).
        velocity: Planned body velocity (vx, vy), world frame [m/s].
        nominal_height: The body's nominal height above the ground [m].

    """
    planned = np.asarray(velocity, dtype=float)[:2]
    speed = float(np.linalg.norm(planned))
    heading = planned / speed if speed > 0 else np.array([1.0, 0.0])
    measured = trace.window(period)
    travel = measured.base_position[-1, :2] - measured.base_position[0, :2]
    tilt = np.abs(roll_pitch(measured.base_quaternion))
    error = measured.reference - measured.joint_angles
    return WalkMetrics(
        planned_distance=speed * period * (cycles - 1),
        distance=float(travel @ heading),
        max_roll=float(tilt[:, 0].max()),
        max_pitch=float(tilt[:, 1].max()),
        min_height=float(measured.base_position[:, 2].min()),
        fell=fell(trace, nominal_height),
        tracking_rms=float(np.sqrt(np.mean(error**2))),
        slip=foot_slip(measured.foot_positions[..., :2], measured.standing),
        peak_torque=peak_torques(measured.joint_torques),
    )
