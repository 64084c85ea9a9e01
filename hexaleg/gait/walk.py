"""One robot walking one gait: the steps from the gait to the torques, shared by every front door.

:class:`Walker` holds what does not change with the stride or the period (the legs'
frames, their limits, who stands when and the paths' shapes); :meth:`Walker.motion`
gives the joint motion of a stride, :meth:`Walker.margins` its constraints and
:meth:`Walker.dynamics` its forces and torques. :func:`~hexaleg.gait.analysis.analyze_gait`,
the limits of :mod:`hexaleg.gait.limits` and the study's columns all walk through it.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass

import numpy as np

from hexaleg._typing import ArrayF, Distribution, require_choice
from hexaleg.exceptions import HexalegError
from hexaleg.gait.dynamics import (
    ForceSplit,
    GeneralizedForces,
    LoadedRobot,
    min_norm_split,
    min_torque_split,
)
from hexaleg.gait.feasibility import JointBounds, Violation, gait_margins, violations
from hexaleg.gait.pattern import GaitPhases, gait_phases
from hexaleg.gait.spec import Gait
from hexaleg.gait.trajectory import (
    FootPaths,
    JointMotion,
    LegFrames,
    PathShapes,
    foot_paths,
    joint_motion,
    path_shapes,
)
from hexaleg.gravity import GRAVITY
from hexaleg.ratings import NEEDS_RATING
from hexaleg.robot.model import HexapodModel
from hexaleg.statics.forces import Payload, check_gravity
from hexaleg.statics.ground import LEVEL, Ground
from hexaleg.statics.ratings import check_safety_factor


@dataclass(frozen=True)
class Stride:
    """The feet's paths, the joints' motion and the broken constraints of one stride."""

    paths: FootPaths
    motion: JointMotion
    violations: tuple[Violation, ...]


@dataclass(frozen=True)
class Loads:
    """The generalized forces of a stride and their split among the standing feet."""

    rnea: GeneralizedForces
    split: ForceSplit


class Walker:
    """A robot set up to walk a gait's pattern, at any stride and period.

    Args:
        model: The robot's Pinocchio model.
        gait: The gait (its pattern, samples, step height and heading are used).
        payload: A point mass on the body.
        distribution: How the standing feet share the load.
        ground: The ground walked on: its slope (gravity turns in the body frame, which
            stays parallel to it) and friction μ (the min-torque distribution's, and what
            the standing feet's forces are held to); level by default.
        gravity: Gravitational acceleration g [m/s²].
        safety_factor: F ≥ 1 [-]: every peak torque and joint speed is held within its
            rating / F (:meth:`rated`).

    """

    def __init__(
        self,
        model: HexapodModel,
        gait: Gait,
        payload: Payload | None = None,
        distribution: Distribution = "min-norm",
        ground: Ground = LEVEL,
        gravity: float = GRAVITY,
        safety_factor: float = 1.0,
    ) -> None:
        require_choice("distribution", distribution, Distribution)
        self.model = model
        self.gait = gait
        self.payload = payload or Payload()
        self.distribution = distribution
        self.ground = ground
        self.friction = ground.friction
        self.gravity = check_gravity(gravity)
        self.safety_factor = check_safety_factor(safety_factor)
        self.frames = LegFrames.from_model(model)
        self.bounds = JointBounds.from_model(model)
        self.phases: GaitPhases = gait_phases(model.design, gait.pattern, gait.samples)
        self.shapes: PathShapes = path_shapes(self.phases)
        self._robot: LoadedRobot | None = None

    def carrying(self, payload: Payload) -> Walker:
        """The same walker with another payload (frames, bounds and phases shared)."""
        other = copy.copy(self)
        other.payload, other._robot = payload, None
        return other

    @property
    def gravity_vector(self) -> ArrayF:
        """Gravity in the body frame, which stays parallel to the ground (3,) [m/s²]."""
        return self.ground.gravity(self.gait.heading, self.gravity)

    @property
    def robot(self) -> LoadedRobot:
        """The Pinocchio model with the payload (built on first use)."""
        if self._robot is None:
            self._robot = LoadedRobot(self.model, self.payload, self.gravity_vector)
        return self._robot

    @property
    def heading(self) -> ArrayF:
        """U = (cos ψ, sin ψ, 0), body frame."""
        return np.array([np.cos(self.gait.heading), np.sin(self.gait.heading), 0.0])

    def stride(self, stride: float) -> Stride:
        """The paths, joint motion and violations of stride S [m]."""
        paths = foot_paths(
            self.frames, self.shapes, stride, self.gait.step_height, self.gait.heading
        )
        motion = joint_motion(self.frames, paths)
        margins = self.margins(motion.angles, motion.reach)
        found = violations(margins, self.frames.legs, self.times(self.gait.period))
        return Stride(paths, motion, found)

    def margins(self, theta: ArrayF, reach: ArrayF) -> ArrayF:
        """Every constraint's margin (..., N, 6, 9) along the period [m or rad].

        Args:
            theta: Joint angles (..., N, 6, 3) [rad].
            reach: Hip-to-foot distances (..., N, 6) [m].

        """
        return gait_margins(self.frames, self.bounds, self.phases.stance, theta, reach)

    def times(self, period: float) -> ArrayF:
        """The sample times t_k = k·T/N (N,) [s]."""
        return np.arange(self.gait.samples) * period / self.gait.samples

    def loads(
        self, stride: float, walk: Stride, period: float, rnea: GeneralizedForces | None = None
    ) -> Loads:
        """RNEA along the period and the feet's forces (min-torque: at period T [s]).

        ``rnea``, the stride's generalized forces if already computed (they do not depend
        on the period), saves the inverse dynamics.
        """
        rnea = self.generalized_forces(stride, walk) if rnea is None else rnea
        position = walk.paths.position
        if self.distribution == "min-norm":
            split = min_norm_split(
                self.model, self.frames, self.phases, position, walk.motion, rnea
            )
        else:
            split = min_torque_split(
                self.model,
                self.frames,
                self.phases,
                position,
                walk.motion,
                rnea,
                period,
                self.friction,
            )
        return Loads(rnea, split)

    def generalized_forces(
        self, stride: float, walk: Stride, inertial: ArrayF | None = None
    ) -> GeneralizedForces:
        """RNEA along the period of stride S [m], as static + inertial/T² (any period).

        ``inertial``: the inertial part of another payload's walk of the same stride (the
        payload changes only the static part: :meth:`LoadedRobot.generalized_forces`).
        """
        travel = stride / self.phases.duty_factor * self.heading
        return self.robot.generalized_forces(walk.motion, travel, inertial)

    def rated(self) -> tuple[ArrayF, ArrayF]:
        """Rated torques [N·m] and speeds [rad/s] (root, hip, knee), each divided by F.

        Raises:
            HexalegError: The design gives no ratings (a robot file's efforts of 0): what
                asks for them needs a rating (callers ask :attr:`HexapodDesign.rated` first).

        """
        design, factor = self.model.design, self.safety_factor
        if design.rated_torques is None or design.rated_speeds is None:
            raise HexalegError(f"the design gives no rated torques and speeds: {NEEDS_RATING}")
        return np.array(design.rated_torques) / factor, np.array(design.rated_speeds) / factor
