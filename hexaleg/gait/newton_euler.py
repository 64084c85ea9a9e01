"""Inverse dynamics of the walking robot's legs, every sample of a period at once.

While the robot walks, its body neither turns nor accelerates: it translates at a
constant velocity. A frame moving so is inertial, so each leg's joint torques and the
wrench it puts on the body depend on that leg's own motion only, and the body's rows of
the generalized forces are its own weight plus the six legs' wrenches. The recursive
Newton–Euler algorithm (Featherstone, *Rigid Body Dynamics Algorithms*, 2008, §5.3)
then runs over the six three-joint chains for all N samples at once, with arrays of
shape (N, 6, 3): one pass instead of 2N calls of Pinocchio's ``rnea`` from Python, the
walks' inverse dynamics (:meth:`~hexaleg.gait.dynamics.LoadedRobot.generalized_forces`).

Geometry and inertias are read from the Pinocchio model (its joint placements, axes and
body inertias: the URDF's), never from the design. A model whose legs are not three
revolute joints in a row on the body (a robot file with other joints) gets ``None`` from
:func:`leg_chains`, and Pinocchio's per-sample ``rnea`` serves it. The tests hold this
module to Pinocchio's ``rnea`` on seeded designs, postures and motions, on a robot file
and on random general hexapods.

Spatial vectors are kept as their two 3-vector parts, in each joint's frame: a motion
by its angular part ω and the linear velocity of the frame's origin v; a force by its
linear part f and its moment n about the origin.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF

REVOLUTE = ("JointModelRX", "JointModelRY", "JointModelRZ", "JointModelRevoluteUnaligned")
"""Pinocchio's one-angle revolute joints (a continuous joint has two coordinates)."""
JOINTS_PER_LEG = 3
"""Root, hip and knee."""
ROOT = 1
"""The free-flyer's joint index in a Pinocchio model (0 is the universe)."""


@dataclass(frozen=True)
class LegBodies:
    """The legs' joints and bodies as Pinocchio has them, one array per quantity.

    Index order: leg (L, the model's ``leg_names``), then joint (3, root to knee).

    Attributes:
        rotations: Each joint frame's rotation in its parent's at zero angle (L, 3, 3, 3).
        translations: Its origin in its parent's frame (L, 3, 3) [m].
        axes: Its rotation axis, in its own frame (L, 3, 3) (unit).
        masses: The body it moves (L, 3) [kg].
        centers: That body's centre of mass in the joint frame (L, 3, 3) [m].
        inertias: Its rotational inertia about the centre (L, 3, 3, 3) [kg·m²].
        armatures: The joint's armature, the rotor's inertia seen at the joint (L, 3)
            [kg·m²]: its torque gains armature × acceleration, as in ``rnea``.
        base_mass: The body's (with anything carried on it) [kg].
        base_center: Its centre of mass in the body frame (3,) [m].

    """

    rotations: ArrayF
    translations: ArrayF
    axes: ArrayF
    masses: ArrayF
    centers: ArrayF
    inertias: ArrayF
    armatures: ArrayF
    base_mass: float
    base_center: ArrayF


@dataclass(frozen=True)
class LegForces:
    """Inverse dynamics over a period: what each joint and the body must supply.

    Attributes:
        torques: Each leg joint's generalized force (N, L, 3) [N·m].
        base: The body's six rows, linear then angular, in the body frame (N, 6) [N, N·m].

    """

    torques: ArrayF
    base: ArrayF


@dataclass(frozen=True)
class LegChains:
    """Which joints of a model make its legs' chains, and how they turn: its structure only.

    Attributes:
        joints: Every leg joint's index, leg by leg, root to knee (L·3,).
        axes: Each joint's rotation axis, in its own frame (L, 3, 3) (unit).
        velocities: Each joint's index in the model's velocity vector (L·3,).

    """

    joints: tuple[int, ...]
    axes: ArrayF
    velocities: tuple[int, ...]


def leg_chains(model: pin.Model, leg_joints: list[list[int]]) -> LegChains | None:
    """The chains of ``model``'s legs, or ``None`` if they are not this module's kind.

    They depend on the model's joints alone, not on its lengths or masses: every model of
    one body shares them (:meth:`~hexaleg.robot.model.HexapodModel.structural`).

    Args:
        model: A free-floating robot's Pinocchio model.
        leg_joints: Each leg's joint indices, root to knee.

    Returns:
        ``None`` unless every joint besides the universe and the free-flyer belongs to a
        leg, each leg is three one-angle revolute joints in a row hung on the body.

    """
    joints = [j for leg in leg_joints for j in leg]
    models, parents = list(model.joints), list(model.parents)  # read once: each read copies
    if models[ROOT].shortname() != "JointModelFreeFlyer" or sorted(joints) != list(
        range(ROOT + 1, model.njoints)
    ):
        return None
    for leg in leg_joints:
        if len(leg) != JOINTS_PER_LEG or [parents[j] for j in leg] != [ROOT, *leg[:-1]]:
            return None
    kinds = [models[j].shortname() for j in joints]
    if not set(kinds) <= set(REVOLUTE):
        return None
    axes = [
        _AXES[kind] if kind in _AXES else _axis(models[j].extract())
        for kind, j in zip(kinds, joints, strict=True)
    ]
    return LegChains(tuple(joints), _per_joint(axes), tuple(models[j].idx_v for j in joints))


