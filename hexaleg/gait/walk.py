"""One robot walking one gait: the steps from the gait to the torques, shared by every front door.

:class:`Walker` holds what does not change with the stride or the period (the legs'
frames, their limits, who stands when and the paths' shapes); :meth:`Walker.motion`
gives the joint motion of a stride, :meth:`Walker.margins` its constraints and
:meth:`Walker.dynamics` its forces and torques. :func:`~hexaleg.gait.analysis.analyze_gait`,
the limits of :mod:`hexaleg.gait.limits` and the study's columns all walk through it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg._typing import ArrayF, Distribution, require_choice
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.gait.dynamics import (
    ForceSplit,
    GeneralizedForces,
    LoadedRobot,
    carried_torques,
    min_norm_split,
    min_norm_split_carrying,
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
from hexaleg.statics.forces import DEFAULT_FRICTION, Payload, check_friction, check_gravity


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
        friction: Friction coefficient μ [-] (min-torque distribution).
        gravity: Gravitational acceleration g [m/s²].

    """

    def __init__(
        self,
        model: HexapodModel,
        gait: Gait,
        payload: Payload | None = None,
        distribution: Distribution = "min-norm",
        friction: float = DEFAULT_FRICTION,
        gravity: float = GRAVITY,
    ) -> None:
        require_choice("distribution", distribution, Distribution)
        self.model = model
        self.gait = gait
        self.payload = payload or Payload()
        self.distribution = distribution
        self.friction = check_friction(friction)
        self.gravity = check_gravity(gravity)
        self.frames = LegFrames.from_model(model)
        self.bounds = JointBounds.from_model(model)
        self.phases: GaitPhases = gait_phases(model.design, gait.pattern, gait.samples)
        self.shapes: PathShapes = path_shapes(self.phases)
        self._robot: LoadedRobot | None = None
        self._own: Stride | None = None  # the gait's own stride, walked once
        self._own_loads: Loads | None = None  # its min-norm loads, computed once

    @property
    def robot(self) -> LoadedRobot:
        """The Pinocchio model with the payload (built on first use)."""
        if self._robot is None:
            self._robot = LoadedRobot(self.model, self.payload, self.gravity)
        return self._robot

    @property
    def heading(self) -> ArrayF:
        """U = (cos ψ, sin ψ, 0), body frame."""
        return np.array([np.cos(self.gait.heading), np.sin(self.gait.heading), 0.0])

    def stride(self, stride: float) -> Stride:
        """The paths, joint motion and violations of stride S [m].

        The gait's own stride is walked once: every analysis of it shares that walk.
        """
        if stride == self.gait.stride and self._own is not None:
            return self._own
        paths = foot_paths(
            self.frames, self.shapes, stride, self.gait.step_height, self.gait.heading
        )
        motion = joint_motion(self.frames, paths)
        margins = self.margins(motion.angles, motion.reach)
        found = violations(margins, self.frames.legs, self.times(self.gait.period))
        walk = Stride(paths, motion, found)
        if stride == self.gait.stride:
            self._own = walk
        return walk

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
        on the period), saves the inverse dynamics. The gait's own stride's min-norm loads
        (any period) are computed once.
        """
        shared = walk is self._own and self.distribution == "min-norm"
        known = self._own_loads
        if shared and known is not None and (rnea is None or rnea is known.rnea):
            return known
        if rnea is None:
            travel = stride / self.phases.duty_factor * self.heading
            rnea = self.robot.generalized_forces(walk.motion, travel)
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
        found = Loads(rnea, split)
        if shared and self._own_loads is None:
            self._own_loads = found
        return found

    def own_loads_carrying(self, wrench: ArrayF) -> tuple[Loads, ArrayF]:
        """The gait's own stride's min-norm loads and what a wrench adds, in one solve.

        What the wrench (6,) [N, N·m], constant on the base's rows (a payload's), adds is
        joint torques (N, 6, 3) [N·m]. The loads are the ones :meth:`loads` then shares.

        Raises:
            ParameterError: The walker splits the load otherwise than min-norm.

        """
        if self.distribution != "min-norm":
            raise ParameterError(
                "distribution", self.distribution, "'min-norm': a wrench's torques are its"
            )
        walk, known = self.stride(self.gait.stride), self._own_loads
        if known is not None:
            loads = self.loads(self.gait.stride, walk, self.gait.period)
            position, motion = walk.paths.position, walk.motion
            return loads, carried_torques(self.frames, self.phases, position, motion, wrench)
        travel = self.gait.stride / self.phases.duty_factor * self.heading
        rnea = self.robot.generalized_forces(walk.motion, travel)
        split, carried = min_norm_split_carrying(
            self.model, self.frames, self.phases, walk.paths.position, walk.motion, rnea, wrench
        )
        assert carried is not None  # a wrench was given
        self._own_loads = Loads(rnea, split)
        return self._own_loads, carried

    def generalized_forces(self, stride: float, walk: Stride) -> GeneralizedForces:
        """RNEA along the period of stride S [m], as static + inertial/T² (any period).

        The gait's own stride's are computed once (for its walk from :meth:`stride`).
        """
        if walk is self._own and self.distribution == "min-norm":
            return self.loads(stride, walk, self.gait.period).rnea
        travel = stride / self.phases.duty_factor * self.heading
        return self.robot.generalized_forces(walk.motion, travel)

    def rated(self) -> tuple[ArrayF, ArrayF]:
        """Rated torques [N·m] and speeds [rad/s] (root, hip, knee).

        Raises:
            HexalegError: The design gives no ratings (a robot file's efforts of 0): what
                asks for them needs a rating (callers ask :attr:`HexapodDesign.rated` first).

        """
        design = self.model.design
        if design.rated_torques is None or design.rated_speeds is None:
            raise HexalegError(f"the design gives no rated torques and speeds: {NEEDS_RATING}")
        return np.array(design.rated_torques), np.array(design.rated_speeds)
