"""The internal wrench at each leg segment's proximal joint: what the segment carries there.

At the coxa's, femur's and tibia's proximal joints (root, hip, knee) the part of the leg
nearer the body holds everything beyond: the foot's force from the ground, the distal
links' and actuators' weights and, when the robot moves, their inertial forces. The part
without the foot's force is Pinocchio's RNEA's ``data.f`` of the joint (the spatial force
the parent exerts on the joint's subtree, at the joint's origin, in its own frame, whose x
axis runs along the segment); the foot's force f at p, which the subtree also carries,
adds −(f, (p − o) × f) at the joint's origin o, turned into the joint's frame. It depends
only on the leg beyond the joint, so the body's own balance plays no part in it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._typing import ArrayF
from hexaleg.robot.model import HexapodModel


@dataclass(frozen=True, eq=False)
class LegStates:
    """The legs in K states, as one pass of Pinocchio's RNEA leaves them.

    Attributes:
        rotations: Each leg joint's frame (K, 6, 3, 3, 3), world frame: its columns are
            the frame's axes, the first along the segment.
        origins: Each leg joint's origin (K, 6, 3, 3), world frame [m].
        feet: Each foot (K, 6, 3), world frame [m].
        own: The wrench at each leg joint without the foot's force (K, 6, 3, 6): force [N]
            then moment [N·m] the parent exerts on the subtree, in the joint's frame.

    """

    rotations: ArrayF
    origins: ArrayF
    feet: ArrayF
    own: ArrayF

    @property
    def axes(self) -> ArrayF:
        """Each segment's direction (K, 6, 3, 3), world frame."""
        return self.rotations[..., 0]


def leg_states(
    model: HexapodModel,
    configurations: npt.ArrayLike,
    gravity: npt.ArrayLike,
    velocities: npt.ArrayLike | None = None,
    accelerations: npt.ArrayLike | None = None,
) -> LegStates:
    """The legs' joints, feet and own wrenches at each configuration (one RNEA each).

    Args:
        model: The robot (hexaleg's template: each segment along x of its joint's frame).
        configurations: q (K, nq).
        gravity: Gravitational acceleration (K, 3) or (3,), world frame [m/s²].
        velocities: v (K, nv) [m/s, rad/s]; at rest if omitted.
        accelerations: a (K, nv) [m/s², rad/s²]; at rest if omitted.

    """
    pin_model, data = model.model, model.data
    q = np.asarray(configurations, dtype=float).reshape(-1, pin_model.nq)
    count = len(q)
    g = np.broadcast_to(np.asarray(gravity, dtype=float), (count, 3))
    v = np.zeros((count, pin_model.nv)) if velocities is None else np.asarray(velocities)
    a = np.zeros((count, pin_model.nv)) if accelerations is None else np.asarray(accelerations)
    joints = [j for leg in model.leg_names for j in model.leg_joint_ids(leg)]
    feet = [model.foot_frame_id(leg) for leg in model.leg_names]
    legs = len(feet)
    rotations = np.empty((count, legs * 3, 3, 3))
    origins = np.empty((count, legs * 3, 3))
    own = np.empty((count, legs * 3, 6))
    foot = np.empty((count, legs, 3))
    saved = pin_model.gravity.linear.copy()
    try:
        for k in range(count):
            pin_model.gravity.linear = g[k]
            pin.framesForwardKinematics(pin_model, data, q[k])  # RNEA leaves oMi as it was
            pin.rnea(pin_model, data, q[k], v[k], a[k])
            for i, joint in enumerate(joints):
                placement = data.oMi[joint]
                rotations[k, i], origins[k, i] = placement.rotation, placement.translation
                own[k, i] = data.f[joint].vector
            for i, frame in enumerate(feet):
                foot[k, i] = data.oMf[frame].translation
    finally:
        pin_model.gravity.linear = saved
    shape = (count, legs, 3)
    return LegStates(
        rotations.reshape(*shape, 3, 3), origins.reshape(*shape, 3), foot, own.reshape(*shape, 6)
    )


def segment_wrenches(states: LegStates, foot_forces: npt.ArrayLike) -> ArrayF:
    """The wrench at each segment's proximal joint, in the segment's frame (K, 6, 3, 6).

    Args:
        states: The legs (:func:`leg_states`).
        foot_forces: Each foot's force from the ground (K, 6, 3), world frame, at the
            foot (zero for a foot in the air) [N].

    Returns:
        Per state, leg and segment (coxa, femur, tibia): the force [N] then the moment
        [N·m] the proximal side exerts on the segment and all beyond it, at the joint's
        origin, in the segment's frame (x along it).

    """
    force = np.asarray(foot_forces, dtype=float)[:, :, None, :]  # (K, 6, 1, 3)
    arm = states.feet[:, :, None, :] - states.origins  # (K, 6, 3, 3)
    along = np.einsum("klsji,klsj->klsi", states.rotations, np.broadcast_to(force, arm.shape))
    about = np.einsum("klsji,klsj->klsi", states.rotations, np.cross(arm, force))
    return states.own - np.concatenate((along, about), axis=-1)
