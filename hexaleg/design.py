"""The hexapod design: segment lengths, body, leg mounting, posture and limits.

A :class:`HexapodDesign` is immutable and validated on construction: every
field is checked in ``__post_init__`` and a :class:`~hexaleg.exceptions.ParameterError`
names the field, the value given and what is allowed.

Every default is a field's declaration (none hidden in code): the paper's segments
l1 = 0.2 m, l2 = 0.4 m, l3 = 0.4 m (§4.1) on hexaleg's box body, legs at its corners
and side mid-points (:mod:`hexaleg.layouts`), standing with femur level and tibia
vertical, so that the body stands at l3 above the ground. The paper gives no body size,
mounting or posture; the study functions report how results depend on them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from functools import cached_property
from typing import Any, cast

import numpy as np
import numpy.typing as npt

from hexaleg._checks import require_in_range, require_instance, require_ratio
from hexaleg.actuators import Actuators
from hexaleg.battery import Battery, bus_voltage
from hexaleg.exceptions import ParameterError
from hexaleg.field_spec import FieldSpec, attributes_section, declare, field_specs
from hexaleg.grids import (  # noqa: F401
    L3_RATIO_POINTS,
    L3_RATIO_RANGE,
    MAX_L3_POINTS,
    l3_ratio_grid,
    ratio_lengths,
)
from hexaleg.kinematics import foot_position
from hexaleg.layouts import (
    LEG_NAMES,
    TRIPODS,
    Layout,
    LegMount,
    checked_mounts,
    default_mounts,
    hexagon_mounts,
    rectangle_mounts,
    require_apart,
    resolve_layout,
)
from hexaleg.leg_structure import Structure, segment_masses
from hexaleg.limits import (
    IMPROVED_LIMITS,
    JOINT_NAMES,
    LEG_JOINTS,
    MANIPULABILITY_LIMITS,
    STANCE_LIMITS,
    WORKSPACE_LIMITS,
    JointLimits,
)
from hexaleg.ratings import (
    DEFAULT_RATED_SPEEDS,
    DEFAULT_RATED_TORQUES,
    SPEED_RANGE,
    TORQUE_RANGE,
    Ratings,
)

RATING = {"option": "ratings", "optional": True}
"""A rating field's declaration: ``--rated-*``, and ``None`` for not given (a file's 0)."""

SEGMENT_RANGE = (1e-3, 100.0)
"""Plausible segment length l2, l3 [m]: a millimetre to a hundred metres."""
COXA_RANGE = (0.0, SEGMENT_RANGE[1])
"""Plausible coxa length l1 [m]: 0 is a leg whose hip axis meets its yaw axis."""
BODY_RANGE = (1e-2, 100.0)
"""Plausible body extent and leg-mount offset [m]."""

SEGMENTS = ("l1", "l2", "l3")
"""The segment-length fields: coxa, femur, tibia."""

DEFAULT_LEG_LENGTH = 1.0
"""Leg length l1 + l2 + l3 [m] of ratios given without one: the paper's 1000 mm."""

FOOT_MASS = 1e-3
"""Mass of each foot link [kg]: negligible, but a valid inertial, so that every simulator
keeps the foot (sdformat drops massless links, PyBullet weighs them 1 kg)."""

__all__ = [
    "DESIGN_FIELDS",
    "FIELD_RANGES",
    "LEG_NAMES",
    "TRIPODS",
    "HexapodDesign",
    "LegMount",
    "default_mounts",
    "require_design",
    "require_in_range",
    "require_ratio",
]


def require_design(value: Any, name: str = "design") -> HexapodDesign:
    """``value`` if it is a :class:`HexapodDesign`; else a ParameterError naming ``name``."""
    return require_instance(name, value, HexapodDesign, "a HexapodDesign")


