"""The internal wrench at each leg segment's proximal joint: what the segment carries there.

At the coxa's, femur's and tibia's proximal joints (root, hip, knee) the part of the leg
nearer the body holds everything beyond: the foot's force from the ground, the distal
links' and actuators' weights and, when the robot moves, their inertial forces. That is the
wrench of Pinocchio's RNEA at the joint (``data.f``: the spatial force the parent exerts on
the joint's subtree, at the joint's origin, in its own frame, whose x axis runs along the
segment), with the foot's force as an external force. It depends only on the leg beyond
the joint, so the body's own balance plays no part in it.

It is computed here as RNEA's backward pass does, vectorized over configurations and legs
in NumPy (reading Pinocchio's per-joint results from Python costs a hundred times more):
the joint placements, axes, link inertias and foot frames are read from the Pinocchio model
once, the legs' frames, velocities and accelerations propagated from the body out, and each
link's m·(a_c − g) and I·α + ω × I·ω summed from the foot in. The tests hold it to
Pinocchio's ``data.oMi`` and ``data.f`` on random configurations, velocities and accelerations.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._typing import ArrayF
from hexaleg.exceptions import ParameterError
from hexaleg.numerics.vectors import cross
from hexaleg.robot.model import HexapodModel


@dataclass(frozen=True, eq=False)
class LegStates:
    """The legs in K states.

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


@dataclass(frozen=True, eq=False)
class _Legs:
    """What the model says of the legs (6 legs × 3 joints), read once."""

    q: npt.NDArray[np.intp]  # (6, 3) configuration indices
    v: npt.NDArray[np.intp]  # (6, 3) velocity indices
    turns: ArrayF  # (6, 3, 3, 3) each joint's placement's rotation in its parent's frame
    offsets: ArrayF  # (6, 3, 3) its placement's translation [m]
    axes: ArrayF  # (6, 3, 3) its axis in its own frame
    masses: ArrayF  # (6, 3) each link's mass [kg] (the tibia's with its foot)
    levers: ArrayF  # (6, 3, 3) its centre of mass in the joint's frame [m]
    inertias: ArrayF  # (6, 3, 3, 3) its inertia about the centre, joint's axes [kg·m²]
    feet: ArrayF  # (6, 3) the foot in the knee's frame [m]

    @classmethod
    def of(cls, model: HexapodModel) -> _Legs:
        pin_model = model.model
        joints = [model.leg_joint_ids(leg) for leg in model.leg_names]
        placements = [[pin_model.jointPlacements[j] for j in row] for row in joints]
        inertias = [[pin_model.inertias[j] for j in row] for row in joints]
        feet = [pin_model.frames[model.foot_frame_id(leg)].placement for leg in model.leg_names]
        return cls(
            q=np.array([model.leg_q_indices(leg) for leg in model.leg_names]),
            v=np.array([model.leg_v_indices(leg) for leg in model.leg_names]),
            turns=np.array([[p.rotation for p in row] for row in placements]),
            offsets=np.array([[p.translation for p in row] for row in placements]),
            axes=np.array([[_axis(pin_model.joints[j]) for j in row] for row in joints]),
            masses=np.array([[i.mass for i in row] for row in inertias]),
            levers=np.array([[i.lever for i in row] for row in inertias]),
            inertias=np.array([[i.inertia for i in row] for row in inertias]),
            feet=np.array([f.translation for f in feet]),
        )


def _axis(joint: pin.JointModel) -> ArrayF:
    """A revolute joint's axis in its own frame: its motion subspace's angular part."""
    data = joint.createData()
    joint.calc(data, np.zeros(joint.nq))
    axis: ArrayF = np.asarray(data.S, dtype=float).reshape(6, -1)[3:, 0].copy()
    return axis


def require_template(model: HexapodModel) -> None:
    """Refuse a model whose links are not its design's (:attr:`~HexapodModel.design_links`).

    ``[structure]`` describes hexaleg's own legs' tubes; a robot file's links are its own.
    """
    if not model.design_links:
        raise ParameterError(
            "structure",
            model.design.structure,
            "hexaleg's own legs only: a robot file's links are its own",
        )


