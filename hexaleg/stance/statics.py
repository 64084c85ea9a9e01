"""Statics: what holding a pose costs — foot forces, joint torques, stability, slopes, payload.

Gravity g = 9.81 m/s² along −z of the ground frame (tilted on a slope). Masses and
centres of mass come from the URDF through Pinocchio, plus an optional payload, a
point mass on the body. The stance feet's forces f_i [N] (ground frame) balance
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

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import pinocchio as pin
import qpsolvers
from scipy.spatial import ConvexHull

from hexaleg._typing import ArrayF, Distribution, require_choice
from hexaleg.exceptions import HexalegError
from hexaleg.robot.model import LEG_JOINTS, HexapodModel

GRAVITY = 9.81
"""Gravitational acceleration [m/s²]."""
DEFAULT_FRICTION = 0.6
"""Default friction coefficient μ between feet and ground [-]."""
SLOPE_HEADINGS: tuple[float, ...] = (0.0, math.pi / 2, math.pi, -math.pi / 2)
"""Uphill headings of the slope study, in the body frame [rad]: ahead, left, behind, right."""
QP_SOLVER = "proxqp"
"""The qpsolvers backend of the min-torque distribution (ProxSuite, from Pinocchio's lab)."""
PAYLOAD_SEARCH_LIMIT = 1e4
"""Largest payload the capacity search considers [kg]."""


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
        if not (math.isfinite(self.mass) and 0 <= self.mass <= PAYLOAD_SEARCH_LIMIT):
            raise HexalegError(
                f"payload mass = {self.mass:g} is not valid: must lie in "
                f"[0, {PAYLOAD_SEARCH_LIMIT:g}] [kg]"
            )
        if self.position is not None:
            position = tuple(float(v) for v in self.position)
            if len(position) != 3 or not all(math.isfinite(v) and abs(v) <= 100 for v in position):
                raise HexalegError(
                    f"payload position = {self.position} is not valid: three coordinates "
                    "in [-100, 100] [m], body frame"
                )
            object.__setattr__(self, "position", position)

    def point(self, model: HexapodModel) -> ArrayF:
        """The payload's position in the body frame [m]."""
        if self.position is not None:
            return np.array(self.position)
        return np.array([0.0, 0.0, model.design.body_height / 2])

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

    """

    def __init__(
        self,
        model: HexapodModel,
        legs: Sequence[str],
        payload: Payload | None = None,
        friction: float = DEFAULT_FRICTION,
    ) -> None:
        if not (math.isfinite(friction) and 0 < friction <= 10):
            raise HexalegError(f"friction = {friction:g} is not valid: must lie in (0, 10] [-]")
        self.model = model
        self.legs = tuple(legs)
        self.payload = payload or Payload()
        self.friction = friction
        self.rated = np.array(model.design.rated_torques)
        self._feet = [model.foot_frame_id(leg) for leg in self.legs]
        self._v = np.array([model.leg_v_indices(leg) for leg in self.legs])  # (N, 3)
        self._robot_mass = float(pin.computeTotalMass(model.model))
        self._support: SupportPolygon | None = None
        self._support_feet = np.zeros((len(self.legs), 2))
        self._downward = np.array([0.0, 0.0, -GRAVITY])

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
        gravity: npt.ArrayLike = (0.0, 0.0, -GRAVITY),
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
        gravity: npt.ArrayLike = (0.0, 0.0, -GRAVITY),
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
        if distribution == "min-norm":  # f = Aᵀ(AAᵀ)⁻¹b: A has full row rank for ≥ 3 feet
            a, b = equilibrium(feet, com, mass, gravity)
            multipliers = np.linalg.solve(a @ a.swapaxes(1, 2), b[..., None])
            forces = (a.swapaxes(1, 2) @ multipliers)[..., 0]
        else:
            forces = np.array(
                [self._min_torque(*terms, mass, gravity) for terms in zip(
                    feet, com, generalized, jacobians, strict=True)]
            )  # fmt: skip
        torques = generalized - np.einsum("kfv,kf->kv", jacobians, forces)
        residuals = np.abs(torques[:, :6]).max(axis=1)
        joint_torques = torques[:, self._v]
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
            body = data.oMf[self.model.base_frame]
            offset = body.rotation @ payload.point(self.model)
            frame = pin.getFrameJacobian(
                model, data, self.model.base_frame, pin.LOCAL_WORLD_ALIGNED
            )
            point_jacobian = frame[:3] - pin.skew(offset) @ frame[3:]
            generalized -= point_jacobian.T @ (payload.mass * gravity)
            mass = self._robot_mass + payload.mass
            com = (self._robot_mass * com + payload.mass * (body.translation + offset)) / mass
        return generalized, com

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
        weights = np.tile(1.0 / self.rated, len(self.legs)) ** 2
        jt = jacobian[:, columns].T  # (3N joints, 3N forces)
        h = generalized[columns]
        hessian = jt.T @ (weights[:, None] * jt) + 1e-12 * np.eye(jt.shape[1])
        linear = -jt.T @ (weights * h)
        solution = qpsolvers.solve_qp(
            hessian,
            linear,
            *friction_pyramid(len(self.legs), self.friction),
            a,
            b,
            solver=QP_SOLVER,
        )
        if solution is None:
            raise HexalegError(
                "no foot forces hold this pose within the friction cone (min-torque)"
            )
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


def ground_point(com: ArrayF, gravity: ArrayF) -> ArrayF:
    """Where the gravity line through the centre of mass meets the ground z = 0 (x, y) [m]."""
    t = com[2] / -gravity[2]
    return (com + t * gravity)[:2]


@dataclass(frozen=True)
class SupportPolygon:
    """The convex hull of the stance feet on the ground, with its edges precomputed.

    Attributes:
        vertices: Hull vertices, counter-clockwise (K, 2) [m].
        edges: Vector from each vertex to the next (K, 2) [m].
        lengths: Edge lengths (K,) [m].

    """

    vertices: ArrayF
    edges: ArrayF
    lengths: ArrayF

    @classmethod
    def of_feet(cls, feet_xy: npt.ArrayLike) -> SupportPolygon:
        """The support polygon of the feet (x, y) (N, 2) [m]."""
        feet_xy = np.asarray(feet_xy, dtype=float)
        try:
            hull = ConvexHull(feet_xy)
        except Exception as err:  # qhull raises its own error type on degenerate input
            raise HexalegError(f"the stance feet span no support polygon: {err}") from err
        vertices = feet_xy[hull.vertices]
        edges = np.roll(vertices, -1, axis=0) - vertices
        return cls(vertices, edges, np.hypot(edges[:, 0], edges[:, 1]))

    def signed_distance(self, point: npt.ArrayLike) -> float:
        """Signed distance [m] from ``point`` (x, y) to the boundary: > 0 inside."""
        relative = np.asarray(point, dtype=float)[:2] - self.vertices
        edges = self.edges
        inward = (edges[:, 0] * relative[:, 1] - edges[:, 1] * relative[:, 0]) / self.lengths
        if inward.min() >= 0:
            return float(inward.min())
        along = (relative[:, 0] * edges[:, 0] + relative[:, 1] * edges[:, 1]) / self.lengths**2
        gap = relative - np.clip(along, 0.0, 1.0)[:, None] * edges
        return -float(np.hypot(gap[:, 0], gap[:, 1]).min())

    def exit_distance(self, point: ArrayF, direction: ArrayF) -> float:
        """How far from ``point`` (inside) along ``direction`` the boundary lies [m]."""
        return float(self.exit_distances(point, np.asarray(direction)[None])[0])

    def exit_distances(self, point: ArrayF, directions: ArrayF) -> ArrayF:
        """:meth:`exit_distance` along each of ``directions`` (H, 2) [m] (inf: none)."""

        def cross(u: ArrayF, v: ArrayF) -> ArrayF:
            return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]

        d = np.asarray(directions, dtype=float)[:, None, :]  # (H, 1, 2)
        offset = self.vertices - np.asarray(point)[:2]  # (K, 2), point to each vertex
        denominator = cross(d, self.edges)  # (H, K)
        parallel = np.abs(denominator) < 1e-15
        denominator = np.where(parallel, 1.0, denominator)
        t = cross(offset, self.edges) / denominator  # along the ray
        s = cross(offset, d) / denominator  # along the edge
        hit = ~parallel & (t >= 0) & (s >= -1e-12) & (s <= 1 + 1e-12)
        return np.where(hit, t, np.inf).min(axis=1)


def stability_margin(feet_xy: ArrayF, point: ArrayF) -> float:
    """Signed distance [m] from ``point`` to the convex hull of the feet: > 0 inside."""
    return SupportPolygon.of_feet(feet_xy).signed_distance(point)


@dataclass(frozen=True)
class SlopeLimit:
    """The steepest slope the robot stands on, uphill toward one heading.

    Attributes:
        heading: Uphill direction in the body frame [rad] (0: straight ahead).
        max_slope: The slope angle α [rad].
        limited_by: ``"tip"`` (the gravity line leaves the support polygon) or
            ``"slide"`` (tan α would exceed μ).

    """

    heading: float
    max_slope: float
    limited_by: str


def slope_limits(
    feet_xy: ArrayF | SupportPolygon,
    com: ArrayF,
    friction: float,
    headings: Sequence[float] = SLOPE_HEADINGS,
) -> tuple[SlopeLimit, ...]:
    """The max slope per heading: the smaller of the tip-over angle and atan μ.

    On a slope α uphill toward ψ (body parallel to the ground), gravity in the robot's
    ground frame is g·(−sin α cos ψ, −sin α sin ψ, −cos α): the gravity line through
    c meets the ground c_z·tan α downhill of c's footprint, and the robot tips when
    that point leaves the support polygon.
    """
    polygon = feet_xy if isinstance(feet_xy, SupportPolygon) else SupportPolygon.of_feet(feet_xy)
    slide = math.atan(friction)
    downhill = -np.column_stack([np.cos(headings), np.sin(headings)])
    tips = np.arctan2(polygon.exit_distances(com[:2], downhill), com[2])
    return tuple(
        SlopeLimit(heading, min(float(tip), slide), "tip" if tip < slide else "slide")
        for heading, tip in zip(headings, tips, strict=True)
    )


def slope_gravity(angle: float, heading: float) -> ArrayF:
    """Gravity [m/s²] in the ground frame of a slope α uphill toward heading ψ."""
    return GRAVITY * np.array(
        [
            -math.sin(angle) * math.cos(heading),
            -math.sin(angle) * math.sin(heading),
            -math.cos(angle),
        ]
    )


@dataclass(frozen=True)
class PayloadCapacity:
    """The largest payload the robot holds at its nominal stance.

    Attributes:
        mass: The payload [kg].
        limited_by: ``"<leg> <joint>"`` whose torque reaches its rating, ``"stability"``,
            or ``"search limit"`` if nothing binds below :data:`PAYLOAD_SEARCH_LIMIT`.

    """

    mass: float
    limited_by: str


def payload_capacity(
    statics: Statics,
    q: npt.ArrayLike,
    distribution: Distribution = "min-norm",
    at: StaticState | None = None,
) -> PayloadCapacity:
    """The largest payload at the statics' payload point that the nominal stance holds.

    Every stance joint's |τ| must stay within its rating and the stability margin
    positive. With min-norm forces every torque is affine in the payload (the six
    equilibrium equations about a fixed point are affine in it), so each joint's limit
    is solved exactly; min-torque forces are found by bisection, to 1e-6 relative.

    Args:
        statics: The robot on its stance legs, with the payload's point.
        q: The stance configuration (the nominal one).
        distribution: ``"min-norm"`` or ``"min-torque"``.
        at: ``statics.state(q)`` if already computed (saves one evaluation).

    """
    if distribution == "min-norm":
        return _affine_capacity(statics, q, at)

    def check(mass: float) -> tuple[bool, str]:
        try:
            state = statics.state(q, distribution, payload=statics.payload.with_mass(mass))
        except HexalegError:
            return False, "stability"
        ratios = state.torque_ratios(statics.rated)
        if ratios.max() > 1.0:
            leg, joint = _first_tied(ratios)
            return False, f"{statics.legs[leg]} {LEG_JOINTS[joint]}"
        if state.stability_margin <= 0:
            return False, "stability"
        return True, ""

    ok, cause = check(0.0)
    if not ok:
        return PayloadCapacity(0.0, cause)
    ok, cause = check(PAYLOAD_SEARCH_LIMIT)
    if ok:
        return PayloadCapacity(PAYLOAD_SEARCH_LIMIT, "search limit")
    lo, hi = 0.0, PAYLOAD_SEARCH_LIMIT
    while hi - lo > 1e-6 * max(hi, 1.0):
        mid = 0.5 * (lo + hi)
        ok, why = check(mid)
        if ok:
            lo = mid
        else:
            hi, cause = mid, why
    return PayloadCapacity(lo, cause)


def _affine_capacity(statics: Statics, q: npt.ArrayLike, at: StaticState | None) -> PayloadCapacity:
    """Payload capacity with min-norm forces: τ(m) = τ(0) + m·τ1, solved joint by joint.

    Two evaluations fix the line (the payload's own state and one kilogram more or
    less); the centre of mass moves along the segment from the robot's own toward the
    payload's point.
    """
    m0 = statics.payload.mass
    at = statics.state(q) if at is None else at
    m1 = m0 + 1.0 if m0 + 1.0 <= PAYLOAD_SEARCH_LIMIT else m0 - 1.0
    other = statics.state(q, payload=statics.payload.with_mass(m1))
    slope = (other.joint_torques - at.joint_torques) / (m1 - m0)
    base = at.joint_torques - m0 * slope
    point = (other.com * other.mass - at.com * at.mass) / (m1 - m0)  # the payload's place
    robot_mass = at.mass - m0
    robot_com = (at.com * at.mass - m0 * point) / robot_mass
    rated = np.broadcast_to(statics.rated, base.shape)
    support = statics.support
    if np.any(np.abs(base) > rated) or support.signed_distance(robot_com) <= 0:
        ratios = np.abs(base) / rated
        leg, joint = _first_tied(ratios)
        cause = "stability" if ratios.max() <= 1 else f"{statics.legs[leg]} {LEG_JOINTS[joint]}"
        return PayloadCapacity(0.0, cause)
    with np.errstate(divide="ignore", invalid="ignore"):  # slope 0: that joint never binds
        limit = np.where(slope > 0, (rated - base) / slope, (-rated - base) / slope)
    limit = np.where(np.abs(slope) > 0, limit, np.inf)
    leg, joint = _first_tied(-limit)
    mass, cause = float(limit[leg, joint]), f"{statics.legs[leg]} {LEG_JOINTS[joint]}"
    tipping = _tipping_payload(support, robot_com, robot_mass, point)
    if tipping < mass:
        mass, cause = tipping, "stability"
    if mass >= PAYLOAD_SEARCH_LIMIT:
        return PayloadCapacity(PAYLOAD_SEARCH_LIMIT, "search limit")
    return PayloadCapacity(mass, cause)


def _tipping_payload(
    support: SupportPolygon, robot_com: ArrayF, robot_mass: float, point: ArrayF
) -> float:
    """The payload [kg] at which the centre of mass's footprint leaves the support polygon.

    With a payload m at p the footprint is c_r + s·(p − c_r), s = m / (M_r + m) < 1: it
    leaves where that segment crosses the boundary, at m = M_r·s / (1 − s).
    """
    if support.signed_distance(point) > 0:
        return math.inf  # a payload inside the polygon only steadies the robot
    towards = point[:2] - robot_com[:2]
    span = float(np.hypot(towards[0], towards[1]))
    s = support.exit_distance(robot_com[:2], towards / span) / span
    return math.inf if s >= 1 else robot_mass * s / (1 - s)


def _first_tied(values: ArrayF, tolerance: float = 1e-9) -> tuple[int, int]:
    """(leg, joint) of the largest value, the first in leg order among near-equal ones.

    Mirror-image legs tie, and round-off must not choose between them.
    """
    flat = values.ravel()
    best = flat.max()
    index = int(np.flatnonzero(flat >= best - tolerance * max(1.0, abs(best)))[0])
    leg, joint = np.unravel_index(index, values.shape)
    return int(leg), int(joint)
