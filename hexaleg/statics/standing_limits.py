"""Standing on a slope with a payload, every heading: the steepest slope, the largest payload.

The robot holds its nominal stance on a slope α uphill toward a heading ψ (the body
parallel to the ground, as in :mod:`hexaleg.statics.slopes`), carrying a payload m at
its point. With the minimum-norm foot forces every joint torque is linear in the
gravity vector and affine in m (so are the equilibrium equations and the generalized
gravity), so the statics under three gravity directions and two payloads give it for
every slope, heading and payload:

    τ(m, α, ψ) = cos α·τ_z(m) − sin α·(cos ψ·τ_x(m) + sin ψ·τ_y(m)),

τ_z under gravity −g·e_z and τ_x, τ_y under +g·e_x and +g·e_y (ground frame). Over
every heading the largest |τ| of a joint is cos α·|τ_z| + sin α·|(τ_x, τ_y)| = A·sin(α + φ),
A = |(τ_z, τ_x, τ_y)|, φ = atan2(|τ_z|, |(τ_x, τ_y)|).

The robot *stands* with m on α when, on every slope from level up to α and in every
heading, every joint's |τ| stays within its rating, the gravity line through the centre
of mass c meets the ground inside the support polygon (c_z·tan α below the distance d
from c's footprint to the polygon's nearest edge: the worst heading is toward that
edge), and tan α ≤ μ. Each condition holds on an interval of m from 0 (the torque bound
is convex in m, the tip margin concave), so the largest payload and the steepest slope
are found joint by joint, exactly or by bisection to 10⁻¹⁰ kg.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.cause import Cause
from hexaleg.gravity import GRAVITY
from hexaleg.robot.model import LEG_JOINTS
from hexaleg.statics.forces import PAYLOAD_SEARCH_LIMIT, Statics
from hexaleg.statics.support import SupportPolygon

BISECTIONS = 48
"""Halvings of the payload interval [0, 10⁴ kg]: to 4·10⁻¹¹ kg."""


@dataclass(frozen=True)
class Standing:
    """The nominal stance's joint torques and centre of mass as payload and gravity vary.

    Attributes:
        legs: Stance legs (N,).
        rated: Rated torques (root, hip, knee) (3,) [N·m].
        down: Torques under gravity −g·e_z (2, N, 3) [N·m]: without payload, and per kg.
        across: Torques under gravity +g·e_x and +g·e_y (2, 2, N, 3) [N·m]: likewise.
        robot_mass: The robot's own mass [kg].
        robot_com: Its centre of mass, ground frame (3,) [m].
        payload_point: Where the payload sits, ground frame (3,) [m].
        support: The stance feet's support polygon.
        friction: Friction coefficient μ [-].

    """

    legs: tuple[str, ...]
    rated: ArrayF
    down: ArrayF
    across: ArrayF
    robot_mass: float
    robot_com: ArrayF
    payload_point: ArrayF
    support: SupportPolygon
    friction: float

    @classmethod
    def of(cls, statics: Statics, q: npt.ArrayLike | None = None) -> Standing:
        """The maps of ``statics``' robot at configuration ``q`` (default: the nominal stance)."""
        q = statics.model.nominal_configuration() if q is None else np.asarray(q, dtype=float)
        # z components other than −g: Statics takes a gravity of z = −g for the upright one
        gravities = GRAVITY * np.array([[0.0, 0.0, -1.0], [1.0, 0.0, -2.0], [0.0, 1.0, -2.0]])
        states = [
            [statics.state(q, gravity=g, payload=statics.payload.with_mass(m)) for g in gravities]
            for m in (0.0, 1.0)
        ]
        torques = np.array([[s.joint_torques for s in row] for row in states])  # (2, 3, N, 3)
        down = torques[:, 0]
        across = torques[:, 1:] - 2 * down[:, None]  # +g·e_x = (g, 0, −2g) − 2·(0, 0, −g)
        own, loaded = states[0][0], states[1][0]
        point = loaded.com * loaded.mass - own.com * own.mass  # the 1 kg payload's place
        return cls(
            legs=statics.legs,
            rated=np.asarray(statics.rated, dtype=float),
            down=np.stack([down[0], down[1] - down[0]]),
            across=np.stack([across[0], across[1] - across[0]]),
            robot_mass=own.mass,
            robot_com=own.com,
            payload_point=point,
            support=statics.support,
            friction=statics.friction,
        )

    # -- the pieces --------------------------------------------------------------------

    def torque_parts(self, mass: float | ArrayF) -> tuple[ArrayF, ArrayF]:
        """(|τ_z|, |(τ_x, τ_y)|) per stance joint (N, 3) [N·m] with payload ``mass`` [kg].

        ``mass`` may also be an array (N, 3): each joint's own payload.
        """
        down = self.down[0] + mass * self.down[1]
        across = self.across[0] + mass * self.across[1]
        return np.abs(down), np.hypot(across[0], across[1])

    def worst_torques(self, mass: float | ArrayF, slope: float) -> ArrayF:
        """Largest |τ| per joint (N, 3) [N·m] over every heading and every slope in [0, slope]."""
        normal, tangential = self.torque_parts(mass)
        peak = np.hypot(normal, tangential)  # A, reached at α = π/2 − φ
        reached = np.arctan2(tangential, normal) <= slope  # π/2 − φ ≤ slope
        at_slope = normal * math.cos(slope) + tangential * math.sin(slope)
        return np.where(reached, peak, at_slope)

    def com(self, mass: float) -> ArrayF:
        """Centre of mass of robot and payload ``mass`` [kg], ground frame (3,) [m]."""
        total = self.robot_mass + mass
        return (self.robot_mass * self.robot_com + mass * self.payload_point) / total

    def tip_slope(self, mass: float) -> float:
        """The slope [rad] at which the robot with payload ``mass`` tips, in the worst heading."""
        com = self.com(mass)
        distance = self.support.signed_distance(com[:2])
        return math.atan2(distance, com[2]) if distance > 0 else 0.0

    # -- the limits --------------------------------------------------------------------

    def max_slope(self, mass: float) -> tuple[float, Cause]:
        """The steepest slope [rad] stood on in every heading with payload ``mass`` [kg].

        The first slope, from level, at which it tips, slides or a joint reaches its
        rated torque, and what that is.
        """
        normal, tangential = self.torque_parts(mass)
        amplitude = np.hypot(normal, tangential)
        with np.errstate(divide="ignore", invalid="ignore"):
            crossing = np.arcsin(np.minimum(self.rated / amplitude, 1.0))
        crossing = crossing - np.arctan2(normal, tangential)  # A·sin(α + φ) = rated
        crossing = np.where(amplitude <= self.rated, math.pi / 2, crossing)
        crossing = np.where(normal > self.rated, 0.0, np.maximum(crossing, 0.0))
        leg, joint = _first_lowest(crossing)
        limits = [
            (math.atan(self.friction), Cause("slide")),
            (self.tip_slope(mass), Cause("tip")),
            (float(crossing[leg, joint]), Cause("torque", self.legs[leg], LEG_JOINTS[joint])),
        ]
        return min(limits, key=lambda limit: limit[0])

    def max_payload(self, slope: float) -> tuple[float, Cause]:
        """The largest payload [kg] held on every slope up to ``slope`` [rad], every heading.

        At most :data:`~hexaleg.statics.forces.PAYLOAD_SEARCH_LIMIT` (then limited by
        ``"search limit"``); 0 if the robot alone does not stand there.
        """
        if math.tan(slope) > self.friction:
            return 0.0, Cause("slide")
        tip = Cause("tip" if slope > 0 else "stability")
        tip_mass = self.tip_payload(slope)
        torque_mass = _largest(
            lambda m: self.rated - self.worst_torques(m, slope),
            self.down.shape[1:],
            PAYLOAD_SEARCH_LIMIT,
        )
        leg, joint = _first_lowest(torque_mass)
        limits = [
            (float(tip_mass), tip),
            (float(torque_mass[leg, joint]), Cause("torque", self.legs[leg], LEG_JOINTS[joint])),
        ]
        mass, cause = min(limits, key=lambda limit: limit[0])
        if mass >= PAYLOAD_SEARCH_LIMIT:
            return PAYLOAD_SEARCH_LIMIT, Cause("search limit")
        return mass, cause

    def tip_payload(self, slope: float) -> float:
        """The payload [kg] at which the robot tips on ``slope`` [rad] in the worst heading.

        The gravity line stays inside while every edge's inward distance of the centre of
        mass's footprint exceeds c_z·tan α; with the payload m the centre of mass moves
        along the segment from the robot's own toward the payload's point,
        c = c_r + s·(p − c_r) with s = m / (M + m), and each edge's margin is affine in s:
        it is lost at the smallest root (inf: never; 0: already).
        """
        start = self._edge_margins(self.robot_com, slope)
        end = self._edge_margins(self.payload_point, slope)
        if start.min() <= 0:
            return 0.0
        falling = end < 0
        if not falling.any():
            return math.inf
        share = float((start[falling] / (start[falling] - end[falling])).min())
        return self.robot_mass * share / (1 - share)

    def _edge_margins(self, point: ArrayF, slope: float) -> ArrayF:
        """Each support edge's inward distance of ``point``'s footprint less z·tan α (K,) [m]."""
        relative = point[:2] - self.support.vertices
        edges = self.support.edges
        inward = (
            edges[:, 0] * relative[:, 1] - edges[:, 1] * relative[:, 0]
        ) / self.support.lengths
        return inward - float(point[2]) * math.tan(slope)


