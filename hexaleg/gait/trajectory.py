"""Foot paths of a gait period and the joint motion that follows them (closed-form IK).

Body frame: x forward, y left, z up, at the body's centre, level at its nominal height;
u = (cos ψ, sin ψ, 0) is the heading. Each leg's nominal foothold P (its foot at the
nominal stance) anchors its path. With φ = t/T the phase of the period:

- standing, at stance phase σ ∈ [0, 1): p = P + S·(1/2 − σ)·u, fixed in the world while
  the body moves at v = S/(β·T) (it goes from P + (S/2)·u to P − (S/2)·u);
- swinging, at swing phase s ∈ [0, 1): in the world, from its lift-off point p0 to its
  touchdown point p1 = p0 + v·T·u, horizontally p0 + (p1 − p0)·h(s) with
  h(s) = 10s³ − 15s⁴ + 6s⁵, at height H·64·s³(1 − s)³ above the ground. In the body
  frame that is p = P + S·(−1/2 + h(s)/β − (1 − β)·s/β)·u + H·64·s³(1 − s)³·z.

Both are affine in S and H, so paths are built from phase-only shapes. Lift-off and
touchdown join the stance with equal velocity (−v·u) and zero acceleration: the paths are
twice continuously differentiable. Derivatives are taken by φ (d/dt = (1/T)·d/dφ), so one
motion serves every period. Joint angles come from the knee-down closed-form IK (eq 8–9)
in each leg-root frame, each leg its model's general leg
(:meth:`~hexaleg.robot.model.HexapodModel.leg_geometry`: the paper's leg for hexaleg's
designs, the file's for an imported robot); joint velocities and accelerations are exact:
θ' = J⁻¹·p' and θ'' = J⁻¹·(p'' − J'·θ'), J the foot Jacobian of eq 22 in closed form
(:mod:`hexaleg.gait.jacobian`). Angles are hexaleg's θ; the model maps them onto its
joints (:meth:`~hexaleg.robot.model.HexapodModel.joint_values`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from hexaleg._typing import ArrayF, Lengths
from hexaleg.gait.jacobian import LegPartials, inverse_times, leg_partials, rate_times
from hexaleg.gait.pattern import GaitPhases
from hexaleg.kinematics import foot_position, leg_solution
from hexaleg.leg_geometry import LegRows, leg_parameters
from hexaleg.robot.model import HexapodModel


@dataclass(frozen=True)
class LegFrames:
    """Where the legs sit, read from the Pinocchio model (body frame).

    Attributes:
        legs: Leg names, the model's ``leg_names`` order.
        parameters: Each leg's general leg (a1, l2, l3, h, e) (6, 5) [m]
            (:data:`~hexaleg.leg_geometry.LegRows`).
        root_rotations: Leg-root frame orientations (6, 3, 3).
        root_positions: Leg-root frame origins (6, 3) [m].
        footholds: Nominal foot positions P (6, 3) [m].
        height: Body frame's height above the ground [m] (the nominal one).

    """

    legs: tuple[str, ...]
    parameters: LegRows
    root_rotations: ArrayF
    root_positions: ArrayF
    footholds: ArrayF
    height: float

    @classmethod
    def from_model(cls, model: HexapodModel) -> LegFrames:
        """The legs of ``model`` at its nominal stance (each leg its own posture)."""
        legs = model.leg_names
        roots = model.root_placements()
        rotations = np.array([roots[leg].rotation for leg in legs])
        positions = np.array([roots[leg].translation for leg in legs])
        parameters = np.array([leg_parameters(model.leg_geometry(leg)) for leg in legs])
        nominal = np.array([model.nominal_angles(leg) for leg in legs])
        foot = foot_position(parameters, nominal)
        return cls(
            legs=legs,
            parameters=parameters,
            root_rotations=rotations,
            root_positions=positions,
            footholds=positions + (rotations @ foot[:, :, None])[:, :, 0],
            height=float(model.nominal_base_pose().translation[2]),
        )

    @property
    def lengths(self) -> Lengths:
        """The segments (a1, l2, l3) [m]: one design has one leg's, on all six."""
        a1, l2, l3 = (float(v) for v in self.parameters[0, :3])
        return (a1, l2, l3)

    def to_roots(self, vectors: ArrayF, points: bool = True) -> ArrayF:
        """Body-frame points (``points=False``: directions) (..., 6, 3) in the leg-root frames."""
        relative = vectors - self.root_positions if points else vectors
        return _rotate(relative, self.root_rotations, transpose=True)

    def points_in_body(self, points: ArrayF) -> ArrayF:
        """Points (K, 3) given in a leg-root frame, seen from each leg's: (6, K, 3), body frame."""
        turned: ArrayF = np.einsum("nij,kj->nki", self.root_rotations, points)
        return self.root_positions[:, None, :] + turned

    def to_body(self, vectors: ArrayF) -> ArrayF:
        """Leg-root-frame directions (..., 6, 3) in the body frame."""
        return _rotate(vectors, self.root_rotations, transpose=False)


