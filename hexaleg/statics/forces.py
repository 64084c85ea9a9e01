"""Foot forces and joint torques holding a pose, with an optional payload.

Gravity g (:data:`~hexaleg.gravity.GRAVITY`) along −z of the ground frame (tilted on a
slope). Masses and centres of mass come from the URDF through Pinocchio, plus an optional
payload, a point mass on the body. The stance feet's forces f_i [N] (ground frame) balance
gravity: Σ f_i + M·g = 0 and Σ (p_i − c) × f_i = 0 about the whole centre of mass c.
Two distributions:

- ``"min-norm"``: the unique minimum of Σ|f_i|² subject to those six equations;
- ``"min-torque"``: the minimum of Σ (τ_j / rated_j)² subject to equilibrium, f_z ≥ 0
  and a friction pyramid |f_x|, |f_y| ≤ μ·f_z, a QP solved by ProxQP through qpsolvers.

Joint torques follow Pinocchio's convention τ = g(q) − Σ J_iᵀ f_i (the payload's
weight enters through the body's Jacobian at its point); the free-flyer rows of τ
vanish at equilibrium. The stability margin is the signed distance [m] from where the
gravity line through c meets the ground to the nearest edge of the support polygon
(positive inside).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
import pinocchio as pin
import qpsolvers

from hexaleg._checks import require_in_range, require_numbers
from hexaleg._typing import ArrayF, Distribution, require_choice
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.gravity import GRAVITY, LEVEL_GRAVITY
from hexaleg.limits import LEG_JOINTS
from hexaleg.ratings import torque_scale
from hexaleg.robot.imported_model import robot_mass
from hexaleg.robot.model import HexapodModel
from hexaleg.statics.ratings import check_safety_factor
from hexaleg.statics.support import SupportPolygon, ground_point

DEFAULT_FRICTION = 0.6
"""Default friction coefficient μ between feet and ground [-]."""
FRICTION_RANGE = (1e-3, 10.0)
"""Friction coefficients μ [-] every analysis takes: positive (a foot on ice still pushes
sideways a little, and MuJoCo needs μ > 0), at most 10 (beyond any real pair of surfaces)."""
GRAVITY_RANGE = (0.01, 1000.0)
"""Gravitational accelerations g [m/s²] the dynamics take: from a small asteroid's to a
hundred Earths' (a gait's forces divide by g, so none is zero)."""


def check_friction(friction: float) -> float:
    """``friction`` as a float, if it lies in :data:`FRICTION_RANGE`; else a ParameterError."""
    return require_in_range("friction", friction, *FRICTION_RANGE, "-")


def check_gravity(gravity: float) -> float:
    """``gravity`` as a float, if it lies in :data:`GRAVITY_RANGE`; else a ParameterError."""
    return require_in_range("gravity", gravity, *GRAVITY_RANGE, "m/s²")


QP_SOLVER = "proxqp"
"""The qpsolvers backend of the min-torque distribution (ProxSuite, from Pinocchio's lab)."""
PAYLOAD_SEARCH_LIMIT = 1e4
"""Largest payload the capacity search considers [kg]."""
PAYLOAD_REACH = 100.0
"""Largest |x|, |y|, |z| of a payload's position in the body frame [m] (as a design's lengths)."""


@dataclass(frozen=True)
class Payload:
    """A point mass carried by the body.

    Attributes:
        mass: Payload mass [kg] (0 for none).
        position: Where it sits in the body frame [m]; None means the centre of the
            body's top face.

    """

    mass: float = 0.0
    position: tuple[float, float, float] | None = None

    def __post_init__(self) -> None:
        mass = require_in_range("payload mass", self.mass, 0.0, PAYLOAD_SEARCH_LIMIT, "kg")
        object.__setattr__(self, "mass", mass)
        if self.position is not None:
            given = require_numbers("payload position", self.position, "xyz", "body-frame [m]")
            position = tuple(
                require_in_range(f"payload position.{axis}", v, -PAYLOAD_REACH, PAYLOAD_REACH, "m")
                for axis, v in zip("xyz", given, strict=True)
            )
            object.__setattr__(self, "position", position)

    def point(self, model: HexapodModel) -> ArrayF:
        """The payload's position in the body frame [m]."""
        return np.array(self.position_on(model.design))

    def position_on(self, design: HexapodDesign) -> list[float]:
        """Where the payload sits on ``design``'s body [m], body frame (default: top centre)."""
        if self.position is not None:
            return list(self.position)
        return [0.0, 0.0, design.body_height / 2]

    def to_dict(self, design: HexapodDesign) -> dict[str, Any]:
        """JSON-ready: the mass [kg] and where it sits on ``design``'s body [m]."""
        return {"mass": self.mass, "position": self.position_on(design)}

    def with_mass(self, mass: float) -> Payload:
        """The same point with another mass [kg]."""
        return Payload(mass, self.position)


@dataclass(frozen=True)
class StaticState:
    """Forces and torques holding one pose.

    Attributes:
        legs: Stance legs.
        foot_forces: Force on each stance foot from the ground (N, 3), ground frame [N].
        joint_torques: Torque of each stance leg's (root, hip, knee) (N, 3) [N·m].
        com: Centre of mass of robot and payload, ground frame [m].
        mass: Total mass, payload included [kg].
        stability_margin: Signed distance from the gravity line's ground point to the
            support polygon's nearest edge [m] (positive inside).
        free_flyer_residual: Largest |τ| on the free-flyer rows [N or N·m] (0 at equilibrium).

    """

    legs: tuple[str, ...]
    foot_forces: ArrayF
    joint_torques: ArrayF
    com: ArrayF
    mass: float
    stability_margin: float
    free_flyer_residual: float

    @property
    def weight(self) -> float:
        """The weight of robot and payload, mass · :data:`GRAVITY` [N]."""
        return self.mass * GRAVITY

    def torque_ratios(self, rated: ArrayF) -> ArrayF:
        """|τ| / rated per stance leg and joint (N, 3) [-]."""
        return np.abs(self.joint_torques) / rated

    def peak_torques(self) -> dict[str, float]:
        """Largest |τ| over the stance legs per joint type [N·m]."""
        peaks = np.abs(self.joint_torques).max(axis=0)
        return {joint: float(peak) for joint, peak in zip(LEG_JOINTS, peaks, strict=True)}


class Statics:
    """Statics of one robot standing on a set of legs, at any configuration.

    Args:
        model: The hexapod's Pinocchio model (masses from its URDF).
        legs: Stance legs.
        payload: A point mass on the body.
        friction: Friction coefficient μ [-] (min-torque distribution and slopes).
        safety_factor: F ≥ 1 [-]: every joint is held within its rated torque / F
            (:attr:`rated`: the payload capacity, the slopes' torque limits).

    """

    def __init__(
        self,
        model: HexapodModel,
        legs: Sequence[str],
        payload: Payload | None = None,
        friction: float = DEFAULT_FRICTION,
        safety_factor: float = 1.0,
    ) -> None:
        friction = check_friction(friction)
        self.model = model
        self.legs = tuple(legs)
        self.payload = payload or Payload()
        self.friction = friction
        self.safety_factor = check_safety_factor(safety_factor)
        self.rated = torque_scale(model.design.rated_torques) / self.safety_factor
        self._feet = [model.foot_frame_id(leg) for leg in self.legs]
        self._v = np.array([model.leg_v_indices(leg) for leg in self.legs])  # (N, 3)
        self._signs = np.array([model.joint_signs(leg) for leg in self.legs])  # torques on θ
        self._robot_mass = robot_mass(model)
        self._support: SupportPolygon | None = None
        self._support_feet = np.zeros((len(self.legs), 2))
        self._downward = LEVEL_GRAVITY

    @property
    def support(self) -> SupportPolygon:
        """The stance feet's support polygon (planted feet do not move)."""
        if self._support is None:
            self.state(self.model.nominal_configuration())
        assert self._support is not None
        return self._support

    def _polygon(self, feet_xy: ArrayF) -> SupportPolygon:
        """The support polygon, computed once: planted feet do not move."""
        support = self._support
        if support is None or np.abs(self._support_feet - feet_xy).max() > 1e-12:
            self._support_feet = feet_xy.copy()
            self._support = support = SupportPolygon.of_feet(feet_xy)
        return support

    def state(
        self,
        q: npt.ArrayLike,
        distribution: Distribution = "min-norm",
        gravity: npt.ArrayLike = LEVEL_GRAVITY,
        payload: Payload | None = None,
    ) -> StaticState:
        """Forces, torques and stability margin holding configuration ``q``.

        Args:
            q: Configuration (free-flyer first) with the stance feet on the ground.
            distribution: ``"min-norm"`` or ``"min-torque"``.
            gravity: Gravitational acceleration in the ground frame [m/s²].
            payload: The payload; this object's own if omitted.

        """
        return self.states([q], distribution, gravity, payload)[0]

    def states(
        self,
        configurations: Sequence[npt.ArrayLike],
        distribution: Distribution = "min-norm",
        gravity: npt.ArrayLike = LEVEL_GRAVITY,
        payload: Payload | None = None,
    ) -> list[StaticState]:
        """:meth:`state` of each configuration, the linear algebra done for all at once."""
        if distribution != "min-norm":
            require_choice("distribution", distribution, Distribution)
        payload = self.payload if payload is None else payload
        gravity = np.asarray(gravity, dtype=float)
        count, legs = len(configurations), len(self.legs)
        nv = self.model.model.nv
        generalized = np.empty((count, nv))
        jacobians = np.empty((count, 3 * legs, nv))
        feet = np.empty((count, legs, 3))
        com = np.empty((count, 3))
        for k, q in enumerate(configurations):
            generalized[k], com[k] = self._pinocchio_terms(
                np.asarray(q, dtype=float), gravity, payload, jacobians[k], feet[k]
            )
        mass = self._robot_mass + payload.mass
        if distribution == "min-norm":
            forces = min_norm_forces(*equilibrium(feet, com, mass, gravity))
        else:
            forces = np.array(
                [
                    self._min_torque(*terms, mass, gravity)
                    for terms in zip(feet, com, generalized, jacobians, strict=True)
                ]
            )
        torques = generalized - np.einsum("kfv,kf->kv", jacobians, forces)
        residuals = np.abs(torques[:, :6]).max(axis=1)
        joint_torques = torques[:, self._v] * self._signs
        return [
            StaticState(
                legs=self.legs,
                foot_forces=forces[k].reshape(-1, 3),
                joint_torques=joint_torques[k],
                com=com[k],
                mass=mass,
                stability_margin=self._polygon(feet[k, :, :2]).signed_distance(
                    ground_point(com[k], gravity)
                ),
                free_flyer_residual=float(residuals[k]),
            )
            for k in range(count)
        ]

    def _pinocchio_terms(
        self, q: ArrayF, gravity: ArrayF, payload: Payload, jacobian: ArrayF, feet: ArrayF
    ) -> tuple[ArrayF, ArrayF]:
        """Generalized gravity and centre of mass at ``q``.

        The stacked foot Jacobian (world axes) and the foot positions are written into
        ``jacobian`` and ``feet``.
        """
        model, data = self.model.model, self.model.data
        tilted = bool(gravity[2] != -GRAVITY)
        if tilted:
            model.gravity.linear = gravity
        try:
            generalized = pin.computeGeneralizedGravity(model, data, q).copy()
        finally:
            if tilted:
                model.gravity.linear = self._downward
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        for i, fid in enumerate(self._feet):
            jacobian[3 * i : 3 * i + 3] = pin.getFrameJacobian(
                model, data, fid, pin.LOCAL_WORLD_ALIGNED
            )[:3]
            feet[i] = data.oMf[fid].translation
        com = pin.centerOfMass(model, data, False)
        if payload.mass > 0:  # the payload's weight through the body at its point
            offset = data.oMf[self.model.base_frame].rotation @ payload.point(self.model)
            frame = pin.getFrameJacobian(
                model, data, self.model.base_frame, pin.LOCAL_WORLD_ALIGNED
            )
            point_jacobian = frame[:3] - pin.skew(offset) @ frame[3:]
            generalized -= point_jacobian.T @ (payload.mass * gravity)
            com = self._carrying(com, payload)
        return generalized, com

    def centres_of_mass(
        self, configurations: npt.ArrayLike, payload: Payload | None = None
    ) -> ArrayF:
        """The centre of mass of robot and payload at each configuration q (K, nq) (K, 3) [m].

        What :meth:`states` finds, without the Jacobians, torques and margins: all that
        the min-norm forces need beside the feet (:func:`equilibrium`).
        """
        model, data = self.model.model, self.model.data
        payload = self.payload if payload is None else payload
        q = np.asarray(configurations, dtype=float).reshape(-1, model.nq)
        com = np.empty((len(q), 3))
        for k in range(len(q)):
            com[k] = pin.centerOfMass(model, data, q[k], False)
            if payload.mass > 0:
                pin.updateFramePlacement(model, data, self.model.base_frame)
                com[k] = self._carrying(com[k], payload)
        return com

    @property
    def mass(self) -> float:
        """The robot's mass and its own payload's [kg]."""
        return self._robot_mass + self.payload.mass

    def _carrying(self, com: ArrayF, payload: Payload) -> ArrayF:
        """The robot's centre of mass ``com`` moved by the payload, its body placed in data."""
        body = self.model.data.oMf[self.model.base_frame]
        point = body.translation + body.rotation @ payload.point(self.model)
        total = self._robot_mass + payload.mass
        moved: ArrayF = (self._robot_mass * com + payload.mass * point) / total
        return moved

    def _min_torque(
        self,
        feet: ArrayF,
        com: ArrayF,
        generalized: ArrayF,
        jacobian: ArrayF,
        mass: float,
        gravity: ArrayF,
    ) -> ArrayF:
        """Forces f (3N,) minimizing Σ (τ_j/rated_j)², τ = h − Jᵀf on the stance joints (a QP)."""
        a, b = equilibrium(feet, com, mass, gravity)
        columns = self._v.ravel()
        return min_torque_forces(
            a, b, jacobian[:, columns], generalized[columns], self.rated, self.friction
        )


def min_norm_forces(a: ArrayF, b: ArrayF) -> ArrayF:
    """The least Σ|f_i|² with A f = b: f = Aᵀ(AAᵀ)⁻¹b, batched over leading axes.

    A (..., 6, 3N) has full row rank for three or more feet not on one line.
    ``b`` may carry a trailing axis of right-hand sides (..., 6, K) for f (..., 3N, K).
    """
    stacked = b.ndim == a.ndim
    rhs = b if stacked else b[..., None]
    multipliers = np.linalg.solve(a @ a.swapaxes(-1, -2), rhs)
    forces = a.swapaxes(-1, -2) @ multipliers
    result: ArrayF = forces if stacked else forces[..., 0]
    return result


def min_torque_forces(
    a: ArrayF, b: ArrayF, joint_jacobian: ArrayF, bias: ArrayF, rated: ArrayF, friction: float
) -> ArrayF:
    """The forces f (3N,) with A f = b and friction minimizing Σ (τ_j/rated_j)² (a QP).

    Args:
        a: Equilibrium rows (6, 3N) of :func:`equilibrium`.
        b: Their right-hand side (6,).
        joint_jacobian: The stance feet's positions' derivatives by the stance joints
            (3N forces, 3N joints), ground frame [m/rad].
        bias: The stance joints' torques before the feet push, τ = bias − Jᵀf (3N,) [N·m].
        rated: Rated torques (root, hip, knee) (3,) [N·m].
        friction: Friction coefficient μ [-] of the pyramid |f_x|, |f_y| ≤ μ·f_z, f_z ≥ 0.

    """
    legs = a.shape[-1] // 3
    weights = np.tile(1.0 / np.asarray(rated, dtype=float), legs) ** 2
    jt = joint_jacobian.T  # (3N joints, 3N forces)
    hessian = jt.T @ (weights[:, None] * jt) + 1e-12 * np.eye(jt.shape[1])
    linear = -jt.T @ (weights * bias)
    solution = qpsolvers.solve_qp(
        hessian, linear, *friction_pyramid(legs, friction), a, b, solver=QP_SOLVER
    )
    if solution is None:
        raise HexalegError("no foot forces hold this pose within the friction cone (min-torque)")
    return np.asarray(solution)


def equilibrium(feet: ArrayF, com: ArrayF, mass: float, gravity: ArrayF) -> tuple[ArrayF, ArrayF]:
    """A f = b: Σ f_i = −M·g and Σ (p_i − c) × f_i = 0, for f stacked per foot (3N,).

    Batched too: feet (..., N, 3) and com (..., 3) give A (..., 6, 3N) and b (..., 6).
    """
    r = np.asarray(feet) - np.asarray(com)[..., None, :]  # (..., N, 3)
    a = np.zeros((*r.shape[:-2], 6, r.shape[-2], 3))
    a[..., 0, :, 0] = a[..., 1, :, 1] = a[..., 2, :, 2] = 1.0
    # rows 3..5: the cross-product matrix [r_i]× of each foot, side by side
    a[..., 3, :, 1], a[..., 3, :, 2] = -r[..., 2], r[..., 1]
    a[..., 4, :, 0], a[..., 4, :, 2] = r[..., 2], -r[..., 0]
    a[..., 5, :, 0], a[..., 5, :, 1] = -r[..., 1], r[..., 0]
    b = np.zeros((*r.shape[:-2], 6))
    b[..., :3] = -mass * gravity
    return a.reshape(*r.shape[:-2], 6, -1), b


def friction_pyramid(legs: int, friction: float) -> tuple[ArrayF, ArrayF]:
    """G f ≤ h: f_z ≥ 0 and |f_x|, |f_y| ≤ μ·f_z on every foot."""
    block = np.array(
        [
            [0.0, 0.0, -1.0],
            [1.0, 0.0, -friction],
            [-1.0, 0.0, -friction],
            [0.0, 1.0, -friction],
            [0.0, -1.0, -friction],
        ]
    )
    return np.kron(np.eye(legs), block), np.zeros(5 * legs)
