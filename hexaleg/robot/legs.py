"""A robot file's leg as hexaleg's general leg: mount, dimensions, joint map, link placements.

From a :class:`~hexaleg.robot.chains.LegChain` and its :class:`~hexaleg.robot.feet.Foot`,
everything is read at q = 0 in the body (root link) frame:

- the yaw axis (c₁, u₁) must lie within :data:`AXIS_TOLERANCE` of the body's vertical,
  either sign; the leg-root frame has its origin at c₁ (the first joint's origin) and z
  along ±u₁ pointing up;
- the hip and knee axes (c₂, u₂), (c₃, u₃) must be parallel to each other and
  perpendicular to u₁; x points from the yaw axis to the hip axis along their common
  perpendicular (toward the foot when they meet), y = z × x, so the pitch axes lie along ±y;
- coxa a1 = the distance between the yaw and hip axis lines, hip height h = the hip axis'
  height above c₁, femur l2 = the distance between the hip and knee axes, tibia l3 = the
  knee axis to the foot in the leg plane, lateral offset e = the foot's offset along y;
- the joint map ``q = s·θ + o``: s = +1 where the file's axis turns the way hexaleg's
  does (+z for the root, −y for the pitch joints), o such that θ2 = 0 levels the femur
  line and θ3 = 0 puts the tibia line in line with it; θ1 = 0 is the file's q1 = 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.exceptions import RobotImportError
from hexaleg.leg_frames import segment_frames
from hexaleg.leg_geometry import JointMap, LegGeometry, placement
from hexaleg.robot.chains import LegChain
from hexaleg.robot.feet import Foot

AXIS_TOLERANCE = 0.01
"""Largest angle between axes that count as parallel (or 90° ± it, perpendicular) [rad]."""

VERTICAL = np.array([0.0, 0.0, 1.0])
"""The body's vertical in the root link's frame (REP 103: z up)."""


@dataclass(frozen=True, eq=False)
class LegReading:
    """One leg as hexaleg reads it.

    Attributes:
        geometry: Its dimensions and link placements.
        joint_map: The file's joint values from hexaleg's angles.
        mount: The leg-root frame (4, 4) in the body (root link) frame [m].
        foot: The foot point and the rule that found it.

    """

    geometry: LegGeometry
    joint_map: JointMap
    mount: ArrayF
    foot: Foot

    @property
    def mount_yaw(self) -> float:
        """Direction of the coxa at θ1 = 0 about the body's z axis [rad]."""
        return float(math.atan2(self.mount[1, 0], self.mount[0, 0]))


def read_leg(chain: LegChain, frames: dict[str, ArrayF], foot: Foot) -> LegReading:
    """The general leg of ``chain`` (``frames``: every link at q = 0 in the root frame).

    Raises:
        RobotImportError: An axis is not where a yaw–pitch–pitch leg has it, or the foot
            lies on the knee axis.

    """
    links = [frames[chain.segments[k][0]] for k in range(3)]
    centres = [link[:3, 3] for link in links]
    axes = [link[:3, :3] @ joint.axis for link, joint in zip(links, chain.joints, strict=True)]
    _check_axes(chain, axes)
    z = axes[0] * math.copysign(1.0, float(axes[0] @ VERTICAL))
    foot_point = links[2][:3, :3] @ np.asarray(foot.point) + links[2][:3, 3]
    pitch = _unit(axes[1] - (axes[1] @ z) * z)
    hip = centres[1] - centres[0]
    x = hip - (hip @ z) * z - (hip @ pitch) * pitch
    coxa = float(np.linalg.norm(x))
    if coxa < 1e-12:  # the hip axis meets the yaw axis: point x toward the foot
        x = np.cross(pitch, z) * math.copysign(1.0, float(np.cross(pitch, z) @ foot_point))
        coxa = 0.0
    x = _unit(x)
    y = np.cross(z, x)
    mount = np.eye(4)
    mount[:3, :3] = np.column_stack((x, y, z))
    mount[:3, 3] = centres[0]
    return _in_leg_frame(chain, mount, links, axes, foot_point, coxa, foot)