def leg_states(
    model: HexapodModel,
    configurations: npt.ArrayLike,
    gravity: npt.ArrayLike,
    velocities: npt.ArrayLike | None = None,
    accelerations: npt.ArrayLike | None = None,
) -> LegStates:
    """The legs' joints, feet and own wrenches at each configuration.

    Args:
        model: The robot (hexaleg's template: each segment along x of its joint's frame).
        configurations: q (K, nq), the free flyer first.
        gravity: Gravitational acceleration (K, 3) or (3,), world frame [m/s²].
        velocities: v (K, nv), the body's in its own frame [m/s, rad/s]; at rest if omitted.
        accelerations: a (K, nv), likewise [m/s², rad/s²]; at rest if omitted.

    """
    legs = _Legs.of(model)
    at_rest = velocities is None and accelerations is None
    q = np.asarray(configurations, dtype=float).reshape(-1, model.model.nq)
    count = len(q)
    v = np.zeros((count, model.model.nv)) if velocities is None else np.asarray(velocities)
    a = np.zeros((count, model.model.nv)) if accelerations is None else np.asarray(accelerations)
    g = np.broadcast_to(np.asarray(gravity, dtype=float), (count, 3))[:, None, :]
    body = _quaternion_matrix(q[:, 3:7])  # (K, 3, 3)
    spin = np.einsum("kij,kj->ki", body, v[:, 3:6])
    # the body origin's classical acceleration: the spatial one plus ω × v (own frame)
    linear = np.einsum("kij,kj->ki", body, a[:, :3] + cross(v[:, 3:6], v[:, :3]))
    parent_r = np.broadcast_to(body[:, None], (count, 6, 3, 3))
    parent_o = np.broadcast_to(q[:, None, :3], (count, 6, 3))
    omega = np.broadcast_to(spin[:, None], (count, 6, 3))
    alpha = np.broadcast_to(np.einsum("kij,kj->ki", body, a[:, 3:6])[:, None], (count, 6, 3))
    acceleration = np.broadcast_to(linear[:, None], (count, 6, 3))
    rotations, origins = np.empty((count, 6, 3, 3, 3)), np.empty((count, 6, 3, 3))
    forces, centres = np.empty((count, 6, 3, 3)), np.empty((count, 6, 3, 3))
    moments = np.zeros((count, 6, 3, 3))  # at rest, none
    for k in range(3):
        origin = parent_o + (parent_r @ legs.offsets[:, k, :, None])[..., 0]
        placed = np.einsum("klij,ljm->klim", parent_r, legs.turns[:, k])
        rotation = placed @ _rodrigues(legs.axes[:, k], q[:, legs.q[:, k]])
        lever = (rotation @ legs.levers[:, k, :, None])[..., 0]
        if at_rest:  # the weights alone: what the motion's terms below add up to at rest
            forces[:, :, k] = legs.masses[:, k, None] * -g
        else:
            arm = origin - parent_o
            acceleration = acceleration + cross(alpha, arm) + cross(omega, cross(omega, arm))
            axis = (placed @ legs.axes[:, k, :, None])[..., 0]
            rate, rate2 = v[:, legs.v[:, k]][..., None], a[:, legs.v[:, k]][..., None]
            alpha = alpha + axis * rate2 + cross(omega, axis * rate)
            omega = omega + axis * rate
            centre = acceleration + cross(alpha, lever) + cross(omega, cross(omega, lever))
            forces[:, :, k] = legs.masses[:, k, None] * (centre - g)
            moments[:, :, k] = _spin_moment(legs.inertias[:, k], rotation, omega, alpha)
        centres[:, :, k] = origin + lever
        rotations[:, :, k], origins[:, :, k] = rotation, origin
        parent_r, parent_o = rotation, origin
    feet = origins[:, :, 2] + (rotations[:, :, 2] @ legs.feet[:, :, None])[..., 0]
    return LegStates(
        rotations, origins, feet, _subtree(rotations, origins, forces, moments, centres)
    )