def _largest(margins: Callable[[ArrayF], ArrayF], shape: tuple[int, ...], upper: float) -> ArrayF:
    """Per constraint, the largest m in [0, upper] with a positive margin (0: none; inf: all).

    ``margins(m)`` gives each constraint's margin at its own payload ``m[k]`` (an array of
    ``shape``); each margin is positive on an interval from 0, found by bisection, all
    constraints at once.
    """
    at_zero = margins(np.zeros(shape))
    at_upper = margins(np.full(shape, upper))
    lower, higher = np.zeros(shape), np.full(shape, upper)
    for _ in range(BISECTIONS):
        middle = 0.5 * (lower + higher)
        inside = margins(middle) > 0
        lower = np.where(inside, middle, lower)
        higher = np.where(inside, higher, middle)
    return np.where(at_zero > 0, np.where(at_upper > 0, np.inf, lower), 0.0)


def _first_lowest(values: ArrayF, tolerance: float = 1e-9) -> tuple[int, int]:
    """(leg, joint) of the smallest value, the first in leg order among near-equal ones.

    Mirror-image legs tie, and round-off must not choose between them.
    """
    flat = values.ravel()
    lowest = float(flat.min())
    slack = tolerance * max(1.0, abs(lowest)) if math.isfinite(lowest) else 0.0
    leg, joint = np.unravel_index(int(np.flatnonzero(flat <= lowest + slack)[0]), values.shape)
    return int(leg), int(joint)