def _in_leg_frame(
    chain: LegChain,
    mount: ArrayF,
    links: list[ArrayF],
    axes: list[ArrayF],
    foot_point: ArrayF,
    coxa: float,
    foot: Foot,
) -> LegReading:
    """Dimensions, joint map and link placements, with the leg-root frame ``mount`` known."""
    rotation, origin = mount[:3, :3], mount[:3, 3]
    local = [rotation.T @ (link[:3, 3] - origin) for link in links]
    foot_local = rotation.T @ (foot_point - origin)
    wanted = (np.array([0.0, 0.0, 1.0]), np.array([0.0, -1.0, 0.0]), np.array([0.0, -1.0, 0.0]))
    signs = tuple(
        int(math.copysign(1, float((rotation.T @ a) @ w)))
        for a, w in zip(axes, wanted, strict=True)
    )
    femur = local[2] - local[1]
    tibia = foot_local - local[2]
    femur_length = math.hypot(femur[0], femur[2])
    tibia_length = math.hypot(tibia[0], tibia[2])
    if tibia_length < 1e-9:
        raise RobotImportError(
            f"leg from joint {chain.joints[0].name}: the foot ({foot.source}) lies on the axis "
            f"of joint {chain.joints[2].name}; give foot_offset X Y Z"
        )
    if femur_length < 1e-9:
        raise RobotImportError(
            f"leg from joint {chain.joints[0].name}: joints {chain.joints[1].name} and "
            f"{chain.joints[2].name} share one axis (no femur)"
        )
    hip_angle = math.atan2(femur[2], femur[0])  # θ2 at q = 0
    knee_angle = _wrap(math.atan2(tibia[2], tibia[0]) - hip_angle)  # θ3 at q = 0
    theta0 = np.array([0.0, hip_angle, knee_angle])
    offsets = tuple(_wrap(-s * t) for s, t in zip(signs, theta0, strict=True))
    geometry = LegGeometry(
        coxa, femur_length, tibia_length, float(local[1][2]), float(foot_local[1])
    )
    kinematic = segment_frames(geometry, theta0)
    inverse = np.linalg.inv(mount)
    coxa_link, femur_link, tibia_link = (
        placement(np.linalg.inv(kinematic[k]) @ inverse @ links[k]) for k in range(3)
    )
    placements = (coxa_link, femur_link, tibia_link)
    geometry = LegGeometry(
        *geometry.lengths, geometry.hip_height, geometry.foot_lateral, placements
    )
    joint_map = JointMap(signs, offsets)  # type: ignore[arg-type]
    return LegReading(geometry, joint_map, mount, foot)


def _check_axes(chain: LegChain, axes: list[ArrayF]) -> None:
    """Refuse a leg whose axes are not yaw (vertical), then two parallel pitch axes."""
    names = [j.name for j in chain.joints]
    tilt = _angle(axes[0], VERTICAL)
    tilt = min(tilt, math.pi - tilt)
    if tilt > AXIS_TOLERANCE:
        raise RobotImportError(
            f"joint {names[0]}'s axis {_text(axes[0])} is {math.degrees(tilt):.1f}° "
            f"from the body's vertical; a leg's first joint must turn about it (yaw)"
        )
    between = _angle(axes[1], axes[2])
    if min(between, math.pi - between) > AXIS_TOLERANCE:
        raise RobotImportError(
            f"joint {names[1]}'s axis {_text(axes[1])} is not parallel to {names[2]}'s "
            f"{_text(axes[2])} ({math.degrees(min(between, math.pi - between)):.1f}° apart)"
        )
    cross = _angle(axes[0], axes[1])
    if abs(cross - math.pi / 2) > AXIS_TOLERANCE:
        raise RobotImportError(
            f"joint {names[1]}'s axis {_text(axes[1])} is not perpendicular to {names[0]}'s "
            f"{_text(axes[0])} ({math.degrees(cross):.1f}° apart)"
        )


def _angle(a: ArrayF, b: ArrayF) -> float:
    return float(math.acos(max(-1.0, min(1.0, float(a @ b)))))


def _unit(v: ArrayF) -> ArrayF:
    return v / float(np.linalg.norm(v))


def _wrap(angle: float) -> float:
    """``angle`` [rad] wrapped to (−π, π]."""
    wrapped = math.remainder(angle, 2 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def _text(vector: ArrayF) -> str:
    """A vector in the body frame, rounded for a message."""
    return "(" + " ".join(f"{v:.3g}" for v in np.where(np.abs(vector) < 5e-4, 0.0, vector)) + ")"