def _spin_moment(inertia: ArrayF, rotation: ArrayF, omega: ArrayF, alpha: ArrayF) -> ArrayF:
    """A link's I·α + ω × I·ω (K, 6, 3), world frame, its inertia (6, 3, 3) in its own axes."""
    spin = np.einsum("klji,klj->kli", rotation, omega)  # ω, α in the link's axes
    turn = np.einsum("klji,klj->kli", rotation, alpha)
    spun = (inertia @ spin[..., None])[..., 0]
    local = (inertia @ turn[..., None])[..., 0] + cross(spin, spun)
    moment: ArrayF = (rotation @ local[..., None])[..., 0]
    return moment


def _subtree(
    rotations: ArrayF, origins: ArrayF, forces: ArrayF, moments: ArrayF, centres: ArrayF
) -> ArrayF:
    """Each joint's wrench (K, 6, 3, 6) holding the links beyond it, in the joint's frame."""
    out = np.empty((*origins.shape[:3], 6))
    for k in range(3):
        force = forces[:, :, k:].sum(axis=2)
        moment = (
            moments[:, :, k:] + cross(centres[:, :, k:] - origins[:, :, k, None], forces[:, :, k:])
        ).sum(axis=2)
        out[:, :, k, :3] = np.einsum("klji,klj->kli", rotations[:, :, k], force)
        out[:, :, k, 3:] = np.einsum("klji,klj->kli", rotations[:, :, k], moment)
    return out


def _quaternion_matrix(xyzw: ArrayF) -> ArrayF:
    """Rotations (K, 3, 3) of unit quaternions (K, 4) stored x, y, z, w (Pinocchio's order)."""
    x, y, z, w = xyzw.T
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
            np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
            np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
        ],
        axis=-2,
    )


def _rodrigues(axes: ArrayF, angles: ArrayF) -> ArrayF:
    """Rotations (K, 6, 3, 3) by ``angles`` (K, 6) [rad] about unit ``axes`` (6, 3)."""
    cross = np.zeros((len(axes), 3, 3))
    cross[:, 0, 1], cross[:, 0, 2], cross[:, 1, 2] = -axes[:, 2], axes[:, 1], -axes[:, 0]
    cross -= cross.swapaxes(-1, -2)
    sine, cosine = np.sin(angles)[..., None, None], np.cos(angles)[..., None, None]
    return np.eye(3) + sine * cross + (1 - cosine) * (cross @ cross)


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
    about = np.einsum("klsji,klsj->klsi", states.rotations, cross(arm, force))
    return states.own - np.concatenate((along, about), axis=-1)


def weight_wrenches(
    states: LegStates, lengths: tuple[float, float, float], gravity: npt.ArrayLike
) -> ArrayF:
    """What one kilogram more of each segment, at its middle, adds to the wrenches at rest.

    Returns:
        (3, K, 6, 3, 6): per segment whose mass grows (coxa, femur, tibia), state, leg and
        joint, the force [N/kg] then the moment [N·m/kg] the parent exerts on the joint's
        subtree in the joint's frame (:attr:`LegStates.own`'s, per kilogram): −g, and its
        moment about the joint, at each joint from the body out to that segment's own.

    """
    count = len(states.feet)
    force = np.broadcast_to(-np.asarray(gravity, dtype=float), (count, 3))[:, None, :]
    force = np.broadcast_to(force, states.feet.shape)  # (K, 6, 3)
    out = np.zeros((3, *states.origins.shape[:3], 6))
    for segment in range(3):
        middle = states.origins[:, :, segment] + states.axes[:, :, segment] * (lengths[segment] / 2)
        for joint in range(segment + 1):
            rotation = states.rotations[:, :, joint]
            moment = cross(middle - states.origins[:, :, joint], force)
            out[segment, :, :, joint, :3] = np.einsum("klji,klj->kli", rotation, force)
            out[segment, :, :, joint, 3:] = np.einsum("klji,klj->kli", rotation, moment)
    return out
