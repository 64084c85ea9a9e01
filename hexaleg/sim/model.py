"""hexaleg's URDF in MuJoCo: free-floating body, floor, contact feet, servo actuators, payload.

:func:`robot_spec` loads the very URDF the Pinocchio model is built from through
``mujoco.MjSpec`` (static links kept, so every URDF link is a MuJoCo body with the
URDF's mass and inertia) and adds what a URDF does not say:

- a free joint on ``base_link`` and a floor plane. Each foot gets a contact sphere of
  the URDF foot's own radius, centred on the foot frame; the floor lies one radius
  below z = 0, so a foot frame planned on the ground (z = 0) is a sphere resting on
  the floor and every height matches the Pinocchio model's;
- the payload (:class:`~hexaleg.statics.forces.Payload`) as a point mass welded to the
  body at its point;
- one servo per leg joint (:class:`ServoGains`), a MuJoCo position actuator fed so that
  its torque is τ = τ_ff + k_p (q_ref − q) + k_d (q̇_ref − q̇): the plan's
  feed-forward torque plus a PD on the tracking error. The URDF's effort (the rated
  torque) does not clamp it, so the measured torque is what the simulated robot needs;
  each joint's ``armature`` is its actuator's reflected rotor inertia N²·J, as in the
  Pinocchio model.

Only the feet touch the floor and the robot does not collide with itself: contacts
between the leg links are the collision analysis' business (:mod:`hexaleg.stance.collisions`).

The URDF loaded is the model's :attr:`~hexaleg.robot.model.HexapodModel.simulation_urdf`:
a robot file's is its links, masses, inertias and joints without the file's visual and
collision shapes (meshes MuJoCo would have to find; only the feet touch the floor), each
foot a sphere on its foot point (:mod:`.feet`). The servos act on the model's own joints:
the plan's angles, rates and torques on hexaleg's θ are mapped by the model's
q = s·θ + o (the identity on the templates), and what the servos measure is mapped back.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._checks import require_in_range
from hexaleg._typing import ArrayF
from hexaleg.exceptions import ParameterError
from hexaleg.gravity import GRAVITY
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.model import ROOT_JOINT, HexapodModel
from hexaleg.sim._mujoco import compiled, refusal, require_mujoco
from hexaleg.sim.feet import (
    contact_body,
    contact_geom_name,
    frame_name,
    leg_joint_names,
)
from hexaleg.statics.forces import DEFAULT_FRICTION, Payload, check_friction

TIMESTEP = 1e-3
"""Simulation time step [s]."""
DEFAULT_BANDWIDTH = 2.0
"""Servo bandwidth f [Hz]: the natural frequency of a standing leg's joint (see
:meth:`ServoGains.from_bandwidth`). Stiffer servos track more closely but, with three
feet planted, push the feet against each other: the measured torque peaks then grow
past the plan's."""
DEFAULT_DAMPING_RATIO = 1.0
"""Servo damping ratio ζ [-] (critically damped)."""
FLOOR = "floor"
"""Name of the floor geom."""
PAYLOAD_BODY = "payload"
"""Name of the payload's body."""
ROBOT_CONTACT, FLOOR_CONTACT = 1, 2
"""Contact bits: robot geoms collide with the floor only, never with each other."""


MAX_GAIN = 1e9
"""Largest servo stiffness [N·m/rad] and damping [N·m·s/rad]: stiffer servos make MuJoCo's
position actuators stiff beyond what its step resolves."""


