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
        self._data = model.model.createData()
        self._feet = [model.foot_frame_id(leg) for leg in self.legs]
        self._v = np.array([model.leg_v_indices(leg) for leg in self.legs])  # (N, 3)
        self._robot_mass = float(pin.computeTotalMass(model.model))
        self._hull: tuple[ArrayF, ArrayF] | None = None  # (feet, their polygon)

    def _polygon(self, feet_xy: ArrayF) -> ArrayF:
        """The support polygon, computed once: planted feet do not move."""
        if self._hull is None or np.abs(self._hull[0] - feet_xy).max() > 1e-12:
            self._hull = (feet_xy.copy(), support_polygon(feet_xy))
        return self._hull[1]

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
        require_choice("distribution", distribution, Distribution)
        payload = self.payload if payload is None else payload
        q = np.asarray(q, dtype=float)
        gravity = np.asarray(gravity, dtype=float)
        model, data = self.model.model, self._data
        tilted = gravity[2] != -GRAVITY
        if tilted:
            model.gravity.linear = gravity
        try:
            generalized = pin.computeGeneralizedGravity(model, data, q).copy()
        finally:
            if tilted:
                model.gravity.linear = np.array([0.0, 0.0, -GRAVITY])
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        jacobians = [
            pin.getFrameJacobian(model, data, fid, pin.LOCAL_WORLD_ALIGNED)[:3]
            for fid in self._feet
        ]
        feet = np.array([data.oMf[fid].translation for fid in self._feet])
        com_robot = pin.centerOfMass(model, data, q, False).copy()
        body = data.oMf[self.model.base_frame]
        offset = body.rotation @ payload.point(self.model)
        point = body.translation + offset
        if payload.mass > 0:  # the payload's weight through the body at its point
            frame = pin.getFrameJacobian(
                model, data, self.model.base_frame, pin.LOCAL_WORLD_ALIGNED
            )
            point_jacobian = frame[:3] - pin.skew(offset) @ frame[3:]
            generalized -= point_jacobian.T @ (payload.mass * gravity)
        mass = self._robot_mass + payload.mass
        com = (self._robot_mass * com_robot + payload.mass * point) / mass
        forces = self._distribute(feet, com, mass, gravity, generalized, jacobians, distribution)
        torques = generalized - np.vstack(jacobians).T @ forces.ravel()
        return StaticState(
            legs=self.legs,
            foot_forces=forces,
            joint_torques=torques[self._v],
            com=com,
            mass=mass,
            stability_margin=signed_distance(
                self._polygon(feet[:, :2]), ground_point(com, gravity)
            ),
            free_flyer_residual=float(np.abs(torques[:6]).max()),
        )

    def _distribute(
        self,
        feet: ArrayF,
        com: ArrayF,
        mass: float,
        gravity: ArrayF,
        generalized: ArrayF,
        jacobians: list[ArrayF],
        distribution: Distribution,
    ) -> ArrayF:
        a, b = equilibrium(feet, com, mass, gravity)
        if distribution == "min-norm":  # f = Aᵀ(AAᵀ)⁻¹b: A has full row rank for ≥ 3 feet
            return (a.T @ np.linalg.solve(a @ a.T, b)).reshape(-1, 3)
        # min Σ (τ_j/rated_j)², τ = h − Jᵀf on the stance joints, as a QP in f
        columns = self._v.ravel()
        weights = np.tile(1.0 / self.rated, len(self.legs)) ** 2
        jt = np.vstack(jacobians)[:, columns].T  # (3N joints, 3N forces)
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
        return np.asarray(solution).reshape(-1, 3)


def equilibrium(feet: ArrayF, com: ArrayF, mass: float, gravity: ArrayF) -> tuple[ArrayF, ArrayF]:
    """A f = b: Σ f_i = −M·g and Σ (p_i − c) × f_i = 0, for f stacked per foot (3N,)."""
    r = np.asarray(feet) - com  # (N, 3)
    a = np.zeros((6, len(r), 3))
    a[0, :, 0] = a[1, :, 1] = a[2, :, 2] = 1.0
    # rows 3..5: the cross-product matrix [r_i]× of each foot, side by side
    a[3, :, 1], a[3, :, 2] = -r[:, 2], r[:, 1]
    a[4, :, 0], a[4, :, 2] = r[:, 2], -r[:, 0]
    a[5, :, 0], a[5, :, 1] = -r[:, 1], r[:, 0]
    b = np.zeros(6)
    b[:3] = -mass * gravity
    return a.reshape(6, -1), b


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


def stability_margin(feet_xy: ArrayF, point: ArrayF) -> float:
    """Signed distance [m] from ``point`` to the convex hull of the feet: > 0 inside."""
    return signed_distance(support_polygon(feet_xy), point)


def signed_distance(polygon: ArrayF, point: ArrayF) -> float:
    """Signed distance [m] from ``point`` to a counter-clockwise convex polygon: > 0 inside."""
    edges = np.roll(polygon, -1, axis=0) - polygon
    lengths = np.linalg.norm(edges, axis=1)
    relative = point - polygon
    inward = (edges[:, 0] * relative[:, 1] - edges[:, 1] * relative[:, 0]) / lengths
    if np.all(inward >= 0):
        return float(inward.min())
    along = np.clip(np.einsum("ij,ij->i", relative, edges) / lengths**2, 0.0, 1.0)
    nearest = polygon + along[:, None] * edges
    return -float(np.linalg.norm(point - nearest, axis=1).min())


