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
    CarriedLoad,
    ForceSplit,
    GeneralizedForces,
    LoadedRobot,
    carried_load,
    min_norm_split,
    min_norm_split_carrying,
    min_torque_split,
)
from hexaleg.gait.feasibility import JointBounds, Violation, gait_margins, violations
from hexaleg.gait.jacobian import LegPartials
from hexaleg.gait.pattern import GaitPhases, gait_phases
from hexaleg.gait.spec import Gait
from hexaleg.gait.stability import Supports, feet_on_ground, zmp_sides
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

    The gait's own stride is walked once, and its min-norm loads, support polygons and ZMP
    sides found once (every analysis of the walker shares them: its walking capacity and
    its period with the max speed); they hold for this walker's ground, payload and g,
    which are read-only: another ground is another walker.

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
        self._model = model
        self._gait = gait
        self._payload = payload or Payload()
        self._distribution: Distribution = distribution
        self._ground = ground
        self._gravity = check_gravity(gravity)
        self._safety_factor = check_safety_factor(safety_factor)
        self.frames = LegFrames.from_model(model)
        self.bounds = JointBounds.from_model(model)
        self.phases: GaitPhases = gait_phases(model.design, gait.pattern, gait.samples)
        self.shapes: PathShapes = path_shapes(self.phases)
        self._robot: LoadedRobot | None = None
        self._own: Stride | None = None  # the gait's own stride, walked once
        self._own_loads: Loads | None = None  # its min-norm loads, computed once
        self._own_supports: Supports | None = None  # its support polygons, found once
        self._own_sides: ArrayF | None = None  # its ZMP's sides, static and inertial, once

    def carrying(self, payload: Payload) -> Walker:
        """The same robot walking the same gait on the same ground with another payload.

        A new walker (its own walk and loads, none of this one's): what it walks on, how
        it splits the load, g and F are this one's.
        """
        return Walker(
            self.model,
            self.gait,
            payload,
            self.distribution,
            self.ground,
            self.gravity,
            self.safety_factor,
        )

    # What the walk's caches depend on is read-only: another ground, payload, split, g
    # or F is another walker (:meth:`carrying`), never a cached walk or load of this one.

    @property
    def model(self) -> HexapodModel:
        """The robot's Pinocchio model."""
        return self._model

    @property
    def gait(self) -> Gait:
        """The gait walked."""
        return self._gait

    @property
    def payload(self) -> Payload:
        """The point mass on the body."""
        return self._payload

    @property
    def distribution(self) -> Distribution:
        """How the standing feet share the load."""
        return self._distribution

    @property
    def ground(self) -> Ground:
        """The ground walked on: its slope and friction."""
        return self._ground

    @property
    def friction(self) -> float:
        """The ground's friction coefficient μ [-]."""
        return self._ground.friction

    @property
    def gravity(self) -> float:
        """Gravitational acceleration g [m/s²]."""
        return self._gravity

    @property
    def safety_factor(self) -> float:
        """F ≥ 1 [-]: peak torques and joint speeds held within rating / F."""
        return self._safety_factor

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
        """The paths, joint motion and violations of stride S [m].

        The gait's own stride is walked once: every analysis of it shares that walk.
        """
        if stride == self.gait.stride and self._own is not None:
            return self._own
        paths = foot_paths(
            self.frames, self.shapes, stride, self.gait.step_height, self.gait.heading
        )
        motion = joint_motion(self.frames, paths)
        margins = self.margins(motion.angles, motion.reach, motion.partials)
        found = violations(margins, self.frames.legs, self.times(self.gait.period))
        walk = Stride(paths, motion, found)
        if stride == self.gait.stride:
            self._own = walk
        return walk

    def supports(self, walk: Stride, configurations: ArrayF) -> Supports:
        """The standing feet's polygons along ``walk``, ground frame.

        ``configurations``: the body's poses along it (its generalized forces', (N, nq)).
        The gait's own stride's are found once: its capacity, max speed and ZMP margins
        share them.
        """
        if walk is self._own and self._own_supports is not None:
            return self._own_supports
        feet = feet_on_ground(walk.paths.position, configurations, self.frames.height)
        found = Supports.of_feet(feet, self.phases)
        if walk is self._own:
            self._own_supports = found
        return found

    def zmp_sides(self, walk: Stride, rnea: GeneralizedForces) -> ArrayF:
        """The ZMP's side of every support edge along ``walk``: static, inertial (2, E).

        F_z·cross(edge, ZMP − vertex) (:func:`~hexaleg.gait.stability.zmp_sides`) of the
        generalized forces' two parts, ``rnea`` (the walk's): at period T the sides are
        static + inertial/T², all ≥ 0 while the ZMP is inside. The gait's own stride's are
        found once: its walking capacity and max speed share them.
        """
        if walk is self._own and self._own_sides is not None:
            return self._own_sides
        configurations = rnea.configurations
        parts = np.stack((rnea.static[:, :6], rnea.inertial[:, :6]))
        supports = self.supports(walk, configurations)
        found = zmp_sides(parts, self.frames.height, configurations[:, :2], supports)
        if walk is self._own:
            self._own_sides = found
        return found

    def margins(self, theta: ArrayF, reach: ArrayF, partials: LegPartials | None = None) -> ArrayF:
        """Every constraint's margin (..., N, 6, 9) along the period [m or rad].

        Args:
            theta: Joint angles (..., N, 6, 3) [rad].
            reach: Hip-to-foot distances (..., N, 6) [m].
            partials: The angles' partials, if known (:func:`gait_margins`).

        """
        stance = self.phases.stance
        return gait_margins(self.frames, self.bounds, stance, theta, reach, partials)

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

    def own_loads_carrying(self, wrench: ArrayF) -> tuple[Loads, CarriedLoad]:
        """The gait's own stride's min-norm loads and what a wrench adds, in one solve.

        What the wrench (6,) [N, N·m], constant on the base's rows (a payload's, on this
        walker's ground: :func:`~hexaleg.gait.dynamics.payload_wrench` of
        :attr:`gravity_vector`), adds is the feet's forces and the joint torques
        (N, 6, 3). The loads are the ones :meth:`loads` then shares.

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
            return loads, carried_load(self.frames, self.phases, position, motion, wrench)
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
        """Rated torques [N·m] and speeds [rad/s] (root, hip, knee), each divided by F.

        Raises:
            HexalegError: The design gives no ratings (a robot file's efforts of 0): what
                asks for them needs a rating (callers ask :attr:`HexapodDesign.rated` first).

        """
        design, factor = self.model.design, self.safety_factor
        if design.rated_torques is None or design.rated_speeds is None:
            raise HexalegError(f"the design gives no rated torques and speeds: {NEEDS_RATING}")
        return np.array(design.rated_torques) / factor, np.array(design.rated_speeds) / factor
