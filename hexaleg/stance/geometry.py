"""Stance phase: the closed chain of body, stance legs and ground (paper §3.2, eq 11–13, 30).

The feet of the stance legs are pinned to footholds on the ground. Given a body
pose, stance inverse kinematics gives every stance leg's joint angles; given the
joint angles, stance forward kinematics fits the body pose (eq 13, a rigid
least-squares fit for N ≥ 3 legs). Everything geometric (leg-root placements,
footholds, the body box) is read from the Pinocchio model built from the URDF,
and collected in a :class:`StanceGeometry` that the vectorized kernels use.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._typing import ArrayF, StanceSet, require_choice
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError, ModelError, ParameterError
from hexaleg.kinematics import InverseKinematics, foot_position, inverse_kinematics, leg_solution
from hexaleg.layouts import first_tripod
from hexaleg.leg_geometry import LegGeometry, leg_parameters
from hexaleg.limits import JointLimits
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.model_cache import per_body


def stance_legs(model: HexapodModel, stance: StanceSet | Sequence[str]) -> tuple[str, ...]:
    """Resolve ``"tripod"``, ``"all"`` or an explicit list into leg names of ``model``.

    ``"tripod"`` is the first tripod: (lf, rm, lr) for the built-in layouts, every other
    leg around the body for custom ones (:func:`~hexaleg.layouts.first_tripod`).
    """
    if isinstance(stance, str):
        require_choice("stance", stance, StanceSet)
        legs = first_tripod(model.design.legs) if stance == "tripod" else model.leg_names
    else:
        legs = tuple(stance)
    unknown = [leg for leg in legs if leg not in model.leg_names]
    if unknown or len(set(legs)) != len(legs) or len(legs) < 3:
        raise ParameterError(
            "stance legs", list(legs), f"at least 3 distinct legs of {', '.join(model.leg_names)}"
        )
    return tuple(legs)


def needed_model(
    design: HexapodDesign,
    model: HexapodModel | None,
    template: StanceGeometry | None,
    collisions: bool,
) -> HexapodModel | None:
    """``design``'s model, built here once if none is given and something will read it.

    The stance geometry reads it unless a ``template`` gives it in closed form; the
    self-collision check reads it whenever ``collisions`` is asked. Otherwise None: no
    URDF is rendered.
    """
    if model is None and (template is None or collisions):
        return HexapodModel(design)
    return model


CORNER_SIGNS = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
"""The eight corners of a box, as signs of its half extents."""


@dataclass(frozen=True)
class StanceGeometry:
    """What the stance kernels need, read from the Pinocchio model.

    Attributes:
        legs: Stance leg names (N,).
        lengths: Segment lengths (l1, l2, l3) [m].
        root_rotations: Leg-root frame orientations in the body frame (N, 3, 3).
        root_positions: Leg-root frame origins in the body frame (N, 3) [m].
        footholds: Fixed foot positions in the world frame (N, 3) [m].
        nominal_height: Body-frame height above the ground at the nominal stance [m].
        body_half_extents: Half sizes of the body's collision shape (3,) [m]: of its box,
            or (radius, radius, half height) of its cylinder.
        body_round: Whether the body's collision shape is a cylinder about z (else a box).
        limits: Joint limits that stop the body (the design's ``stance_limits``).
        leg_geometries: Each stance leg's general leg, where the legs are their own
            (:attr:`~hexaleg.robot.model.HexapodModel.own_legs`; empty: the paper's leg of
            ``lengths`` on every leg).
        leg_bounds: Each stance leg's joint limits (2, N, 3) [rad], lower then upper, where
            its own limits hold it standing (None: ``limits`` on every leg).

    """

    legs: tuple[str, ...]
    lengths: tuple[float, float, float]
    root_rotations: ArrayF
    root_positions: ArrayF
    footholds: ArrayF
    nominal_height: float
    body_half_extents: ArrayF
    body_round: bool
    limits: JointLimits
    leg_geometries: tuple[LegGeometry, ...] = ()
    leg_bounds: ArrayF | None = None

    @classmethod
    def from_model(
        cls, model: HexapodModel, stance: StanceSet | Sequence[str] = "all"
    ) -> StanceGeometry:
        """Read the stance geometry of ``model`` at its nominal stance, all from Pinocchio."""
        legs = stance_legs(model, stance)
        half_extents, round_body = body_collision_shape(model)
        roots = model.root_placements()
        feet = model.foot_positions(model.nominal_configuration())
        index = [model.leg_names.index(leg) for leg in legs]
        own = model.own_legs
        return cls(
            legs=legs,
            lengths=model.design.lengths,
            root_rotations=np.array([roots[leg].rotation for leg in legs]),
            root_positions=np.array([roots[leg].translation for leg in legs]),
            footholds=feet[index],
            nominal_height=float(model.nominal_base_pose().translation[2]),
            body_half_extents=half_extents,
            body_round=round_body,
            limits=model.design.stance_limits,
            leg_geometries=() if own is None else tuple(own[leg] for leg in legs),
            leg_bounds=_leg_bounds(model, legs) if model.stance_limits is None else None,
        )

    @classmethod
    def template_of(
        cls, model: HexapodModel, stance: StanceSet | Sequence[str] = "all"
    ) -> StanceGeometry | None:
        """The geometry other designs of ``model``'s body derive theirs from in closed form.

        By :meth:`with_design`; ``None`` where its legs are their own
        (:attr:`~hexaleg.robot.model.HexapodModel.own_legs`): each design's is then read from
        its own model.
        """
        return cls.from_model(model, stance) if model.own_legs is None else None

    @classmethod
    def of_design(
        cls,
        design: HexapodDesign,
        stance: StanceSet | Sequence[str] = "all",
        model: HexapodModel | None = None,
        template: StanceGeometry | None = None,
    ) -> StanceGeometry:
        """``design``'s stance geometry: from ``template`` if given, else from its model.

        A template of the same body and mounts (a study's, read once) gives it by
        :meth:`with_design` in closed form, without rendering the design's URDF; its
        stance legs are the template's. Otherwise it is read from ``model`` (built if
        omitted) by :meth:`from_model`.
        """
        if template is not None:
            return template.with_design(design)
        return cls.from_model(HexapodModel(design) if model is None else model, stance)

    def with_design(self, design: HexapodDesign) -> StanceGeometry:
        """The same body and mounting with ``design``'s legs and posture (closed form, eq 7).

        Only valid when ``design`` has the mounts and body of the design this geometry
        was read from; the tests prove it equal to :meth:`from_model` of ``design``.
        Not for a robot file's legs (their geometry is the file's).
        """
        if self.leg_geometries:
            raise HexalegError("an imported robot's stance is read from its model")
        height = design.nominal_height
        foot_in_root = foot_position(design.lengths, design.nominal_angles)
        footholds = self.root_positions + self.root_rotations @ foot_in_root
        footholds[:, 2] += height
        return StanceGeometry(
            legs=self.legs,
            lengths=design.lengths,
            root_rotations=self.root_rotations,
            root_positions=self.root_positions,
            footholds=footholds,
            nominal_height=height,
            body_half_extents=self.body_half_extents,
            body_round=self.body_round,
            limits=design.stance_limits,
        )

    @property
    def leg_parameters(self) -> ArrayF:
        """Each stance leg's (a1, l2, l3, h, e) (N, 5) [m]: what the compiled kernels take."""
        if self.leg_geometries:
            return np.array([leg_parameters(g) for g in self.leg_geometries])
        return np.tile([*self.lengths, 0.0, 0.0], (len(self.legs), 1))

    @property
    def joint_lower(self) -> ArrayF:
        """Each stance leg's lower joint limits (N, 3) [rad]."""
        if self.leg_bounds is not None:
            return np.asarray(self.leg_bounds[0], dtype=float)
        return np.tile(self.limits.lower, (len(self.legs), 1))

    @property
    def joint_upper(self) -> ArrayF:
        """Each stance leg's upper joint limits (N, 3) [rad]."""
        if self.leg_bounds is not None:
            return np.asarray(self.leg_bounds[1], dtype=float)
        return np.tile(self.limits.upper, (len(self.legs), 1))

    def leg_solutions(self, targets: npt.ArrayLike) -> tuple[ArrayF, ArrayF]:
        """Knee-down angles (..., N, 3) [rad] and reach r (..., N) [m] of foot targets (..., N, 3).

        Each leg by its own geometry (:func:`~hexaleg.kinematics.leg_solution`).
        """
        targets = np.asarray(targets, dtype=float)
        if not self.leg_geometries:
            return leg_solution(self.lengths, targets)
        solved = [leg_solution(g, targets[..., n, :]) for n, g in enumerate(self.leg_geometries)]
        return np.stack([t for t, _ in solved], axis=-2), np.stack([r for _, r in solved], axis=-1)

    @property
    def nominal_pose(self) -> pin.SE3:
        """Body pose of the nominal stance: level, at the nominal height."""
        return pin.SE3(np.eye(3), np.array([0.0, 0.0, self.nominal_height]))

    def feet_in_roots(self, rotation: npt.ArrayLike, translation: npt.ArrayLike) -> ArrayF:
        """Footholds seen from each leg root, for body poses.

        Args:
            rotation: Body orientations (..., 3, 3).
            translation: Body positions (..., 3) [m].

        Returns:
            Foot targets (..., N, 3) in each leg-root frame [m].

        """
        rotation = np.asarray(rotation, dtype=float)
        translation = np.asarray(translation, dtype=float)
        # world → body: b = Rᵀ(f − t), row-wise (f − t)·R; body → root: R_rᵀ(b − p_r).
        in_body = (self.footholds - translation[..., None, :]) @ rotation  # (..., N, 3)
        # row-wise (b − p_r)·R_r per leg n, as a batch of (1, 3) @ (3, 3) products
        return ((in_body - self.root_positions)[..., None, :] @ self.root_rotations)[..., 0, :]

    def body_corners(self, rotation: npt.ArrayLike, translation: npt.ArrayLike) -> ArrayF:
        """World positions of the body box's 8 corners for body poses (..., 8, 3) [m]."""
        if self.body_round:
            raise HexalegError("a cylinder body has no corners")
        rotation = np.asarray(rotation, dtype=float)
        return self._corners @ np.swapaxes(rotation, -1, -2) + np.asarray(translation)[..., None, :]

    def lowest_body_height(self, rotation: npt.ArrayLike, translation: npt.ArrayLike) -> ArrayF:
        """Height of the body's lowest point above the ground for body poses (...) [m].

        A box's lowest point is a corner: −Σ_k h_k |R_zk|. A cylinder's lies on a rim:
        −r·√(R_zx² + R_zy²) − h |R_zz| (r its radius, h its half height).
        """
        rotation = np.asarray(rotation, dtype=float)
        tilt = rotation[..., 2, :]  # the body axes' z components
        hx, _, hz = self.body_half_extents
        if self.body_round:
            drop = hx * np.hypot(tilt[..., 0], tilt[..., 1]) + hz * np.abs(tilt[..., 2])
        else:
            drop = np.abs(tilt) @ self.body_half_extents
        return np.asarray(translation)[..., 2] - drop

    @cached_property
    def _corners(self) -> ArrayF:
        return CORNER_SIGNS * self.body_half_extents