@dataclass(frozen=True)
class ServoGains:
    """Stiffness and damping of the joint servos, per joint type (root, hip, knee).

    Attributes:
        stiffness: k_p per joint type [N·m/rad].
        damping: k_d per joint type [N·m·s/rad].

    """

    stiffness: tuple[float, float, float]
    damping: tuple[float, float, float]

    def __post_init__(self) -> None:
        for name, lower, unit in (("stiffness", 1e-6, "N·m/rad"), ("damping", 0.0, "N·m·s/rad")):
            values = tuple(
                require_in_range(f"{name}.{joint}", value, lower, MAX_GAIN, unit)
                for joint, value in zip(LEG_JOINTS, getattr(self, name), strict=True)
            )
            object.__setattr__(self, name, values)

    @classmethod
    def from_bandwidth(
        cls,
        model: HexapodModel,
        bandwidth: float = DEFAULT_BANDWIDTH,
        damping_ratio: float = DEFAULT_DAMPING_RATIO,
    ) -> ServoGains:
        """Gains giving each joint of a standing leg the natural frequency f.

        With I the joint's reflected inertia (:func:`reflected_inertia`: its own leg and
        the third of the robot a tripod foot carries), ω = 2π f: k_p = I ω²,
        k_d = 2 ζ I ω. A swinging leg, lighter, answers faster; the feed-forward torque
        carries the load, the servo corrects what the plan did not foresee.

        Args:
            model: The hexapod's Pinocchio model.
            bandwidth: Natural frequency f [Hz], in (0, 100].
            damping_ratio: Damping ratio ζ [-], in [0, 10].

        """
        require_in_range("bandwidth", bandwidth, 1e-3, 100.0, "Hz")
        require_in_range("damping_ratio", damping_ratio, 0.0, 10.0, "-")
        omega = 2 * math.pi * bandwidth
        root, hip, knee = (float(i) for i in reflected_inertia(model))
        stiff, damp = omega**2, 2 * damping_ratio * omega
        if max(root, hip, knee) * stiff > MAX_GAIN:  # the design, not the gains, is at fault
            raise ParameterError(
                "l1, l2, l3",
                model.design.lengths,
                f"too large to simulate: a {bandwidth:g} Hz servo on legs this heavy needs a "
                f"stiffness of {max(root, hip, knee) * stiff:.3g} N·m/rad, beyond {MAX_GAIN:g}",
            )
        return cls(
            (root * stiff, hip * stiff, knee * stiff), (root * damp, hip * damp, knee * damp)
        )


def reflected_inertia(model: HexapodModel, carried: float | None = None) -> ArrayF:
    """Each joint type's inertia about its axis at the nominal stance [kg·m²] (3,).

    A standing leg moves its own links and the share of the robot it carries: with
    the foot planted, turning joint j at θ̇_j moves that share at the foot's speed
    |J_j|·θ̇_j (J_j the j-th column of the foot Jacobian). So
    I_j = M_jj + m·|J_j|², M the joint-space inertia matrix (Pinocchio's CRBA), m the
    carried mass; largest over the legs.

    Args:
        model: The hexapod's Pinocchio model.
        carried: Mass a standing foot carries [kg]; a third of the robot's (a tripod)
            if omitted.

    """
    q = model.nominal_configuration()
    if carried is None:
        carried = float(pin.computeTotalMass(model.model)) / 3
    mass_matrix = np.diag(pin.crba(model.model, model.data, q))
    inertia = np.array(
        [
            mass_matrix[model.leg_v_indices(leg)]
            + carried * (model.leg_foot_jacobian(q, leg) ** 2).sum(axis=0)
            for leg in model.leg_names
        ]
    )
    return np.asarray(inertia.max(axis=0), dtype=float)


def robot_spec(
    model: HexapodModel,
    payload: Payload | None = None,
    friction: float = DEFAULT_FRICTION,
    gains: ServoGains | None = None,
    timestep: float = TIMESTEP,
) -> Any:
    """The ``mujoco.MjSpec`` of the hexapod on its floor (see the module docstring).

    Args:
        model: The hexapod's Pinocchio model (its URDF is loaded).
        payload: A point mass on the body.
        friction: Coefficient of friction μ between feet and floor [-].
        gains: Joint servo gains; :meth:`ServoGains.from_bandwidth` if omitted.
        timestep: Integration step [s].

    """
    mujoco = require_mujoco()
    check_friction(friction)
    require_in_range("timestep", timestep, 1e-5, 1e-2, "s")
    gains = ServoGains.from_bandwidth(model) if gains is None else gains
    spec = _parsed(mujoco, model.simulation_urdf)
    spec.compiler.fusestatic = False  # keep every link (the feet) as its own body
    spec.option.timestep = timestep
    spec.option.gravity = [0.0, 0.0, -GRAVITY]
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
    base = spec.body(frame_name(model, model.base_frame))
    base.add_freejoint(name=ROOT_JOINT)
    for geom in spec.geoms:  # the URDF's collision shapes: touch the floor, not each other
        geom.contype, geom.conaffinity = ROBOT_CONTACT, 0
    radius = model.contact_radius(model.leg_names[0])
    spec.worldbody.add_geom(
        name=FLOOR,
        type=mujoco.mjtGeom.mjGEOM_PLANE,
        size=[0.0, 0.0, 1.0],
        pos=[0.0, 0.0, -radius],
        contype=0,
        conaffinity=FLOOR_CONTACT | ROBOT_CONTACT,
        rgba=[0.8, 0.8, 0.8, 1.0],
    )
    for leg in model.leg_names:
        body, at = contact_body(spec.body(frame_name(model, model.foot_frame_id(leg))))
        body.add_geom(
            name=contact_geom_name(leg),
            type=mujoco.mjtGeom.mjGEOM_SPHERE,
            size=[model.contact_radius(leg), 0.0, 0.0],
            pos=at.tolist(),
            contype=ROBOT_CONTACT,
            conaffinity=0,
            condim=3,
            friction=[friction, 0.0, 0.0],
            mass=0.0,  # the URDF's foot inertial is the foot's mass
            rgba=[0.1, 0.1, 0.1, 1.0],
        )
    _add_payload(spec, model, payload or Payload())
    _add_servos(spec, model, gains)
    return spec


