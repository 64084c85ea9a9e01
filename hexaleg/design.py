"""The hexapod design: segment lengths, body, leg mounting, posture and limits.

A :class:`HexapodDesign` is immutable and validated on construction: every
field is checked in ``__post_init__`` and a :class:`~hexaleg.exceptions.DesignError`
names the field, the value given and what is allowed.

Defaults (each one a field, none hidden in code):

- segments: the paper's l1 = 0.2 m, l2 = 0.4 m, l3 = 0.4 m (§4.1);
- body: a 1.0 m × 0.6 m × 0.1 m box (x forward, y left, z up), 60 kg;
- mounting: legs at the four corners and the two side mid-points of the body's
  mid-plane, each pointing straight outward (front ±45°, middle ±90°,
  rear ±135°), named ``lf lm lr rf rm rr`` (left/right, front/middle/rear);
- nominal posture: every leg at θ = (0, 0, −π/2): coxa outward, femur
  horizontal, tibia vertical. The body then stands at l3 above the ground.

The paper gives no body size, mounting or posture; the study functions report
how results depend on them.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass, field, fields, replace
from functools import cached_property
from typing import Any, cast

import numpy as np
import numpy.typing as npt

from hexaleg.exceptions import DesignError
from hexaleg.kinematics import foot_position
from hexaleg.limits import (
    IMPROVED_LIMITS,
    MANIPULABILITY_LIMITS,
    STANCE_LIMITS,
    WORKSPACE_LIMITS,
    JointLimits,
)

LEG_NAMES: tuple[str, ...] = ("lf", "lm", "lr", "rf", "rm", "rr")
"""Default leg names: left/right × front/middle/rear."""

TRIPODS: tuple[tuple[str, str, str], tuple[str, str, str]] = (
    ("lf", "rm", "lr"),
    ("rf", "lm", "rr"),
)
"""The two alternating tripods of the default leg names."""

SEGMENT_RANGE = (1e-3, 100.0)
"""Plausible segment length l1, l2, l3 [m]: a millimetre to a hundred metres."""
BODY_RANGE = (1e-2, 100.0)
"""Plausible body extent and leg-mount offset [m]."""

FIELD_RANGES: dict[str, tuple[float, float, str]] = {
    "l1": (*SEGMENT_RANGE, "m"),
    "l2": (*SEGMENT_RANGE, "m"),
    "l3": (*SEGMENT_RANGE, "m"),
    "body_length": (*BODY_RANGE, "m"),
    "body_width": (*BODY_RANGE, "m"),
    "body_height": (*BODY_RANGE, "m"),
    "body_mass": (1e-3, 1e6, "kg"),
    "link_linear_density": (1e-4, 1e5, "kg/m"),
    "link_radius": (1e-4, 10.0, "m"),
}
"""Each physical field's plausible range (lower, upper, unit); values outside are refused."""

DEFAULT_RATED_TORQUES: tuple[float, float, float] = (60.0, 150.0, 120.0)
"""Rated torques (root, hip, knee) [N·m] of the default 60 kg body's actuators. At the
nominal stance each hip holds about 46 N·m (a sixth of the 84 kg robot, 0.4 m out) and
the knee almost nothing; the ratings leave room for the body's extremes, where hip and
knee torques peak, and for a payload of a few times the body's mass."""

TORQUE_RANGE = (1e-3, 1e6)
"""Plausible rated torque [N·m]."""

SEGMENTS = ("l1", "l2", "l3")
"""The segment-length fields: coxa, femur, tibia."""

FOOT_MASS = 1e-3
"""Mass of each foot link [kg]: negligible beside the legs, but a valid inertial, so
that every simulator keeps the foot (sdformat drops massless links, PyBullet weighs
them 1 kg)."""

_NAME_PATTERN = re.compile(r"^[a-z][a-z0-9_]{0,31}$")