FINITE_BOUND = 2 * np.pi
"""A continuous joint's limits in the stance kernels: ±2π [rad] (θ never leaves (−π, π])."""


def _leg_bounds(model: HexapodModel, legs: Sequence[str]) -> ArrayF:
    """The stance legs' own joint limits (2, N, 3) on θ [rad], continuous joints at ±2π."""
    bounds = np.array([model.joint_limits(leg) for leg in legs]).transpose(1, 0, 2)
    return np.clip(bounds, -FINITE_BOUND, FINITE_BOUND)


def body_collision_shape(model: HexapodModel) -> tuple[ArrayF, bool]:
    """``base_link``'s collision shape read from the URDF: half extents [m] and roundness.

    A box gives its half sizes; a cylinder (radius r, length 2h, about z) gives (r, r, h).
    The body's alone determines it: it is read once per body
    (:func:`~hexaleg.robot.model_cache.per_body`).
    """
    if model.body_box is not None:
        return model.body_box.copy(), False
    half_extents, round_body = per_body(
        "body collision shape", model.design, lambda: _read_body_shape(model)
    )
    return half_extents.copy(), round_body


def _read_body_shape(model: HexapodModel) -> tuple[ArrayF, bool]:
    for obj in model.collision_model().geometryObjects:
        if obj.parentFrame != model.base_frame:
            continue
        if hasattr(obj.geometry, "halfSide"):
            return np.array(obj.geometry.halfSide, dtype=float), False
        if hasattr(obj.geometry, "halfLength") and hasattr(obj.geometry, "radius"):
            r, h = float(obj.geometry.radius), float(obj.geometry.halfLength)
            return np.array([r, r, h]), True
    raise ModelError("base_link has no box or cylinder collision geometry")