def _parsed(mujoco: Any, urdf: str) -> Any:
    """MuJoCo's spec of URDF text; its refusal in one line naming the link."""
    try:
        return mujoco.MjSpec.from_string(urdf)
    except ValueError as err:
        raise refusal(err) from None


def _add_payload(spec: Any, model: HexapodModel, payload: Payload) -> None:
    if payload.mass > 0:
        spec.body(frame_name(model, model.base_frame)).add_body(
            name=PAYLOAD_BODY,
            pos=payload.point(model).tolist(),
            mass=payload.mass,
            ipos=[0.0, 0.0, 0.0],  # a point mass: its centre at the body's origin, no inertia
            inertia=[0.0, 0.0, 0.0],
            explicitinertial=True,
        )


def _add_servos(spec: Any, model: HexapodModel, gains: ServoGains) -> None:
    mujoco = require_mujoco()
    for joint in spec.joints:
        joint.actfrclimited = mujoco.mjtLimited.mjLIMITED_FALSE  # the rating clamps nothing
    armatures = model.design.actuators.armatures if model.design.actuators else (0.0, 0.0, 0.0)
    for leg in model.leg_names:
        for name, kp, kd, armature in zip(
            leg_joint_names(model, leg), gains.stiffness, gains.damping, armatures, strict=True
        ):
            spec.joint(name).armature = armature  # the rotor's N²·J, as Pinocchio's
            actuator = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            actuator.set_to_position(kp=kp, kv=kd)