@dataclass(frozen=True)
class LegMount:
    """Where one leg's root joint sits on the body.

    Attributes:
        name: Leg name, a lower-case identifier used in URDF link/joint names.
        x: Root position along the body's x axis (forward) [m].
        y: Root position along the body's y axis (left) [m].
        z: Root position along the body's z axis (up) [m].
        yaw: Direction of the coxa at θ1 = 0, about the body z axis [rad].

    """

    name: str
    x: float
    y: float
    z: float
    yaw: float

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not _NAME_PATTERN.match(self.name):
            raise DesignError(
                "mount.name", self.name, "a lower-case identifier like 'lf' (letters, digits, _)"
            )
        for name in ("x", "y", "z", "yaw"):
            value = getattr(self, name)
            field = f"mounts[{self.name}].{name}"
            limit = math.pi if name == "yaw" else BODY_RANGE[1]
            unit = "rad" if name == "yaw" else "m"
            object.__setattr__(self, name, require_in_range(field, value, -limit, limit, unit))

    @property
    def position(self) -> npt.NDArray[np.float64]:
        """Root position in the body frame [m]."""
        return np.array([self.x, self.y, self.z])


def default_mounts(body_length: float, body_width: float) -> tuple[LegMount, ...]:
    """Legs at the corners and side mid-points of the body's mid-plane, pointing outward.

    Args:
        body_length: Body extent along x [m].
        body_width: Body extent along y [m].

    """
    hx, hy = body_length / 2, body_width / 2
    q = math.pi / 4
    return (
        LegMount("lf", hx, hy, 0.0, q),
        LegMount("lm", 0.0, hy, 0.0, 2 * q),
        LegMount("lr", -hx, hy, 0.0, 3 * q),
        LegMount("rf", hx, -hy, 0.0, -q),
        LegMount("rm", 0.0, -hy, 0.0, -2 * q),
        LegMount("rr", -hx, -hy, 0.0, -3 * q),
    )