def leg_bodies(model: pin.Model, chains: LegChains) -> LegBodies:
    """The bodies of ``model``'s legs, whose chains are ``chains`` (:func:`leg_chains`)."""
    joints = chains.joints
    placements, inertias = list(model.jointPlacements), list(model.inertias)
    frames = _per_joint([placements[j].homogeneous for j in joints])  # rotation | translation
    bodies = [inertias[j] for j in joints]
    base = inertias[ROOT]
    return LegBodies(
        rotations=np.ascontiguousarray(frames[..., :3, :3]),
        translations=np.ascontiguousarray(frames[..., :3, 3]),
        axes=chains.axes,
        masses=_per_joint([inertia.mass for inertia in bodies]),
        centers=_per_joint([inertia.lever for inertia in bodies]),
        inertias=_per_joint([inertia.inertia for inertia in bodies]),
        armatures=_per_joint(np.asarray(model.armature)[list(chains.velocities)]),
        base_mass=float(base.mass),
        base_center=np.array(base.lever, dtype=float),
    )


def _per_joint(values: npt.ArrayLike) -> ArrayF:
    """Values of the legs' joints in leg order, as (6, 3, ...)."""
    array = np.array(values, dtype=float)
    return array.reshape(-1, JOINTS_PER_LEG, *array.shape[1:])


_AXES: dict[str, ArrayF] = {
    "JointModelRX": np.array([1.0, 0.0, 0.0]),
    "JointModelRY": np.array([0.0, 1.0, 0.0]),
    "JointModelRZ": np.array([0.0, 0.0, 1.0]),
}
"""The axes of the revolute joints that name theirs; an unaligned one carries its own."""


def _axis(joint: object) -> ArrayF:
    """A one-angle revolute joint's axis in its own frame (unit)."""
    axis = getattr(joint, "axis", None)  # unaligned; RX, RY, RZ name theirs
    found = joint.getMotionAxis() if axis is None else axis  # type: ignore[attr-defined]
    return np.array(found, dtype=np.float64)


def leg_forces(
    bodies: LegBodies,
    angles: ArrayF,
    rates: ArrayF,
    accelerations: ArrayF,
    base_velocity: ArrayF,
    gravity: ArrayF,
) -> tuple[LegForces, LegForces]:
    """Recursive Newton–Euler over every leg and sample: Pinocchio's ``rnea``, batched.

    The body moves at ``base_velocity`` without turning or accelerating. The forces come
    in two parts, as the walks use them: the static part holds the robot still in
    gravity, ``rnea(q, 0, 0)`` (Pinocchio's ``computeGeneralizedGravity``), the inertial
    part moves it without gravity, ``rnea(q, v, a)`` at zero gravity.

    Args:
        bodies: The legs (:func:`leg_bodies`).
        angles: Joint coordinates q (N, L, 3) [rad].
        rates: Their rates (N, L, 3) [rad/s].
        accelerations: Their accelerations (N, L, 3) [rad/s²].
        base_velocity: The body's linear velocity in its own frame (3,) [m/s].
        gravity: Gravitational acceleration in the body frame (3,) [m/s²].

    Returns:
        The static part and the inertial part.

    """
    torques = np.empty((2, *np.shape(angles)))
    base = np.zeros((2, len(angles), 6))  # the body's own weight, then the legs' wrenches
    base[0, :, :3] = -bodies.base_mass * np.asarray(gravity, dtype=float)
    base[0, :, 3:] = _cross(_vector(bodies.base_center), _vector(base[0, 0, :3]))
    _newton_euler(
        bodies.rotations,
        bodies.translations,
        bodies.axes,
        bodies.masses,
        bodies.centers,
        bodies.inertias,
        bodies.armatures,
        np.ascontiguousarray(angles, dtype=float),
        np.ascontiguousarray(rates, dtype=float),
        np.ascontiguousarray(accelerations, dtype=float),
        np.asarray(base_velocity, dtype=float),
        np.asarray(gravity, dtype=float),
        bodies.base_mass,
        bodies.base_center,
        torques,
        base,
    )
    return LegForces(torques[0], base[0]), LegForces(torques[1], base[1])