class SimModel:
    """The compiled MuJoCo model of a hexapod and where each leg lives in it.

    Args:
        model: The hexapod's Pinocchio model.
        payload: A point mass on the body.
        friction: Coefficient of friction μ between feet and floor [-].
        gains: Joint servo gains; :meth:`ServoGains.from_bandwidth` if omitted.
        timestep: Integration step [s].

    Attributes:
        hexapod: The Pinocchio model it was built from.
        payload: The payload carried.
        gains: The joint servo gains.
        spec: The ``mujoco.MjSpec`` it was compiled from.
        mj: The compiled ``mujoco.MjModel``.
        qpos: Address of each leg joint in ``qpos`` (legs, 3), Pinocchio's leg order.
        dof: Address of each leg joint in ``qvel`` (legs, 3).
        actuators: Actuator id of each leg joint (legs, 3).
        feet: Body id of each foot (legs,).
        contacts: Geom id of each foot's contact sphere (legs,).
        floor: Geom id of the floor.
        base: Body id of the body link (``base_link``; an imported robot's ``hexaleg_body``).
        signs: Each leg joint's dq/dθ (legs, 3), s of q = s·θ + o (all 1 for hexaleg's URDF).
        offsets: Each leg joint's o (legs, 3) [rad].

    """

    def __init__(
        self,
        model: HexapodModel,
        payload: Payload | None = None,
        friction: float = DEFAULT_FRICTION,
        gains: ServoGains | None = None,
        timestep: float = TIMESTEP,
    ) -> None:
        mujoco = require_mujoco()
        self.hexapod = model
        self.payload = payload or Payload()
        self.gains = ServoGains.from_bandwidth(model) if gains is None else gains
        self.spec = robot_spec(model, self.payload, friction, self.gains, timestep)
        self.mj = compiled(self.spec)

        def ids(kind: Any, names: list[list[str]] | list[str]) -> npt.NDArray[np.int_]:
            found = np.vectorize(lambda n: mujoco.mj_name2id(self.mj, kind, n))(names)
            return np.asarray(found, dtype=int)

        legs = model.leg_names
        names = [list(leg_joint_names(model, leg)) for leg in legs]
        joints = ids(mujoco.mjtObj.mjOBJ_JOINT, names)
        self.qpos = self.mj.jnt_qposadr[joints]
        self.dof = self.mj.jnt_dofadr[joints]
        self.actuators = ids(mujoco.mjtObj.mjOBJ_ACTUATOR, names)
        body = mujoco.mjtObj.mjOBJ_BODY
        self.feet = ids(body, [frame_name(model, model.foot_frame_id(leg)) for leg in legs])
        self.contacts = ids(mujoco.mjtObj.mjOBJ_GEOM, [contact_geom_name(leg) for leg in legs])
        self.floor = int(mujoco.mj_name2id(self.mj, mujoco.mjtObj.mjOBJ_GEOM, FLOOR))
        self.base = int(mujoco.mj_name2id(self.mj, body, frame_name(model, model.base_frame)))
        self.signs = np.array([model.joint_signs(leg) for leg in legs])
        self.offsets = np.array([model.joint_values(leg, np.zeros(3)) for leg in legs])
        self._q_index = np.array([model.leg_q_indices(leg) for leg in legs])
        self.stiffness = np.tile(self.gains.stiffness, (len(model.leg_names), 1))
        self.damping = np.tile(self.gains.damping, (len(model.leg_names), 1))

    @property
    def timestep(self) -> float:
        """Integration step [s]."""
        return float(self.mj.opt.timestep)

    def qpos_of(self, q: npt.ArrayLike) -> ArrayF:
        """MuJoCo ``qpos`` of a Pinocchio configuration (quaternion w first in MuJoCo)."""
        q = np.asarray(q, dtype=float)
        qpos = np.zeros(self.mj.nq)
        qpos[:3] = q[:3]
        qpos[3], qpos[4:7] = q[6], q[3:6]
        qpos[self.qpos] = q[self._q_index]  # the same URDF joints: the same values
        return qpos

    def configuration_of(self, qpos: npt.ArrayLike) -> ArrayF:
        """Pinocchio configuration of a MuJoCo ``qpos`` (the inverse of :meth:`qpos_of`)."""
        qpos = np.asarray(qpos, dtype=float)
        base = np.concatenate((qpos[:3], qpos[4:7], qpos[3:4]))
        base[3:] /= np.linalg.norm(base[3:])
        q = self.hexapod.configuration(pin.XYZQUATToSE3(base))
        q[self._q_index] = qpos[self.qpos]
        return q

    def angles_of(self, values: npt.ArrayLike) -> ArrayF:
        """Hexaleg's angles θ = s·(q − o) (..., legs, 3) [rad] of the joints' values q."""
        theta: ArrayF = self.signs * (np.asarray(values, dtype=float) - self.offsets)
        return theta

    def command(self, q_ref: ArrayF, v_ref: ArrayF, torque: ArrayF) -> ArrayF:
        """Actuator controls (legs·3,) giving τ_ff + k_p (q_ref − q) + k_d (q̇_ref − q̇).

        Args:
            q_ref: Joint angles θ to track (..., legs, 3) [rad].
            v_ref: Joint speeds θ̇ to track (..., legs, 3) [rad/s].
            torque: Feed-forward torques on θ (..., legs, 3) [N·m].

        Each is mapped onto the model's joints (q = s·θ + o, q̇ = s·θ̇, s·τ).

        """
        # A position actuator gives k_p (u − q) − k_d q̇; shifting its set-point u by
        # (k_d q̇_ref + τ_ff) / k_p adds the reference speed's damping and the feed-forward.
        s = self.signs
        u = s * q_ref + self.offsets + (self.damping * (s * v_ref) + s * torque) / self.stiffness
        out = np.empty((*u.shape[:-2], self.mj.nu))
        out[..., self.actuators] = u
        return out
