"""Inverse dynamics of a gait period on the free-flyer model, and the standing feet's forces.

At each sample, the RNEA on the free-flyer Pinocchio model (the design's URDF, the payload
a point mass fixed to the body) gives the generalized forces of the motion: base velocity
v·u, base acceleration 0, the legs' joint motion. The body neither turns nor accelerates,
so the legs' chains are solved for every sample at once
(:mod:`~hexaleg.gait.newton_euler`, held to Pinocchio's ``rnea`` by the tests); a model
whose legs are not plain chains takes Pinocchio's calls, sample by sample. The standing
feet's forces f_i (ground frame, at the foot frame's origin) balance its six base rows,
Σ J_i,baseᵀ f_i = RNEA[0:6], and the joint torques are τ = RNEA[6:] − Σ J_i,jointsᵀ f_i;
swinging legs carry their own inertia and gravity. The split is the minimum-norm one
(:func:`~hexaleg.statics.forces.min_norm_forces`) or the min-torque QP with friction of
the statics (:func:`~hexaleg.statics.forces.min_torque_forces`), on the equilibrium rows
of :func:`~hexaleg.statics.forces.equilibrium` written about the body's origin.

Joint angles are hexaleg's θ; the model's joints turn as q = s·θ + o (the identity for
hexaleg's own URDF, a robot file's signs and offsets for an imported robot), so the RNEA
runs at q, q̇ = s·θ̇, q̈ = s·θ̈ and each joint's torque on θ is s times the model's.

Every joint velocity is (1/T)·(a derivative by the phase) and every acceleration (1/T²)·(…),
so RNEA = g(q) + (M(q)·q'' + C(q, q')·q')/T² exactly: a static part and an inertial part
over T². Both are computed once (the generalized gravity, and RNEA without gravity on
the phase derivatives); the minimum-norm forces and the torques are linear in
them, so one evaluation serves every period of the same stride.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._typing import ArrayF
from hexaleg.gait.jacobian import transpose_times
from hexaleg.gait.newton_euler import LegBodies, leg_bodies, leg_chains, leg_forces
from hexaleg.gait.pattern import GaitPhases
from hexaleg.gait.trajectory import JointMotion, LegFrames
from hexaleg.kinematics import foot_jacobian
from hexaleg.numerics.vectors import cross
from hexaleg.ratings import torque_scale
from hexaleg.robot.imported_model import robot_mass
from hexaleg.robot.model import ROOT_JOINT, HexapodModel
from hexaleg.statics.forces import (
    Payload,
    equilibrium,
    min_norm_forces,
    min_torque_forces,
)


@dataclass(frozen=True)
class GeneralizedForces:
    """RNEA along the period, split as static + inertial/T² (N, nv).

    Attributes:
        configurations: q at each sample (N, nq), Pinocchio's layout [m, -, rad].
        velocities: dq/dφ (N, nv) [m, rad]: divide by T for v.
        accelerations: d²q/dφ² (N, nv) [m, rad]: divide by T² for a.
        static: g(q): what holds each pose against gravity [N, N·m].
        inertial: M(q)·q'' + C(q, q')·q' with the phase derivatives [N·s², N·m·s²].

    """

    configurations: ArrayF
    velocities: ArrayF
    accelerations: ArrayF
    static: ArrayF
    inertial: ArrayF


def payload_wrench(point: ArrayF, mass: float, gravity: ArrayF) -> ArrayF:
    """What a point mass on the body adds to the base's generalized forces (6,).

    The body's rows hold the wrench that carries it, in the body's frame at its origin:
    the force f = −m·g [N] against gravity g (3,) [m/s²] given in the body frame (−g·z on
    level ground, tilted on a slope: :class:`~hexaleg.statics.ground.Ground`) and the
    moment p × f [N·m] of the point p [m] (body frame). With the body at constant velocity
    and not turning (a gait period's body, parallel to the ground), the point's inertial
    forces are zero, so this is exactly what RNEA gives with the mass added to the body's
    inertia.
    """
    force = -mass * np.asarray(gravity, dtype=float)
    return np.concatenate((force, cross(point, force)))


@dataclass(frozen=True)
class CarriedLoad:
    """What a constant wrench on the base's rows adds to a min-norm split (any period).

    Attributes:
        forces: The standing feet's added forces (N, 6, 3), ground frame [N] (zero while
            a foot swings).
        torques: The joints' added torques (N, 6, 3) [N·m].

    """

    forces: ArrayF
    torques: ArrayF


class LoadedRobot:
    """The robot's Pinocchio model carrying the payload: a copy, built once per walker.

    The payload is a point mass added to the body's inertia (its weight and, were the body
    to accelerate, its inertia). Gravity is given in the body frame, which stays parallel
    to the ground: −g·z on level ground, tilted on a slope
    (:class:`~hexaleg.statics.ground.Ground`). Without a payload, at the model's own
    gravity, the model itself serves (a study's designs are not copied).

    Args:
        model: The robot.
        payload: A point mass on the body.
        gravity: Gravitational acceleration in the body (ground) frame (3,) [m/s²].

    """

    def __init__(self, model: HexapodModel, payload: Payload, gravity: ArrayF) -> None:
        robot_mass(model)  # a robot file without masses is refused here
        self.gravity = np.array(gravity, dtype=float)
        own = payload.mass == 0 and bool(np.all(model.model.gravity.linear == self.gravity))
        self.model = model.model if own else pin.Model(model.model)
        if payload.mass > 0:
            base = int(self.model.getJointId(ROOT_JOINT))
            point = pin.Inertia(payload.mass, payload.point(model), np.zeros((3, 3)))
            self.model.inertias[base] = self.model.inertias[base] + point
        self.model.gravity.linear = self.gravity
        self._source, self._own = model, own  # the robot, and whether its model serves
        self._data: pin.Data | None = None
        self.mass = float(pin.computeTotalMass(self.model))
        self.legs = model.leg_names
        self.q_index = np.array([model.leg_q_indices(leg) for leg in model.leg_names])
        self.v_index = np.array([model.leg_v_indices(leg) for leg in model.leg_names])
        self.signs = joint_signs(model)
        self.height = float(model.nominal_base_pose().translation[2])
        self._joint_values = model.joint_values
        self._joints = [list(model.leg_joint_ids(leg)) for leg in model.leg_names]

    @property
    def data(self) -> pin.Data:
        """Pinocchio's workspace for :attr:`model` (made on first use: the chains need none)."""
        if self._data is None:
            self._data = self._source.data if self._own else self.model.createData()
        return self._data

    @cached_property
    def bodies(self) -> LegBodies | None:
        """The legs as chains for :func:`~hexaleg.gait.newton_euler.leg_forces`, or ``None``.

        ``None`` where the model is not six chains of three revolute joints on the body
        (:func:`~hexaleg.gait.newton_euler.leg_chains`, found once for every model of the
        body): Pinocchio's calls serve it.
        """
        chains = self._source.structural("leg chains", lambda: leg_chains(self.model, self._joints))
        return None if chains is None else leg_bodies(self.model, chains)

    def generalized_forces(self, motion: JointMotion, base_travel: ArrayF) -> GeneralizedForces:
        """RNEA at each sample, by its two parts.

        The body translates at a constant velocity without turning, so the legs' chains
        are solved for every sample at once (:func:`~hexaleg.gait.newton_euler.leg_forces`);
        a model whose legs are not such chains (:attr:`bodies`) takes one Pinocchio call
        per part and sample.

        Args:
            motion: Joint angles θ and their phase derivatives (N, 6, 3), ``leg_names``
                order (the model's joints at q = s·θ + o).
            base_travel: How far the body moves in one period, v·T·u, body frame (3,) [m].

        """
        count, model = len(motion.angles), self.model
        values = [self._joint_values(leg, motion.angles[:, i]) for i, leg in enumerate(self.legs)]
        joints = np.stack(values, axis=1)  # the model's q of every leg (N, 6, 3)
        rates, accelerations = self.signs * motion.velocity, self.signs * motion.acceleration
        q = np.zeros((count, model.nq))
        q[:, :3] = np.arange(count)[:, None] / count * base_travel
        q[:, 2] += self.height
        q[:, 6] = 1.0  # level: the identity quaternion (x, y, z, w)
        q[:, self.q_index] = joints
        velocity = np.zeros((count, model.nv))
        velocity[:, :3] = base_travel  # the body's, per unit phase, in its own (level) frame
        velocity[:, self.v_index] = rates
        acceleration = np.zeros((count, model.nv))
        acceleration[:, self.v_index] = accelerations
        if self.bodies is not None:
            static, inertial = self._chain_rows(joints, rates, accelerations, base_travel)
        else:
            static, inertial = self._pinocchio_rows(q, velocity, acceleration)
        return GeneralizedForces(q, velocity, acceleration, static, inertial)

    def _chain_rows(
        self, joints: ArrayF, rates: ArrayF, accelerations: ArrayF, base_velocity: ArrayF
    ) -> tuple[ArrayF, ArrayF]:
        """The static and inertial rows (N, nv) from the legs' chains (every joint a leg's).

        Args:
            joints: The model's joint values (N, 6, 3) [rad].
            rates: Their phase derivatives (N, 6, 3) [rad].
            accelerations: Their second phase derivatives (N, 6, 3) [rad].
            base_velocity: The body's, per unit phase, in its own frame (3,) [m].

        """
        assert self.bodies is not None
        parts = leg_forces(self.bodies, joints, rates, accelerations, base_velocity, self.gravity)
        rows = np.empty((2, len(joints), self.model.nv))  # every row is a leg's or the body's
        for row, part in zip(rows, parts, strict=True):
            row[:, :6] = part.base
            row[:, self.v_index] = part.torques
        return rows[0], rows[1]

    def _pinocchio_rows(
        self, q: ArrayF, velocity: ArrayF, acceleration: ArrayF
    ) -> tuple[ArrayF, ArrayF]:
        """The static and inertial rows (N, nv): Pinocchio's, one call per part and sample."""
        model, data, count = self.model, self.data, len(q)
        static, inertial = np.empty((count, model.nv)), np.empty((count, model.nv))
        for k in range(count):
            static[k] = pin.computeGeneralizedGravity(model, data, q[k])
        model.gravity.linear = np.zeros(3)
        try:
            for k in range(count):
                inertial[k] = pin.rnea(model, data, q[k], velocity[k], acceleration[k])
        finally:
            model.gravity.linear = self.gravity
        return static, inertial


@dataclass(frozen=True)
class ForceSplit:
    """Foot forces and joint torques along the period, as static + inertial/T².

    Attributes:
        static_forces: Each foot's force from the ground (N, 6, 3) [N], ground frame
            (zero while it swings).
        inertial_forces: Their inertial parts (N, 6, 3) [N·s²].
        static_torques: Each joint's torque (N, 6, 3) [N·m].
        inertial_torques: Their inertial parts (N, 6, 3) [N·m·s²].

    """

    static_forces: ArrayF
    inertial_forces: ArrayF
    static_torques: ArrayF
    inertial_torques: ArrayF

    def forces(self, period: float) -> ArrayF:
        """Foot forces (N, 6, 3) at period T [s] [N]."""
        return self.static_forces + self.inertial_forces / period**2

    def torques(self, period: float) -> ArrayF:
        """Joint torques (N, 6, 3) at period T [s] [N·m]."""
        return self.static_torques + self.inertial_torques / period**2


def stance_indices(phases: GaitPhases) -> npt.NDArray[np.intp]:
    """The standing legs' indices at each sample (N, 6β), in leg order."""
    stance = phases.stance
    return np.nonzero(stance)[1].reshape(len(stance), -1)


def joint_signs(model: HexapodModel) -> ArrayF:
    """dq/dθ of every leg joint (6, 3), ``leg_names`` order (±1; all +1 for hexaleg's URDF)."""
    return np.array([model.joint_signs(leg) for leg in model.leg_names])


def leg_rows(model: HexapodModel, rows: ArrayF) -> ArrayF:
    """The legs' joint rows (..., N, 6, 3) of generalized forces (..., N, nv), on hexaleg's θ.

    ``leg_names`` order; each row times its joint's sign dq/dθ (a torque about the
    model's joint axis is s times the torque on θ).
    """
    v_index = np.array([model.leg_v_indices(leg) for leg in model.leg_names])
    on_theta: ArrayF = rows[..., v_index] * joint_signs(model)
    return on_theta


def min_norm_split(
    model: HexapodModel,
    frames: LegFrames,
    phases: GaitPhases,
    feet: ArrayF,
    motion: JointMotion,
    rnea: GeneralizedForces,
) -> ForceSplit:
    """The minimum-norm foot forces balancing the base rows, and the torques that follow.

    Args:
        model: The robot.
        frames: The legs.
        phases: Who stands when.
        feet: Foot positions (N, 6, 3) in the body frame [m].
        motion: Joint angles (N, 6, 3).
        rnea: The generalized forces.

    """
    return min_norm_split_carrying(model, frames, phases, feet, motion, rnea)[0]


def min_norm_split_carrying(
    model: HexapodModel,
    frames: LegFrames,
    phases: GaitPhases,
    feet: ArrayF,
    motion: JointMotion,
    rnea: GeneralizedForces,
    wrench: ArrayF | None = None,
) -> tuple[ForceSplit, CarriedLoad | None]:
    """:func:`min_norm_split`, and in the same solve :func:`carried_load` of ``wrench``.

    Arguments as :func:`min_norm_split`'s; ``wrench`` (6,) [N, N·m], or none (``None``).
    """
    columns = [rnea.static[:, :6], rnea.inertial[:, :6]]
    if wrench is not None:
        columns.append(np.broadcast_to(np.asarray(wrench, dtype=float), (len(feet), 6)))
    forces, pushed = _min_norm_pushes(frames, phases, feet, motion, np.stack(columns, axis=-1))
    joints = leg_rows(model, np.stack((rnea.static, rnea.inertial)))
    torques = joints - pushed[:2]
    split = ForceSplit(forces[0], forces[1], torques[0], torques[1])
    return split, (None if wrench is None else CarriedLoad(forces[2], -pushed[2]))


def carried_load(
    frames: LegFrames, phases: GaitPhases, feet: ArrayF, motion: JointMotion, wrench: ArrayF
) -> CarriedLoad:
    """The feet's forces and joint torques a constant wrench (6,) on the base's rows adds.

    What :func:`min_norm_split` gives with the wrench added to the base's rows less what it
    gives without (the split is linear in them): the minimum-norm forces carrying the
    wrench, e.g. a payload's (:func:`payload_wrench`), and −Jᵀ of them. Arguments as
    :func:`min_norm_split`'s.
    """
    columns = np.broadcast_to(np.asarray(wrench, dtype=float)[:, None], (len(feet), 6, 1))
    forces, pushed = _min_norm_pushes(frames, phases, feet, motion, columns)
    return CarriedLoad(forces[0], -pushed[0])


def _min_norm_pushes(
    frames: LegFrames, phases: GaitPhases, feet: ArrayF, motion: JointMotion, wrenches: ArrayF
) -> tuple[ArrayF, ArrayF]:
    """The minimum-norm feet's forces balancing base wrenches, and the torques they push.

    The least-norm forces do not depend on the point the moments are taken about, and
    during a run of samples (:attr:`~hexaleg.gait.pattern.GaitPhases.runs`) the standing
    feet do not move on the ground while the body translates: about the body's origin at
    the run's first sample (its moment M + d × F, d how far the body has moved since, as
    far as its standing feet have moved back), one set of balance rows and one solve
    (:func:`~hexaleg.statics.forces.min_norm_forces`) serve every sample of the run.

    Args:
        frames: The legs.
        phases: Who stands when.
        feet: Foot positions (N, 6, 3) in the body frame [m].
        motion: Joint angles (N, 6, 3).
        wrenches: K base wrenches at each sample (N, 6, K) [N, N·m].

    Returns:
        The forces (K, N, 6, 3) [N] and Jᵀf per leg (K, N, 6, 3) [N·m].

    """
    kinds, runs = wrenches.shape[-1], phases.runs
    starts = np.repeat([run.start for run in runs], [run.stop - run.start for run in runs])
    lead = np.argmax(phases.stance[starts], axis=1)  # a standing leg of each sample's run
    moved = feet[starts, lead] - feet[np.arange(len(feet)), lead]  # the body, since (N, 3)
    force, moment = wrenches[:, :3], wrenches[:, 3:]  # (N, 3, K) each
    about_start = np.empty((len(feet), 6, kinds))  # F, and M + moved × F: the same wrench
    about_start[:, :3] = force  # about the body's origin at its run's first sample
    turn = cross(moved[:, None], force.transpose(0, 2, 1))  # (N, K, 3)
    about_start[:, 3:] = moment + turn.transpose(0, 2, 1)
    forces = np.zeros((kinds, len(feet), 6, 3))  # each wrench's forces in one block
    for run in runs:  # the standing feet stay put: one set of rows serves the run
        legs = np.flatnonzero(phases.stance[run.start])
        rows, _ = equilibrium(feet[run.start, legs], np.zeros(3), 0.0, np.zeros(3))
        rhs = about_start[run].transpose(1, 0, 2).reshape(6, -1)  # (6, n·K)
        split = min_norm_forces(rows, rhs)  # (3·legs, n·K)
        forces[:, run, legs] = split.reshape(len(legs), 3, -1, kinds).transpose(3, 2, 0, 1)
    in_roots = frames.to_roots(forces, points=False)
    return forces, transpose_times(motion.partials, in_roots)


def min_torque_split(
    model: HexapodModel,
    frames: LegFrames,
    phases: GaitPhases,
    feet: ArrayF,
    motion: JointMotion,
    rnea: GeneralizedForces,
    period: float,
    friction: float,
) -> ForceSplit:
    """The statics' min-torque QP at each sample, at period T [s] (no inertial part)."""
    count, rated = len(feet), torque_scale(model.design.rated_torques)
    generalized = rnea.static + rnea.inertial / period**2
    joints = leg_rows(model, generalized)
    in_roots = foot_jacobian(frames.parameters, motion.angles)
    jacobian = np.einsum("lij,nljk->nlik", frames.root_rotations, in_roots)  # body frame
    forces = np.zeros((count, 6, 3))
    for k, legs in enumerate(stance_indices(phases)):
        a, _ = equilibrium(feet[k, legs], np.zeros(3), 0.0, np.zeros(3))
        blocks = np.zeros((3 * len(legs), 3 * len(legs)))
        for i, leg in enumerate(legs):
            blocks[3 * i : 3 * i + 3, 3 * i : 3 * i + 3] = jacobian[k, leg]
        solved = min_torque_forces(
            a, generalized[k, :6], blocks, joints[k, legs].ravel(), rated, friction
        )
        forces[k, legs] = solved.reshape(-1, 3)
    pushed = np.einsum("nlij,nli->nlj", jacobian, forces)
    zero = np.zeros_like(forces)
    return ForceSplit(forces, zero, joints - pushed, zero)