@compiled
def _newton_euler(
    rotations: ArrayF,
    translations: ArrayF,
    axes: ArrayF,
    masses: ArrayF,
    centers: ArrayF,
    inertias: ArrayF,
    armatures: ArrayF,
    angles: ArrayF,
    rates: ArrayF,
    accelerations: ArrayF,
    base_velocity: ArrayF,
    gravity: ArrayF,
    base_mass: float,
    base_center: ArrayF,
    torques: ArrayF,
    base: ArrayF,
) -> None:  # pragma: no cover - compiled; tested against Pinocchio's rnea
    """:func:`leg_forces`' work: fills ``torques`` (2, N, L, 3), adds the legs to ``base``.

    Index 0 is the static part: at rest in gravity, every body's acceleration is the
    upward −g carried down the chain. Index 1 the inertial part, moving without gravity.
    The body neither turns nor accelerates. Joint by joint, the forward pass runs over
    every sample (:func:`_forward`), keeping each joint's rotation in its parent's frame
    (``frame``) and each body's I·a + v ×* (I·v) per part in its joint's frame
    (``forces``) for the backward pass (:func:`_carry_up`).
    """
    count, legs, joints = angles.shape
    frame = np.empty((joints, count, 3, 3))
    forces = np.empty((2, joints, 2, count, 3))
    state = np.empty((5, count, 3))  # ω, v, α, the origin's acceleration, upward gravity
    for leg in range(legs):
        for n in range(count):
            for i in range(3):
                state[0, n, i] = state[2, n, i] = state[3, n, i] = 0.0
                state[1, n, i], state[4, n, i] = base_velocity[i], -gravity[i]
        for k in range(joints):
            _forward(
                rotations[leg, k],
                translations[leg, k],
                axes[leg, k],
                masses[leg, k],
                centers[leg, k],
                inertias[leg, k],
                angles[:, leg, k],
                rates[:, leg, k],
                accelerations[:, leg, k],
                state,
                frame[k],
                forces[:, k],
            )
        for n in range(count):
            _carry_up(translations, axes, frame, forces, torques, base, n, leg)
        for k in range(joints):
            for n in range(count):
                torques[1, n, leg, k] += armatures[leg, k] * accelerations[n, leg, k]


@compiled
def _forward(
    placement: ArrayF,
    offset: ArrayF,
    axis: ArrayF,
    mass: float,
    center: ArrayF,
    inertia: ArrayF,
    angles: ArrayF,
    rates: ArrayF,
    accelerations: ArrayF,
    state: ArrayF,
    frame: ArrayF,
    forces: ArrayF,
) -> None:  # pragma: no cover - compiled
    """One joint's forward pass over every sample: its frames, its body's forces per part.

    ``state`` (ω, v, α, the origin's linear acceleration, upward gravity; each (N, 3)) is
    the parent's motion, carried to this joint's frame and given its own; ``frame`` (N, 3,
    3) receives the joint's rotations, ``forces`` (2, 2, N, 3) its body's force and moment.
    """
    turn_axis, lever, middle = _vector(axis), _vector(offset), _vector(center)
    omega, velocity, alpha, linear, lifted = state[0], state[1], state[2], state[3], state[4]
    for n in range(len(angles)):
        turn = frame[n]
        _joint_frame(placement, turn_axis, angles[n], turn)
        spin = _scale(rates[n], turn_axis)
        # the parent's motion carried to this joint's frame, then the joint's own
        up = _inverse_rotate(turn, _get(lifted, n))
        omega_n, alpha_n = _get(omega, n), _get(alpha, n)
        moving = _inverse_rotate(turn, _add(_get(velocity, n), _cross(omega_n, lever)))
        along = _inverse_rotate(turn, _add(_get(linear, n), _cross(alpha_n, lever)))
        omega_n = _add(_inverse_rotate(turn, omega_n), spin)
        driven = _add(_inverse_rotate(turn, alpha_n), _scale(accelerations[n], turn_axis))
        alpha_n = _add(driven, _cross(omega_n, spin))
        along = _add(along, _cross(moving, spin))
        _put(lifted, n, up)
        _put(omega, n, omega_n)
        _put(velocity, n, moving)
        _put(alpha, n, alpha_n)
        _put(linear, n, along)
        momentum = _scale(mass, _add(moving, _cross(omega_n, middle)))
        angular = _add(_rotate(inertia, omega_n), _cross(middle, momentum))
        force = _scale(mass, _add(along, _cross(alpha_n, middle)))
        moment = _add(_rotate(inertia, alpha_n), _cross(middle, force))
        force = _add(force, _cross(omega_n, momentum))
        moment = _add(_add(moment, _cross(omega_n, angular)), _cross(moving, momentum))
        weight = _scale(mass, up)
        _put(forces[0, 0], n, weight)
        _put(forces[0, 1], n, _cross(middle, weight))
        _put(forces[1, 0], n, force)
        _put(forces[1, 1], n, moment)