# -- stance inverse / forward kinematics ------------------------------------------------


def stance_inverse_kinematics(geometry: StanceGeometry, body: pin.SE3) -> InverseKinematics:
    """Joint angles (N, 3) [rad] of every stance leg for a body pose, feet on their footholds.

    ``reachable`` (N,) flags legs whose foothold is out of reach or whose angles
    leave the stance limits. Each leg by its own geometry and limits (a robot file's).
    """
    targets = geometry.feet_in_roots(body.rotation, body.translation)
    if not geometry.leg_geometries:
        return inverse_kinematics(geometry.lengths, targets, limits=geometry.limits)
    solved = [inverse_kinematics(g, targets[n]) for n, g in enumerate(geometry.leg_geometries)]
    theta = np.array([s.theta for s in solved])
    inside = (theta >= geometry.joint_lower - 1e-12) & (theta <= geometry.joint_upper + 1e-12)
    reachable = np.array([s.reachable for s in solved]) & inside.all(axis=-1)
    return InverseKinematics(theta, reachable)


def stance_forward_kinematics(geometry: StanceGeometry, joint_angles: npt.ArrayLike) -> pin.SE3:
    """Body pose from the stance legs' joint angles (N, 3) [rad] (eq 13, N ≥ 3).

    Each leg gives its foot in the body frame, u_i = T_root·p(θ_i) (by its own geometry);
    the body pose T_C with T_C·u_i = foothold_i is the rigid least-squares fit (Kabsch).
    """
    angles = np.asarray(joint_angles, dtype=float)
    if geometry.leg_geometries:
        legs = zip(geometry.leg_geometries, angles, strict=True)
        feet = np.array([foot_position(leg, theta) for leg, theta in legs])
    else:
        feet = foot_position(geometry.lengths, angles)
    feet_body = geometry.root_positions + np.einsum("nij,nj->ni", geometry.root_rotations, feet)
    return rigid_fit(feet_body, geometry.footholds)