@dataclass(frozen=True)
class HexapodDesign:
    """A hexapod whose legs are to be sized.

    Every field is declared once below (:func:`~hexaleg.field_spec.declare`): what it
    is, its unit and plausible range, and the command-line group that offers it. The
    ``Attributes`` section that follows is written from those declarations.

    """

    # a table, one field a row: its declaration's default, meaning, unit and range
    # fmt: off
    l1: float = declare(0.2, "coxa length", "m", COXA_RANGE, option="lengths")
    l2: float = declare(0.4, "femur length", "m", SEGMENT_RANGE, option="lengths")
    l3: float = declare(0.4, "tibia length", "m", SEGMENT_RANGE, option="lengths")
    body_length: float = declare(
        1.0, "body box extent along x, forward", "m", BODY_RANGE, option="body",
        applies="rectangle and custom layouts",
    )
    body_width: float = declare(
        0.6, "body box extent along y, left", "m", BODY_RANGE, option="body",
        applies="rectangle and custom layouts",
    )
    body_height: float = declare(0.1, "body extent along z, up", "m", BODY_RANGE, option="body")
    layout: Layout | None = declare(
        None, "how the legs sit on the body: rectangle (the paper's box), hexagon (legs "
        "every 60° around a cylinder) or custom (the six mounts given; the default when "
        "mounts are)", kind="choice", option="body",
    )
    body_radius: float = declare(
        0.4, "leg roots' distance from the body axis, and the cylinder body's radius", "m",
        BODY_RANGE, option="body", applies="hexagon layout",
    )
    first_leg_angle: float = declare(
        math.pi / 6, "left front leg's direction from straight ahead, in [0, π/3]", "rad",
        (0.0, math.pi / 3), option="body", applies="hexagon layout",
    )
    middle_leg_offset: float = declare(
        0.0, "how much further out than the body's side the middle legs sit", "m",
        (0.0, BODY_RANGE[1]), option="body", applies="rectangle layout",
    )
    front_yaw: float = declare(
        math.pi / 4, "left front coxa direction; the right one mirrors it", "rad",
        (0.0, math.pi), option="body", applies="rectangle layout",
    )
    rear_yaw: float = declare(
        3 * math.pi / 4, "left rear coxa direction; the right one mirrors it", "rad",
        (0.0, math.pi), option="body", applies="rectangle layout",
    )
    mounts: tuple[LegMount, ...] | None = declare(
        None, "the six leg roots (name, x, y, z [m], yaw [rad]); unset: placed by the layout",
        kind="mounts",
    )
    nominal_angles: tuple[float, float, float] = declare(
        (0.0, 0.0, -math.pi / 2), "standing joint angles of every leg", "rad", kind="triple",
        items=JOINT_NAMES, option="posture",
    )
    workspace_limits: JointLimits = declare(
        WORKSPACE_LIMITS, "Table 2 limits: the Monte Carlo workspace", kind="limits"
    )
    improved_limits: JointLimits = declare(
        IMPROVED_LIMITS, "Table 4 limits (coupled knee): the improved workspace", kind="limits"
    )
    manipulability_limits: JointLimits = declare(
        MANIPULABILITY_LIMITS, "eq 26 limits: the optimum pose and average manipulability",
        kind="limits",
    )
    stance_limits: JointLimits = declare(
        STANCE_LIMITS, "limits that stop the body in stance (the paper's §6)", kind="limits"
    )
    body_mass: float = declare(60.0, "body mass", "kg", (1e-3, 1e6))
    link_linear_density: float = declare(
        4.0, "mass per length of a segment without a [structure] tube", "kg/m", (1e-4, 1e5)
    )
    link_radius: float = declare(0.025, "radius of the links' cylinders", "m", (1e-4, 10.0))
    rated_torques: Ratings = declare(
        DEFAULT_RATED_TORQUES, "actuators' rated torques (each URDF joint's effort; none: not "
        "given)", "N·m", TORQUE_RANGE, kind="triple", items=LEG_JOINTS, **RATING)
    rated_speeds: Ratings = declare(
        DEFAULT_RATED_SPEEDS, "actuators' rated speeds (each URDF joint's velocity; none: not "
        "given)", "rad/s", SPEED_RANGE, kind="triple", items=LEG_JOINTS, **RATING)
    actuators: Actuators | None = declare(
        None, "each joint type's motor and gearbox, [actuators.root|hip|knee]; set, its peak "
        "torques and speed ratings are the rated ones", kind="record", record=Actuators,
    )
    battery: Battery | None = declare(None, "the battery, [battery]", kind="record", record=Battery)
    structure: Structure | None = declare(
        None, "the legs' tubes and their material, [structure]; each segment without one "
        "weighs link_linear_density", kind="record", record=Structure,
    )

    def __post_init__(self) -> None:
        for spec in DESIGN_FIELDS:  # each value on its own first, then how they fit together
            object.__setattr__(self, spec.name, spec.check(getattr(self, spec.name)))
        if self.actuators is not None:
            object.__setattr__(self, "rated_torques", self.actuators.rated_torques)
            object.__setattr__(self, "rated_speeds", self.actuators.rated_speeds)
        bus_voltage(self.battery, self.actuators)  # a Battery or None; motors of one bus
        layout = resolve_layout(self.layout, self.mounts)
        object.__setattr__(self, "layout", layout)
        mounts = checked_mounts(layout, self.mounts, self.layout_mounts(), self.link_radius)
        object.__setattr__(self, "mounts", mounts)
        self._validate_nominal_stance()

    # -- constructors ---------------------------------------------------------------------

    @classmethod
    def from_ratios(
        cls, l1_ratio: float, l3_ratio: float, total: float = DEFAULT_LEG_LENGTH, **fields: Any
    ) -> HexapodDesign:
        """Design from segment ratios of a total leg length, as the paper sweeps them.

        Args:
            l1_ratio: Coxa length over total leg length [-].
            l3_ratio: Tibia length over total leg length [-].
            total: Total leg length l1 + l2 + l3 [m].
            **fields: Any other :class:`HexapodDesign` field.

        """
        total = require_in_range("total", total, 3 * SEGMENT_RANGE[0], 3 * SEGMENT_RANGE[1], "m")
        l1, l2, l3 = ratio_lengths(l1_ratio, l3_ratio, total)
        return cls(l1=l1, l2=l2, l3=l3, **fields)

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

        Legs placed by a layout follow the new body fields; passing ``mounts`` without
        ``layout`` places the legs by hand (``layout = "custom"``).
        """
        if "mounts" in changes:
            changes.setdefault("layout", "custom" if changes["mounts"] is not None else None)
        elif changes.get("layout", self.layout) != "custom":
            changes["mounts"] = None
        return replace(self, **changes)

    # -- derived quantities ---------------------------------------------------------------

    @property
    def lengths(self) -> tuple[float, float, float]:
        """Segment lengths (l1, l2, l3) [m]."""
        return (self.l1, self.l2, self.l3)

    @property
    def rated(self) -> bool:
        """Whether both ratings are given: torques and speeds (a robot file may give neither)."""
        return self.rated_torques is not None and self.rated_speeds is not None

    @property
    def leg_length(self) -> float:
        """Total leg length L = l1 + l2 + l3 [m] (eq 29)."""
        return self.l1 + self.l2 + self.l3

    @property
    def total_mass(self) -> float:
        """Mass of the whole robot [kg]: body, six legs' links, feet, actuators, battery."""
        segments = segment_masses(self.structure, self.lengths, self.link_linear_density)
        legs = 6 * (sum(segments) + FOOT_MASS)
        motors = 0.0 if self.actuators is None else self.actuators.total_mass
        return self.body_mass + legs + motors + (0.0 if self.battery is None else self.battery.mass)

    @property
    def bus_voltage(self) -> float | None:
        """The voltage every motor is fed from [V] (:func:`~hexaleg.battery.bus_voltage`)."""
        return bus_voltage(self.battery, self.actuators)

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
    def nominal_footholds(self) -> npt.NDArray[np.float64]:
        """Every foot at the nominal stance, body frame at the origin (6, 3) [m] (eq 7)."""
        x, y, z = foot_position(self.lengths, self.nominal_angles)
        turns = [(math.cos(m.yaw), math.sin(m.yaw)) for m in self.legs]
        feet = np.array([[c * x - s * y, s * x + c * y, z] for c, s in turns])
        return np.array([m.position for m in self.legs]) + feet

    @property
    def body_shape(self) -> str:
        """``"cylinder"`` for the hexagon layout's round body, else ``"box"``."""
        return "cylinder" if self.layout == "hexagon" else "box"

    @property
    def body_description(self) -> str:
        """The body in words, with its sizes [m]."""
        if self.body_shape == "cylinder":
            return (
                f"hexagon layout: cylinder of radius {self.body_radius:g} m and height "
                f"{self.body_height:g} m, legs every 60° from {self.first_leg_angle:.4g} rad"
            )
        size = f"{self.body_length:g} × {self.body_width:g} × {self.body_height:g} m box"
        return f"{self.layout} layout: {size}"

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
                value = value.as_dict()
            elif isinstance(value, Actuators | Battery | Structure):
                value = value.to_table()
            elif isinstance(value, tuple):
                value = list(value)
            out[f.name] = value
        return out

    # -- validation -----------------------------------------------------------------------

    def layout_mounts(self) -> tuple[LegMount, ...] | None:
        """The mounts this design's layout places, or ``None`` for a custom layout."""
        if self.layout == "rectangle":
            return rectangle_mounts(
                self.body_length,
                self.body_width,
                self.middle_leg_offset,
                self.front_yaw,
                self.rear_yaw,
            )
        if self.layout == "hexagon":
            return hexagon_mounts(self.body_radius, self.first_leg_angle)
        return None

    def _validate_nominal_stance(self) -> None:
        angles = self.nominal_angles
        limits = self.stance_limits
        for i, name in enumerate(JOINT_NAMES):
            lower, upper = getattr(limits, name)
            if not lower <= angles[i] <= upper:
                raise ParameterError(
                    f"nominal_angles.{name}",
                    angles[i],
                    f"must lie within stance_limits.{name} = [{lower:.6g}, {upper:.6g}] [rad]",
                )
        require_apart(
            "nominal footholds",
            self.leg_names,
            self.nominal_footholds[:, :2],
            2 * self.link_radius,
            "two link radii, so that their tibias do not overlap",
        )
        clearance = self.nominal_height - self.body_height / 2
        if not clearance > 0:
            raise ParameterError(
                "nominal_angles",
                angles,
                "the feet must stand below the body's underside (clearance "
                f"{clearance:.4g} m); lower the hip or bend the knee further down",
            )


DESIGN_FIELDS: tuple[FieldSpec, ...] = field_specs(HexapodDesign)
"""Every design field's declaration, in order: what validation, files, options and docs read."""

HexapodDesign.__doc__ = (
    cast(str, HexapodDesign.__doc__).rstrip() + "\n\n" + attributes_section(DESIGN_FIELDS)
)

FIELD_RANGES: dict[str, tuple[float, float, str]] = {
    spec.name: (*spec.bounds, spec.unit)
    for spec in DESIGN_FIELDS
    if spec.kind == "number" and spec.bounds is not None
}
"""Each number field's plausible range (lower, upper, unit); values outside are refused."""