@dataclass(frozen=True)
class HexapodDesign:
    """A hexapod whose legs are to be sized.

    Attributes:
        l1: Coxa length [m].
        l2: Femur length [m].
        l3: Tibia length [m].
        body_length: Body box extent along x [m].
        body_width: Body box extent along y [m].
        body_height: Body box extent along z [m].
        mounts: The six leg roots; ``None`` means :func:`default_mounts` of the body size.
        nominal_angles: Standing joint angles (θ1, θ2, θ3) of every leg [rad].
        workspace_limits: Table 2 limits, used for the Monte Carlo workspace.
        improved_limits: Table 4 limits (coupled knee), the improved workspace.
        manipulability_limits: Eq 26 limits, for the optimum pose and w_A.
        stance_limits: Limits that stop the body in the flexibility study (§6).
        body_mass: Body mass [kg].
        link_linear_density: Mass per length of coxa, femur and tibia [kg/m].
        link_radius: Radius of the links' cylinder geometry [m].
        rated_torques: The actuators' rated torques (root, hip, knee) [N·m], written to
            each joint's URDF ``effort``; the statics compare every torque with them.

    """

    l1: float = 0.2
    l2: float = 0.4
    l3: float = 0.4
    body_length: float = 1.0
    body_width: float = 0.6
    body_height: float = 0.1
    mounts: tuple[LegMount, ...] | None = None
    nominal_angles: tuple[float, float, float] = (0.0, 0.0, -math.pi / 2)
    workspace_limits: JointLimits = WORKSPACE_LIMITS
    improved_limits: JointLimits = IMPROVED_LIMITS
    manipulability_limits: JointLimits = MANIPULABILITY_LIMITS
    stance_limits: JointLimits = STANCE_LIMITS
    body_mass: float = 60.0
    link_linear_density: float = 4.0
    link_radius: float = field(default=0.025)
    rated_torques: tuple[float, float, float] = DEFAULT_RATED_TORQUES

    def __post_init__(self) -> None:
        for name, (lower, upper, unit) in FIELD_RANGES.items():
            value = require_in_range(name, getattr(self, name), lower, upper, unit)
            object.__setattr__(self, name, value)
        self._validate_rated_torques()
        self._validate_mounts()
        self._validate_nominal_stance()

    # -- constructors ---------------------------------------------------------------------

    @classmethod
    def from_ratios(
        cls, l1_ratio: float, l3_ratio: float, total: float = 1.0, **fields: Any
    ) -> HexapodDesign:
        """Design from segment ratios of a total leg length, as the paper sweeps them.

        Args:
            l1_ratio: Coxa length over total leg length [-].
            l3_ratio: Tibia length over total leg length [-].
            total: Total leg length l1 + l2 + l3 [m].
            **fields: Any other :class:`HexapodDesign` field.

        """
        total = require_in_range("total", total, 3 * SEGMENT_RANGE[0], 3 * SEGMENT_RANGE[1], "m")
        l1_ratio = require_ratio("l1_ratio", l1_ratio)
        l3_ratio = require_ratio("l3_ratio", l3_ratio)
        if not l1_ratio + l3_ratio < 1.0:
            raise DesignError(
                "l1_ratio + l3_ratio",
                l1_ratio + l3_ratio,
                "must be < 1 so that the femur ratio 1 - l1_ratio - l3_ratio is positive",
            )
        l1, l3 = l1_ratio * total, l3_ratio * total
        return cls(l1=l1, l2=total - l1 - l3, l3=l3, **fields)

    def with_ratios(
        self, l1_ratio: float, l3_ratio: float, total: float | None = None
    ) -> HexapodDesign:
        """Copy of the design (body, mounts, posture, limits) with its segments at these ratios.

        Args:
            l1_ratio: Coxa length over total leg length [-].
            l3_ratio: Tibia length over total leg length [-].
            total: Total leg length [m]; this design's own if omitted.

        """
        kept = {f.name: getattr(self, f.name) for f in fields(self) if f.name not in SEGMENTS}
        total = self.leg_length if total is None else total
        return HexapodDesign.from_ratios(l1_ratio, l3_ratio, total, **kept)

    def replace(self, **changes: Any) -> HexapodDesign:
        """Copy with some fields changed (validated again).

        Changing the body size without passing ``mounts`` moves default-placed legs
        to the new body's corners; explicitly placed legs stay where they were.
        """
        if (
            "mounts" not in changes
            and {"body_length", "body_width"} & changes.keys()
            and self.mounts == default_mounts(self.body_length, self.body_width)
        ):
            changes["mounts"] = None
        return replace(self, **changes)

    # -- derived quantities ---------------------------------------------------------------

    @property
    def lengths(self) -> tuple[float, float, float]:
        """Segment lengths (l1, l2, l3) [m]."""
        return (self.l1, self.l2, self.l3)

    @property
    def leg_length(self) -> float:
        """Total leg length L = l1 + l2 + l3 [m] (eq 29)."""
        return self.l1 + self.l2 + self.l3

    @property
    def total_mass(self) -> float:
        """Mass of the whole robot [kg]: body, six legs' links, six feet."""
        legs = 6 * (self.link_linear_density * self.leg_length + FOOT_MASS)
        return self.body_mass + legs

    @property
    def legs(self) -> tuple[LegMount, ...]:
        """The six leg mounts, in mounting order (``mounts`` as resolved on construction)."""
        return cast(tuple[LegMount, ...], self.mounts)

    @property
    def leg_names(self) -> tuple[str, ...]:
        """Names of the legs, in mounting order."""
        return tuple(m.name for m in self.legs)

    @cached_property
    def nominal_height(self) -> float:
        """Height of the body frame above the ground at the nominal stance [m]."""
        foot_z = foot_position(self.lengths, self.nominal_angles)[2]
        return float(-(self.legs[0].z + foot_z))

    @property
    def joint_range(self) -> JointLimits:
        """Envelope of every named limit set: the joint limits written into the URDF."""
        envelope = self.workspace_limits
        for limits in (self.improved_limits, self.manipulability_limits, self.stance_limits):
            envelope = envelope.envelope(limits)
        return replace(envelope, name="joint_range")

    def as_dict(self) -> dict[str, Any]:
        """Every field as plain JSON-ready values (SI units, radians)."""
        out: dict[str, Any] = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name == "mounts":
                value = [vars(m).copy() for m in value]
            elif isinstance(value, JointLimits):
                value = {
                    "theta1": list(value.theta1),
                    "theta2": list(value.theta2),
                    "theta3": list(value.theta3),
                    "coupled_knee": value.coupled_knee,
                }
            elif isinstance(value, tuple):
                value = list(value)
            out[f.name] = value
        return out

    # -- validation -----------------------------------------------------------------------

    def _validate_rated_torques(self) -> None:
        torques = tuple(self.rated_torques)
        if len(torques) != 3:
            raise DesignError("rated_torques", torques, "three torques (root, hip, knee) [N·m]")
        checked = tuple(
            require_in_range(f"rated_torques.{joint}", value, *TORQUE_RANGE, "N·m")
            for joint, value in zip(("root", "hip", "knee"), torques, strict=True)
        )
        object.__setattr__(self, "rated_torques", checked)

    def _validate_mounts(self) -> None:
        mounts = self.mounts
        if mounts is None:
            mounts = default_mounts(self.body_length, self.body_width)
        if not isinstance(mounts, Sequence) or not all(isinstance(m, LegMount) for m in mounts):
            raise DesignError("mounts", mounts, "a sequence of six LegMount")
        mounts = tuple(mounts)
        if len(mounts) != 6:
            raise DesignError("mounts", len(mounts), "exactly 6 legs (a hexapod)")
        names = [m.name for m in mounts]
        if len(set(names)) != len(names):
            raise DesignError("mounts", names, "leg names must be unique")
        heights = {m.z for m in mounts}
        if len(heights) != 1:
            raise DesignError(
                "mounts[*].z",
                sorted(heights),
                "every leg root at the same height, so that all feet reach level ground [m]",
            )
        object.__setattr__(self, "mounts", mounts)

    def _validate_nominal_stance(self) -> None:
        angles = tuple(self.nominal_angles)
        if len(angles) != 3:
            raise DesignError("nominal_angles", angles, "three angles (θ1, θ2, θ3) [rad]")
        for name, value in zip(("theta1", "theta2", "theta3"), angles, strict=True):
            _require_finite(f"nominal_angles.{name}", value)
        angles = tuple(float(a) for a in angles)
        object.__setattr__(self, "nominal_angles", angles)
        limits = self.stance_limits
        for i, name in enumerate(("theta1", "theta2", "theta3")):
            lower, upper = getattr(limits, name)
            if not lower <= angles[i] <= upper:
                raise DesignError(
                    f"nominal_angles.{name}",
                    angles[i],
                    f"must lie within stance_limits.{name} = [{lower:.6g}, {upper:.6g}] [rad]",
                )
        clearance = self.nominal_height - self.body_height / 2
        if not clearance > 0:
            raise DesignError(
                "nominal_angles",
                angles,
                "the feet must stand below the body's underside (clearance "
                f"{clearance:.4g} m); lower the hip or bend the knee further down",
            )