def support_polygon(feet_xy: ArrayF) -> ArrayF:
    """The convex hull of the stance feet (x, y), counter-clockwise (K, 2) [m]."""
    try:
        hull = ConvexHull(np.asarray(feet_xy, dtype=float))
    except Exception as err:  # qhull raises its own error type on degenerate input
        raise HexalegError(f"the stance feet span no support polygon: {err}") from err
    return np.asarray(feet_xy)[hull.vertices]


def exit_distance(polygon: ArrayF, point: ArrayF, direction: ArrayF) -> float:
    """How far from ``point`` (inside) along ``direction`` the polygon's boundary lies [m]."""
    best = math.inf
    for a, b in zip(polygon, np.roll(polygon, -1, axis=0), strict=True):
        edge = b - a
        denominator = direction[0] * -edge[1] - direction[1] * -edge[0]
        if abs(denominator) < 1e-15:
            continue
        rhs = a - point
        t = (rhs[0] * -edge[1] - rhs[1] * -edge[0]) / denominator
        s = (direction[0] * rhs[1] - direction[1] * rhs[0]) / denominator
        if t >= 0 and -1e-12 <= s <= 1 + 1e-12:
            best = min(best, t)
    return best


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
    feet_xy: ArrayF, com: ArrayF, friction: float, headings: Sequence[float] = SLOPE_HEADINGS
) -> tuple[SlopeLimit, ...]:
    """The max slope per heading: the smaller of the tip-over angle and atan μ.

    On a slope α uphill toward ψ (body parallel to the ground), gravity in the robot's
    ground frame is g·(−sin α cos ψ, −sin α sin ψ, −cos α): the gravity line through
    c meets the ground c_z·tan α downhill of c's footprint, and the robot tips when
    that point leaves the support polygon.
    """
    polygon = support_polygon(feet_xy)
    slide = math.atan(friction)
    limits = []
    for heading in headings:
        downhill = -np.array([math.cos(heading), math.sin(heading)])
        tip = math.atan2(exit_distance(polygon, com[:2], downhill), com[2])
        limits.append(SlopeLimit(heading, min(tip, slide), "tip" if tip < slide else "slide"))
    return tuple(limits)


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
    statics: Statics, q: npt.ArrayLike, distribution: Distribution = "min-norm"
) -> PayloadCapacity:
    """The largest payload at the statics' payload point that the nominal stance holds.

    Every stance joint's |τ| must stay within its rating and the stability margin
    positive. With min-norm forces every torque is affine in the payload (the six
    equilibrium equations about a fixed point are affine in it), so each joint's limit
    is solved exactly; min-torque forces are found by bisection, to 1e-6 relative.
    """
    if distribution == "min-norm":
        return _affine_capacity(statics, q)

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


def _affine_capacity(statics: Statics, q: npt.ArrayLike) -> PayloadCapacity:
    """Payload capacity with min-norm forces: τ(m) = τ0 + m·τ1, solved joint by joint."""
    empty = statics.state(q, payload=statics.payload.with_mass(0.0))
    unit = statics.state(q, payload=statics.payload.with_mass(1.0))
    base, slope = empty.joint_torques, unit.joint_torques - empty.joint_torques
    rated = np.broadcast_to(statics.rated, base.shape)
    if np.any(np.abs(base) > rated) or empty.stability_margin <= 0:
        ratios = np.abs(base) / rated
        leg, joint = _first_tied(ratios)
        cause = "stability" if ratios.max() <= 1 else f"{statics.legs[leg]} {LEG_JOINTS[joint]}"
        return PayloadCapacity(0.0, cause)
    with np.errstate(divide="ignore", invalid="ignore"):  # slope 0: that joint never binds
        limit = np.where(slope > 0, (rated - base) / slope, (-rated - base) / slope)
    limit = np.where(np.abs(slope) > 0, limit, np.inf)
    leg, joint = _first_tied(-limit)
    mass, cause = float(limit[leg, joint]), f"{statics.legs[leg]} {LEG_JOINTS[joint]}"
    tipping = _tipping_payload(empty, unit, statics)
    if tipping < mass:
        mass, cause = tipping, "stability"
    if mass >= PAYLOAD_SEARCH_LIMIT:
        return PayloadCapacity(PAYLOAD_SEARCH_LIMIT, "search limit")
    return PayloadCapacity(mass, cause)


def _tipping_payload(empty: StaticState, unit: StaticState, statics: Statics) -> float:
    """The payload at which the centre of mass's footprint leaves the support polygon."""
    mass0 = empty.mass
    point = unit.com * unit.mass - empty.com * mass0  # the payload's position (1 kg)
    polygon = statics._hull[1] if statics._hull is not None else None
    if polygon is None or signed_distance(polygon, point[:2]) > 0:
        return math.inf  # a payload inside the polygon only steadies the robot

    def margin(mass: float) -> float:
        com = (mass0 * empty.com + mass * point) / (mass0 + mass)
        return signed_distance(polygon, com[:2])

    lo, hi = 0.0, PAYLOAD_SEARCH_LIMIT
    if margin(hi) > 0:
        return math.inf
    while hi - lo > 1e-9 * max(hi, 1.0):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if margin(mid) > 0 else (lo, mid)
    return lo


def _first_tied(values: ArrayF, tolerance: float = 1e-9) -> tuple[int, int]:
    """(leg, joint) of the largest value, the first in leg order among near-equal ones.

    Mirror-image legs tie, and round-off must not choose between them.
    """
    flat = values.ravel()
    best = flat.max()
    index = int(np.flatnonzero(flat >= best - tolerance * max(1.0, abs(best)))[0])
    leg, joint = np.unravel_index(index, values.shape)
    return int(leg), int(joint)