def _rotate(vectors: ArrayF, rotations: ArrayF, transpose: bool) -> ArrayF:
    """R·v (or Rᵀ·v) per leg for vectors (..., 6, 3) and rotations (6, 3, 3).

    One matrix product per leg, its vectors as rows (vᵀ·Rᵀ, or vᵀ·R), written in place
    into the result's (..., 6, 3) layout: a stacked product of 3×3 blocks, or broadcast
    products over a last axis of three, are many times slower on a period's samples and on
    a stride scan, and a result in legs-first layout slows every reduction after it.
    """
    columns = rotations if transpose else np.swapaxes(rotations, 1, 2)
    rows = np.reshape(vectors, (-1, *np.shape(vectors)[-2:]))  # (K, 6, 3)
    turned = np.empty(rows.shape)
    np.matmul(rows.swapaxes(0, 1), columns, out=turned.swapaxes(0, 1))
    return turned.reshape(np.shape(vectors))


@dataclass(frozen=True)
class PathShapes:
    """The feet's paths per unit stride and step height, and their φ-derivatives (N, 6) [-].

    p = P + S·along·u + H·lift·z; ``*_d`` = d/dφ, ``*_dd`` = d²/dφ².
    """

    along: ArrayF
    along_d: ArrayF
    along_dd: ArrayF
    lift: ArrayF
    lift_d: ArrayF
    lift_dd: ArrayF


@lru_cache(maxsize=32)
def path_shapes(phases: GaitPhases) -> PathShapes:
    """The shapes of every foot's path at every sample (shared, read-only, per phases)."""
    beta, s, swing = phases.duty_factor, phases.phase, phases.swing
    rate = 1.0 / (1.0 - beta)  # ds/dφ
    h = s**3 * (10 - 15 * s + 6 * s**2)
    h_d = 30 * s**2 * (1 - s) ** 2
    h_dd = 60 * s * (1 - s) * (1 - 2 * s)
    lift = 64 * s**3 * (1 - s) ** 3
    lift_d = 192 * s**2 * (1 - s) ** 2 * (1 - 2 * s)
    lift_dd = 384 * s * (1 - s) * (1 - 5 * s + 5 * s**2)
    zero = np.zeros_like(s)
    shapes = PathShapes(
        along=np.where(swing, -0.5 + h / beta - (1 - beta) * s / beta, 0.5 - s),
        along_d=np.where(swing, h_d * rate / beta - 1 / beta, -1 / beta),
        along_dd=np.where(swing, h_dd * rate**2 / beta, zero),
        lift=np.where(swing, lift, zero),
        lift_d=np.where(swing, lift_d * rate, zero),
        lift_dd=np.where(swing, lift_dd * rate**2, zero),
    )
    for array in vars(shapes).values():
        array.flags.writeable = False
    return shapes