def _require_finite(name: str, value: Any) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise DesignError(name, value, "must be a real number") from None
    if not math.isfinite(number):
        raise DesignError(name, value, "must be finite")
    return number


def require_in_range(name: str, value: Any, lower: float, upper: float, unit: str) -> float:
    """``value`` as a float if it is a real number in [lower, upper]; else a DesignError."""
    number = _require_finite(name, value)
    if not lower <= number <= upper:
        raise DesignError(name, value, f"must lie in [{lower:g}, {upper:g}] [{unit}]")
    return number


def require_ratio(name: str, value: Any) -> float:
    """``value`` as a float if it lies in the open interval (0, 1); else a DesignError."""
    number = _require_finite(name, value)
    if not 0 < number < 1:
        raise DesignError(name, value, "must lie in the open interval (0, 1)")
    return number


L3_RATIO_RANGE: tuple[float, float] = (0.10, 0.75)
"""Tibia-ratio range of hexaleg's design sweeps [-]. The paper gives only the
count (80 per coxa ratio); this range leaves a femur of at least 5 % of the leg
for every coxa ratio up to 0.20."""


MAX_L3_POINTS = 1000
"""Most tibia ratios per coxa ratio in a sweep: 1000 keeps a sweep to minutes on 2 cores."""


def l3_ratio_grid(points: int = 80) -> npt.NDArray[np.float64]:
    """Evenly spaced tibia ratios over :data:`L3_RATIO_RANGE` [-]."""
    if not 2 <= points <= MAX_L3_POINTS:
        raise DesignError("l3_points", points, f"from 2 to {MAX_L3_POINTS} tibia ratios")
    return np.linspace(*L3_RATIO_RANGE, points)