def rigid_fit(source: npt.ArrayLike, target: npt.ArrayLike) -> pin.SE3:
    """The rotation R and translation t minimizing Σ|R·s_i + t − t_i|² (N ≥ 3 points)."""
    source = np.asarray(source, dtype=float)
    target = np.asarray(target, dtype=float)
    if source.shape[0] < 3:
        raise HexalegError("a rigid fit needs at least 3 points")
    cs, ct = source.mean(axis=0), target.mean(axis=0)
    u, _, vt = np.linalg.svd((source - cs).T @ (target - ct))
    d = np.sign(np.linalg.det(vt.T @ u.T))
    rotation = vt.T @ np.diag([1.0, 1.0, d]) @ u.T
    return pin.SE3(rotation, ct - rotation @ cs)


# -- constraints on the Pinocchio model -------------------------------------------------


def stance_configuration(
    model: HexapodModel, geometry: StanceGeometry, body: pin.SE3
) -> tuple[ArrayF, InverseKinematics]:
    """Full configuration q for a body pose: stance legs by stance IK, swing legs nominal."""
    solution = stance_inverse_kinematics(geometry, body)
    angles = {leg: model.nominal_angles(leg) for leg in model.leg_names}
    angles.update(zip(geometry.legs, solution.theta, strict=True))
    return model.configuration(body, angles), solution


def constraint_residual(model: HexapodModel, geometry: StanceGeometry, q: npt.ArrayLike) -> ArrayF:
    """Foot anchoring residual (3N,): each stance foot minus its foothold, world frame [m]."""
    feet = model.foot_positions(q)
    index = [model.leg_names.index(leg) for leg in geometry.legs]
    return (feet[index] - geometry.footholds).ravel()


def constraint_jacobian(model: HexapodModel, geometry: StanceGeometry, q: npt.ArrayLike) -> ArrayF:
    """Jacobian (3N, nv) of :func:`constraint_residual`, stacked foot rows from Pinocchio."""
    q = np.asarray(q, dtype=float)
    pin.computeJointJacobians(model.model, model.data, q)
    pin.updateFramePlacements(model.model, model.data)
    rows = [
        pin.getFrameJacobian(
            model.model, model.data, model.foot_frame_id(leg), pin.LOCAL_WORLD_ALIGNED
        )[:3]
        for leg in geometry.legs
    ]
    return np.vstack(rows)


def mechanism_columns(model: HexapodModel, legs: Sequence[str]) -> npt.NDArray[np.int_]:
    """Velocity indices of the closed-chain mechanism: the body (6) and the stance joints."""
    return np.concatenate([np.arange(6), *(model.leg_v_indices(leg) for leg in legs)])


def mobility(
    model: HexapodModel, geometry: StanceGeometry, q: npt.ArrayLike, tol: float = 1e-9
) -> int:
    """Degrees of freedom of body + stance legs with the feet pinned (eq 1–2 predict 6).

    nv of the mechanism (6 + 3N) minus the rank of its constraint Jacobian.
    """
    columns = mechanism_columns(model, geometry.legs)
    jac = constraint_jacobian(model, geometry, q)[:, columns]
    return int(len(columns) - np.linalg.matrix_rank(jac, tol=tol))
