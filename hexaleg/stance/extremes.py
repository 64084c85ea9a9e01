"""The result of a flexibility analysis: twelve extremes, six ranges (eq 28) and FB (eq 29)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._typing import FlexibilityMode
from hexaleg.cause import Cause
from hexaleg.design import HexapodDesign
from hexaleg.stance.constraints import AXES, TRANSLATIONS, direction_label, displacement_poses
from hexaleg.stance.geometry import StanceGeometry


class FlexibilityWarning(UserWarning):
    """A free-coupled extreme lacks the evidence of a maximum; the best value found is kept."""


@dataclass(frozen=True)
class SearchEvidence:
    """What supports a free-coupled extreme being the maximum over the reachable poses.

    Attributes:
        searches: Local searches run for the direction, from starts spread over a box.
        basins: Distinct optima (by value) those searches ended in, feasible ones only.
        starts_agreeing: Searches that ended at the reported value.
        reachable: A feasible path (steps of 1 mm and 1 mrad) joins the reported pose
            to the nominal stance.
        polished: The final local solve at the reported pose converged.
        unreachable_value: The best value found at a pose that could not be shown
            reachable, where it beats the reported one [m or rad]; None otherwise.

    """

    searches: int
    basins: int
    starts_agreeing: int
    reachable: bool
    polished: bool = True
    unreachable_value: float | None = None

    @property
    def converged(self) -> bool:
        """Whether the evidence supports a maximum.

        A converged, reachable optimum that two searches from different starts reached,
        and no better pose left unexplained.
        """
        return (
            self.polished
            and self.reachable
            and self.starts_agreeing >= 2
            and self.unreachable_value is None
        )

    @property
    def doubt(self) -> str:
        """Why the evidence falls short (empty if it does not)."""
        reasons = []
        if self.starts_agreeing < 2:
            reasons.append(f"reached by {self.starts_agreeing} of {self.searches} searches")
        if not self.reachable:
            reasons.append("no feasible path from the nominal stance was found")
        if not self.polished:
            reasons.append("the final local solve did not converge")
        if self.unreachable_value is not None:
            reasons.append(f"{self.unreachable_value:.6g} found at a pose not shown reachable")
        return "; ".join(reasons)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {
            "converged": self.converged,
            "searches": self.searches,
            "basins": self.basins,
            "starts_agreeing": self.starts_agreeing,
            "reachable": self.reachable,
            "polished": self.polished,
            "unreachable_value": self.unreachable_value,
        }


@dataclass(frozen=True)
class Extreme:
    """How far the body goes in one direction.

    Attributes:
        axis: One of :data:`AXES`.
        sign: +1 or −1.
        value: Signed displacement from the nominal pose at the extreme [m or rad].
        limited_by: The constraint that stops it: the first, in constraint order, of
            those that bind together (mirror-image legs often do).
        binding: Every constraint that binds there, ``limited_by`` first.
        pose: The body's displacement from the nominal stance there: x, y, z [m], roll,
            pitch, yaw [rad] (world frame, Pinocchio's ``rpy``).
        joint_angles: Each stance leg's (θ1, θ2, θ3) there [rad].
        evidence: For a free-coupled extreme, what supports it being the maximum
            (None for an axis-locked one, which is exact).

    """

    axis: str
    sign: int
    value: float
    limited_by: Cause
    binding: tuple[Cause, ...] = ()
    pose: tuple[float, ...] = ()
    joint_angles: dict[str, tuple[float, float, float]] = field(default_factory=dict)
    evidence: SearchEvidence | None = None

    def __post_init__(self) -> None:
        if not self.binding:
            object.__setattr__(self, "binding", (self.limited_by,))

    @property
    def name(self) -> str:
        """The direction's label, e.g. ``x+`` or ``yaw-``."""
        return direction_label(self.axis, self.sign)

    @property
    def description(self) -> str:
        """What stops the body, naming every leg that binds: "lf, rf knee joint at ..."."""
        return self._summary(list_others=True)

    @property
    def label(self) -> str:
        """:attr:`description` short enough for a plot: the first cause and how many more."""
        return self._summary(list_others=False)

    def _summary(self, list_others: bool) -> str:
        first, others = self.limited_by, self.binding[1:]
        if not others:
            return str(first)
        if first.leg and all(c.leg and c.same_constraint_as(first) for c in others):
            legs = ", ".join([first.leg, *(c.leg for c in others if c.leg)])
            return str(first).replace(first.leg, legs, 1)
        if list_others:
            return f"{first} (also {', '.join(str(c) for c in others)})"
        return f"{first} (+{len(others)} more)"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (value in m or rad)."""
        return {
            "axis": self.axis,
            "sign": self.sign,
            "value": self.value,
            "limited_by": self.limited_by.to_dict(),
            "description": self.description,
            "binding": [cause.to_dict() for cause in self.binding],
            "pose": list(self.pose),
            "joint_angles": {leg: list(angles) for leg, angles in self.joint_angles.items()},
            "evidence": None if self.evidence is None else self.evidence.to_dict(),
        }


@dataclass(frozen=True)
class FlexibilityResult:
    """The twelve extremes, the six ranges (eq 28) and FB (eq 29) of one design.

    Attributes:
        design: The design analysed.
        legs: Stance legs.
        mode: ``"axis"`` (axis-locked) or ``"free"`` (free-coupled).
        extremes: One per direction of :data:`DIRECTIONS`.
        converged: False if a free-coupled extreme lacks the evidence of a maximum
            (see :attr:`doubts`).
        iterations: Optimizer iterations summed over the twelve directions (0 for axis mode).
        collisions: Whether the robot's own parts touching stopped the body too.

    """

    design: HexapodDesign
    legs: tuple[str, ...]
    mode: FlexibilityMode
    extremes: tuple[Extreme, ...]
    converged: bool = True
    iterations: int = 0
    collisions: bool = False

    def extreme(self, axis: str, sign: int) -> Extreme:
        """The extreme in direction (axis, sign)."""
        return next(e for e in self.extremes if e.axis == axis and e.sign == sign)

    @property
    def doubts(self) -> tuple[str, ...]:
        """For each extreme whose evidence falls short, its direction and why."""
        return tuple(
            f"{e.name}: {e.evidence.doubt}"
            for e in self.extremes
            if e.evidence is not None and not e.evidence.converged
        )

    @property
    def ranges(self) -> dict[str, float]:
        """S_x, S_y, S_z [m] and φ_x, φ_y, φ_z [rad] (eq 28), keyed x y z roll pitch yaw."""
        return {a: self.extreme(a, 1).value - self.extreme(a, -1).value for a in AXES}

    @property
    def fb(self) -> float:
        """Flexibility index FB (eq 29), angles in degrees as the paper defines it [-]."""
        return flexibility_index(self.ranges, self.design.leg_length)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: fb, ranges, extremes and every design field used."""
        return {
            "fb": self.fb,
            "mode": self.mode,
            "stance": list(self.legs),
            "converged": self.converged,
            "warnings": list(self.doubts),
            "collisions": self.collisions,
            "ranges": self.ranges,
            "extremes": [e.to_dict() for e in self.extremes],
            "units": {
                "x y z": "m",
                "roll pitch yaw": "rad",
                "fb": "1",
                "pose": "x y z [m], roll pitch yaw [rad], world frame, from the nominal stance",
                "joint_angles": "rad",
            },
            "design": self.design.as_dict(),
        }


def flexibility_index(ranges: dict[str, float], leg_length: float) -> float:
    """FB = (1/6)·[(S_x+S_y+S_z)/(2L) + (φ_x+φ_y+φ_z)/180°] (eq 29).

    Args:
        ranges: S_x, S_y, S_z [m] and φ_x, φ_y, φ_z [rad], keyed as :data:`AXES`.
        leg_length: L = l1 + l2 + l3 [m].

    """
    translation = sum(ranges[a] for a in TRANSLATIONS) / (2 * leg_length)
    rotation = sum(math.degrees(ranges[a]) for a in AXES[3:]) / 180.0
    return (translation + rotation) / 6.0


def pose_extreme(
    geometry: StanceGeometry,
    axis: str,
    sign: int,
    displacement: npt.ArrayLike,
    binding: Sequence[Cause],
) -> Extreme:
    """The extreme reached at a body displacement (6,), with every stance leg's angles there."""
    return pose_extremes(geometry, [(axis, sign, binding)], np.asarray(displacement)[None])[0]


def pose_extremes(
    geometry: StanceGeometry,
    directions: Sequence[tuple[str, int, Sequence[Cause]]],
    displacements: npt.ArrayLike,
) -> tuple[Extreme, ...]:
    """Extremes at body displacements (K, 6), the legs' angles by one vectorized IK.

    Args:
        geometry: The stance.
        directions: Per extreme, its axis, sign and binding constraints.
        displacements: Per extreme, the body displacement there (m, rad).

    """
    d = np.asarray(displacements, dtype=float).reshape(-1, len(AXES))
    rotation, translation = displacement_poses(geometry, d)
    theta, _ = geometry.leg_solutions(geometry.feet_in_roots(rotation, translation))
    extremes = []
    for (axis, sign, binding), pose, angles in zip(directions, d, theta, strict=True):
        extremes.append(
            Extreme(
                axis,
                sign,
                float(pose[AXES.index(axis)]),
                binding[0],
                tuple(binding),
                tuple(pose.tolist()),
                {
                    leg: (float(a), float(b), float(c))
                    for leg, (a, b, c) in zip(geometry.legs, angles, strict=True)
                },
            )
        )
    return tuple(extremes)