@compiled
def _carry_up(
    translations: ArrayF,
    axes: ArrayF,
    frame: ArrayF,
    forces: ArrayF,
    torques: ArrayF,
    base: ArrayF,
    n: int,
    leg: int,
) -> None:  # pragma: no cover - compiled
    """Leg ``leg``'s backward pass at sample ``n``, both parts: torques, wrench on the body."""
    static, static_moment = (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    force, moment = (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    for k in range(forces.shape[1] - 1, -1, -1):
        turn, axis, offset = frame[k, n], _vector(axes[leg, k]), _vector(translations[leg, k])
        static = _add(static, _get(forces[0, k, 0], n))
        static_moment = _add(static_moment, _get(forces[0, k, 1], n))
        force = _add(force, _get(forces[1, k, 0], n))
        moment = _add(moment, _get(forces[1, k, 1], n))
        torques[0, n, leg, k] = _dot(axis, static_moment)
        torques[1, n, leg, k] = _dot(axis, moment)
        static = _rotate(turn, static)
        static_moment = _add(_rotate(turn, static_moment), _cross(offset, static))
        force = _rotate(turn, force)
        moment = _add(_rotate(turn, moment), _cross(offset, force))
    for part, (pushed, turned) in enumerate(((static, static_moment), (force, moment))):
        for i in range(3):
            base[part, n, i] += pushed[i]
            base[part, n, 3 + i] += turned[i]


Vector = tuple[float, float, float]


@compiled
def _get(rows: ArrayF, n: int) -> Vector:  # pragma: no cover - compiled
    """Row ``n`` of an (N, 3) array as a tuple."""
    return (rows[n, 0], rows[n, 1], rows[n, 2])


@compiled
def _put(rows: ArrayF, n: int, value: Vector) -> None:  # pragma: no cover - compiled
    """``value`` into row ``n`` of an (N, 3) array."""
    rows[n, 0], rows[n, 1], rows[n, 2] = value[0], value[1], value[2]


@compiled
def _vector(a: ArrayF) -> Vector:  # pragma: no cover - compiled
    """A 3-array as a tuple."""
    return (a[0], a[1], a[2])


@compiled
def _add(a: Vector, b: Vector) -> Vector:  # pragma: no cover - compiled
    """A + b."""
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


@compiled
def _scale(s: float, a: Vector) -> Vector:  # pragma: no cover - compiled
    """s·a."""
    return (s * a[0], s * a[1], s * a[2])


@compiled
def _dot(a: Vector, b: Vector) -> float:  # pragma: no cover - compiled
    """A · b."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@compiled
def _cross(a: Vector, b: Vector) -> Vector:  # pragma: no cover - compiled
    """A × b."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@compiled
def _rotate(matrix: ArrayF, a: Vector) -> Vector:  # pragma: no cover - compiled
    """M·a of a 3 × 3 array."""
    return (
        matrix[0, 0] * a[0] + matrix[0, 1] * a[1] + matrix[0, 2] * a[2],
        matrix[1, 0] * a[0] + matrix[1, 1] * a[1] + matrix[1, 2] * a[2],
        matrix[2, 0] * a[0] + matrix[2, 1] * a[1] + matrix[2, 2] * a[2],
    )


@compiled
def _inverse_rotate(rotation: ArrayF, a: Vector) -> Vector:  # pragma: no cover - compiled
    """Rᵀ·a: a parent-frame vector in the child's frame."""
    return (
        rotation[0, 0] * a[0] + rotation[1, 0] * a[1] + rotation[2, 0] * a[2],
        rotation[0, 1] * a[0] + rotation[1, 1] * a[1] + rotation[2, 1] * a[2],
        rotation[0, 2] * a[0] + rotation[1, 2] * a[1] + rotation[2, 2] * a[2],
    )


@compiled
def _joint_frame(
    placement: ArrayF, axis: Vector, angle: float, out: ArrayF
) -> None:  # pragma: no cover - compiled
    """Placement · Rot(axis, angle) into ``out``: Rodrigues' formula for the joint's turn."""
    x, y, z = axis
    s, c = np.sin(angle), np.cos(angle)
    t = 1.0 - c
    turn = (
        (c + t * x * x, t * x * y - s * z, t * x * z + s * y),
        (t * x * y + s * z, c + t * y * y, t * y * z - s * x),
        (t * x * z - s * y, t * y * z + s * x, c + t * z * z),
    )
    for i in range(3):
        for j in range(3):
            out[i, j] = (
                placement[i, 0] * turn[0][j]
                + placement[i, 1] * turn[1][j]
                + placement[i, 2] * turn[2][j]
            )