@dataclass(frozen=True)
class FootPaths:
    """Every foot's position and its φ-derivatives at every sample, body frame (N, 6, 3) [m]."""

    position: ArrayF
    velocity: ArrayF
    acceleration: ArrayF


def foot_paths(
    frames: LegFrames, shapes: PathShapes, stride: float, step_height: float, heading: float
) -> FootPaths:
    """The feet's paths for stride S [m], step height H [m] and heading ψ [rad]."""
    u = np.array([np.cos(heading), np.sin(heading), 0.0])
    z = np.array([0.0, 0.0, 1.0])

    def combine(along: ArrayF, lift: ArrayF) -> ArrayF:  # S·along·u + H·lift·z
        forward, up = stride * along, step_height * lift
        combined = np.empty((*along.shape, 3))
        for axis in range(3):  # per axis: a broadcast over a last axis of three is slow
            combined[..., axis] = forward * u[axis] + up * z[axis]
        return combined

    return FootPaths(
        position=frames.footholds + combine(shapes.along, shapes.lift),
        velocity=combine(shapes.along_d, shapes.lift_d),
        acceleration=combine(shapes.along_dd, shapes.lift_dd),
    )


@dataclass(frozen=True)
class JointMotion:
    """Every leg's joint angles and their φ-derivatives at every sample (N, 6, 3).

    Attributes:
        angles: θ [rad] (knee-down IK; the nearest pose where out of reach).
        velocity: dθ/dφ [rad]; divide by T for q̇ [rad/s].
        acceleration: d²θ/dφ² [rad]; divide by T² for q̈ [rad/s²].
        reach: Hip-to-foot distance r (N, 6) [m].
        partials: The foot Jacobian's terms at these angles (for J⁻¹, Jᵀ and J̇).

    """

    angles: ArrayF
    velocity: ArrayF
    acceleration: ArrayF
    reach: ArrayF
    partials: LegPartials


def joint_motion(frames: LegFrames, paths: FootPaths) -> JointMotion:
    """The joint motion that puts every foot on its path (exact first and second derivatives)."""
    targets = frames.to_roots(paths.position)
    velocity = frames.to_roots(paths.velocity, points=False)
    acceleration = frames.to_roots(paths.acceleration, points=False)
    angles, reach = leg_solution(frames.parameters, targets)
    leg = leg_partials(frames.parameters, angles)
    rates = inverse_times(leg, velocity)
    with np.errstate(invalid="ignore"):  # a straight leg: unbounded rates
        accelerations = inverse_times(leg, acceleration - rate_times(leg, rates))
    return JointMotion(angles, rates, accelerations, reach, leg)


def knee_heights(frames: LegFrames, angles: ArrayF, partials: LegPartials | None = None) -> ArrayF:
    """Each knee's height above the ground (..., 6) [m], body level at its nominal height.

    The knee is the femur's tip, eq 7 without the tibia (of a general leg, the point of
    the knee axis in the tibia's plane, e off the leg plane); only its height is needed,
    so only the leg-root frames' z rows turn it into the body frame. ``partials``: those
    of ``angles`` (:func:`~hexaleg.gait.jacobian.leg_partials`), whose cosines and sines
    serve, if known.
    """
    a1, l2, _, h, e = leg_parameters(frames.parameters)
    if partials is None:
        t1, t2 = angles[..., 0], angles[..., 1]
        c1, s1, c2, s2 = np.cos(t1), np.sin(t1), np.cos(t2), np.sin(t2)
    else:
        c1, s1, c2, s2 = partials.c1, partials.s1, partials.c2, partials.s2
    out = a1 + l2 * c2
    up = frames.root_rotations[:, 2, :]  # (6, 3)
    rise = up[:, 0] * (c1 * out - s1 * e) + up[:, 1] * (s1 * out + c1 * e)
    rise = rise + up[:, 2] * (h + l2 * s2)
    return frames.height + frames.root_positions[:, 2] + rise
