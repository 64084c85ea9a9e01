"""The general yaw–pitch–pitch leg: its dimensions, joint maps and link placements.

Every leg of three revolute joints — a yaw axis, then two parallel pitch axes
perpendicular to it — is, in its leg-root frame (origin on the yaw axis, z along it
pointing up, x along the common perpendicular from the yaw axis to the hip axis at
θ1 = 0, y = z × x, the pitch axes along y)::

    p(θ) = Rz(θ1) · [a1 + l2 cos θ2 + l3 cos(θ2+θ3),  e,  h + l2 sin θ2 + l3 sin(θ2+θ3)]

with the coxa a1 (the shortest distance between the yaw and hip axis lines), the hip
height h (of the hip axis above the root along the yaw axis), the femur l2 (between the
parallel hip and knee axes), the tibia l3 (from the knee axis to the foot, out of the
leg's pitch axes) and the lateral offset e (the foot's offset along the pitch axes).
Posture follows the paper: θ2 = 0 puts the femur (hip axis → knee axis) level and a
positive θ2 lifts it, θ3 = 0 puts the tibia (knee axis → foot) in line with it and the
knee bends down for θ3 < 0. The paper's leg is h = e = 0 (:func:`as_leg` of three lengths).

A robot file's joint values are ``q = s·θ + o`` (:class:`JointMap`, a sign and an offset
per joint): they absorb mirrored frames, bent segments and axes turned by rpy.

Each link's frame is a constant placement (:attr:`LegGeometry.link_placements`) in its
segment frame: the coxa's ``Rz(θ1)``, the femur's at the hip axis (x along the femur,
turning about −y by θ2), the tibia's at the knee axis (x along the tibia). Changing a
segment's length moves the joint or foot beyond it along that segment's line and keeps
every placement, offset and bend: :meth:`LegGeometry.with_lengths`. The closed forms of
the positions and Jacobians are in :mod:`hexaleg.kinematics`, those of the link frames
and gravity torques in :mod:`hexaleg.leg_frames`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, overload

import numpy as np
import numpy.typing as npt

from hexaleg._checks import require_in_range, require_numbers
from hexaleg._typing import ArrayF, Lengths
from hexaleg.exceptions import ParameterError

SEGMENT_NAMES: tuple[str, str, str] = ("coxa", "femur", "tibia")
"""The leg's moving segments, from the body out; each is the child link of one joint."""

LENGTH_LIMIT = 100.0
"""Largest length, height or offset of a leg [m]."""

Placement = tuple[tuple[float, float, float, float], ...]
"""A rigid transform as the three rows (rotation | translation) of its 4×4 matrix [m]."""

IDENTITY: Placement = ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0))
"""The identity placement: a link frame that is its segment frame (the paper's leg)."""


def placement(matrix: npt.ArrayLike) -> Placement:
    """A 4×4 (or 3×4) rigid transform as a :data:`Placement` of plain floats."""
    array = np.asarray(matrix, dtype=float)
    if array.shape not in ((4, 4), (3, 4)) or not np.all(np.isfinite(array)):
        raise ParameterError("placement", array.shape, "a finite 4×4 or 3×4 rigid transform")
    rows = array[:3]
    return tuple((float(r[0]), float(r[1]), float(r[2]), float(r[3])) for r in rows)


def placement_matrix(value: Placement) -> ArrayF:
    """The 4×4 matrix of a :data:`Placement`."""
    matrix = np.eye(4)
    matrix[:3] = np.asarray(value, dtype=float)
    return matrix


@dataclass(frozen=True)
class LegGeometry:
    """The dimensions of one yaw–pitch–pitch leg, in its leg-root frame.

    Attributes:
        coxa: a1, the shortest distance between the yaw and hip axis lines [m] (≥ 0).
        femur: l2, the distance between the parallel hip and knee axes [m] (> 0).
        tibia: l3, the knee axis to the foot, in the plane normal to the pitch axes [m] (> 0).
        hip_height: h, the hip axis' height above the leg root along the yaw axis [m].
        foot_lateral: e, the foot's offset along the pitch axes (along y) [m].
        link_placements: Each segment's link frame in its segment frame (coxa, femur,
            tibia): constant, and the identity for the paper's leg.

    """

    coxa: float
    femur: float
    tibia: float
    hip_height: float = 0.0
    foot_lateral: float = 0.0
    link_placements: tuple[Placement, Placement, Placement] = (IDENTITY, IDENTITY, IDENTITY)

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        set_(self, "coxa", require_in_range("coxa", self.coxa, 0.0, LENGTH_LIMIT, "m"))
        for name in ("femur", "tibia"):
            value = require_in_range(name, getattr(self, name), 0.0, LENGTH_LIMIT, "m")
            if value <= 0.0:
                raise ParameterError(name, value, f"must lie in (0, {LENGTH_LIMIT:g}] [m]")
            set_(self, name, value)
        for name in ("hip_height", "foot_lateral"):
            value = require_in_range(name, getattr(self, name), -LENGTH_LIMIT, LENGTH_LIMIT, "m")
            set_(self, name, value)
        given = self.link_placements
        given = list(given) if isinstance(given, np.ndarray) else given
        links = require_numbers("link_placements", given, SEGMENT_NAMES, "placements")
        set_(
            self,
            "link_placements",
            tuple(_rigid(n, p) for n, p in zip(SEGMENT_NAMES, links, strict=True)),
        )

    @classmethod
    def from_lengths(cls, lengths: Lengths) -> LegGeometry:
        """The paper's leg of segment lengths (l1, l2, l3) [m]: h = e = 0."""
        l1, l2, l3 = require_numbers("lengths", lengths, ("l1", "l2", "l3"), "lengths [m]")
        return cls(l1, l2, l3)

    @property
    def lengths(self) -> Lengths:
        """(a1, l2, l3) [m]: the coxa, femur and tibia."""
        return (self.coxa, self.femur, self.tibia)

    @property
    def leg_length(self) -> float:
        """a1 + l2 + l3 [m], the paper's L."""
        return self.coxa + self.femur + self.tibia

    @property
    def is_planar(self) -> bool:
        """Whether this is the paper's leg shape: no hip height, no lateral offset."""
        return self.hip_height == 0.0 and self.foot_lateral == 0.0

    def with_lengths(
        self, coxa: float | None = None, femur: float | None = None, tibia: float | None = None
    ) -> LegGeometry:
        """The same leg with segments lengthened or shortened along their own lines [m].

        Offsets (h, e), bends (the joint maps' offsets) and link placements are kept: the
        joint or foot beyond a changed segment moves along that segment.
        """
        return replace(
            self,
            coxa=self.coxa if coxa is None else coxa,
            femur=self.femur if femur is None else femur,
            tibia=self.tibia if tibia is None else tibia,
        )

    def link_placement(self, segment: int) -> ArrayF:
        """4×4 placement of segment ``segment``'s link frame (0 coxa, 1 femur, 2 tibia)."""
        return placement_matrix(self.link_placements[segment])

    def segment_directions(self) -> ArrayF:
        """Each segment's line (3, 3), a unit vector in its own link's frame.

        The coxa's runs along the common perpendicular (yaw axis → hip axis), the femur's
        from the hip axis to the knee axis, the tibia's from the knee axis toward the foot:
        the direction :meth:`with_lengths` moves along, as a robot file would draw it.
        """
        return np.array([self.link_placement(i)[:3, :3].T[:, 0] for i in range(3)])

    def as_dict(self) -> dict[str, Any]:
        """The dimensions as JSON-ready values [m]."""
        return {
            "coxa": self.coxa,
            "femur": self.femur,
            "tibia": self.tibia,
            "hip_height": self.hip_height,
            "foot_lateral": self.foot_lateral,
        }


LegLike = LegGeometry | Lengths
"""A leg: a :class:`LegGeometry`, or the paper's leg by its three lengths (l1, l2, l3) [m]."""


def as_leg(leg: LegLike) -> LegGeometry:
    """``leg`` as a :class:`LegGeometry` (three lengths make the paper's leg)."""
    return leg if isinstance(leg, LegGeometry) else LegGeometry.from_lengths(leg)


LegRows = npt.NDArray[np.float64]
"""Several legs side by side: one row (a1, l2, l3, h, e) [m] per leg (..., 5).

Given to the closed forms of :mod:`hexaleg.kinematics` in place of one leg, each column
broadcasts over the angles' leg axis (the one before the last): six different legs at once.
"""

Dimension = float | npt.NDArray[np.float64]
"""One dimension of a leg [m], or of each of several legs side by side (:data:`LegRows`)."""


@overload
def leg_parameters(leg: LegLike) -> tuple[float, float, float, float, float]: ...


@overload
def leg_parameters(
    leg: LegRows,
) -> tuple[LegRows, LegRows, LegRows, LegRows, LegRows]: ...


def leg_parameters(
    leg: LegLike | LegRows,
) -> tuple[Dimension, Dimension, Dimension, Dimension, Dimension]:
    """(a1, l2, l3, h, e) [m] of a leg, without validating three plain lengths again.

    Of several legs (:data:`LegRows`), the five columns, each (...,) one value per leg.
    """
    if isinstance(leg, LegGeometry):
        return (leg.coxa, leg.femur, leg.tibia, leg.hip_height, leg.foot_lateral)
    if isinstance(leg, np.ndarray):
        return (leg[..., 0], leg[..., 1], leg[..., 2], leg[..., 3], leg[..., 4])
    l1, l2, l3 = leg
    return (l1, l2, l3, 0.0, 0.0)


@dataclass(frozen=True)
class JointMap:
    """A robot file's joint values q from hexaleg's angles θ: ``q = s·θ + o``, per joint.

    Attributes:
        signs: s, +1 or −1 per joint (root, hip, knee).
        offsets: o, the file's value at θ = 0, per joint [rad], in (−π, π].

    """

    signs: tuple[int, int, int] = (1, 1, 1)
    offsets: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        signs = require_numbers("signs", self.signs, SEGMENT_NAMES, "signs (+1 or -1)")
        if any(s not in (1, -1) or isinstance(s, bool) for s in signs):
            raise ParameterError("signs", self.signs, "each +1 or -1")
        offsets = require_numbers("offsets", self.offsets, SEGMENT_NAMES, "angles [rad]")
        checked = tuple(
            require_in_range(f"offsets.{n}", o, -math.pi, math.pi, "rad")
            for n, o in zip(SEGMENT_NAMES, offsets, strict=True)
        )
        object.__setattr__(self, "signs", tuple(int(s) for s in signs))
        object.__setattr__(self, "offsets", checked)

    @property
    def sign_array(self) -> ArrayF:
        """The signs s as a float array (3,)."""
        return np.asarray(self.signs, dtype=float)

    def to_file(self, theta: npt.ArrayLike) -> ArrayF:
        """The file's joint values q (..., 3) [rad] at hexaleg's angles θ (..., 3) [rad]."""
        return self.sign_array * np.asarray(theta, dtype=float) + np.asarray(self.offsets)

    def from_file(self, q: npt.ArrayLike) -> ArrayF:
        """Hexaleg's angles θ (..., 3) [rad] at the file's joint values q (..., 3) [rad]."""
        return self.sign_array * (np.asarray(q, dtype=float) - np.asarray(self.offsets))

    def theta_bounds(self, lower: npt.ArrayLike, upper: npt.ArrayLike) -> tuple[ArrayF, ArrayF]:
        """The file's joint limits [lower, upper] (3,) [rad] as limits on θ [rad].

        A negative sign swaps the ends; infinite limits (continuous joints) stay infinite.
        """
        a = self.from_file(lower)
        b = self.from_file(upper)
        return np.minimum(a, b), np.maximum(a, b)

    def torques_to_file(self, torque: npt.ArrayLike) -> ArrayF:
        """Joint torques about the file's axes (..., 3) [N·m] from torques on θ [N·m]."""
        return self.sign_array * np.asarray(torque, dtype=float)


def _rigid(name: str, value: Any) -> Placement:
    """``value`` as a :data:`Placement` whose rotation is orthonormal and right-handed."""
    if value is IDENTITY:  # the paper's leg, made for every sample of a sweep: nothing to check
        return IDENTITY
    try:
        checked = placement(value)
    except (ParameterError, TypeError, ValueError):
        raise ParameterError(f"link_placements.{name}", value, "a 3×4 rigid transform") from None
    rotation = np.asarray(checked)[:, :3]
    if not np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-9) or np.linalg.det(rotation) < 0:
        raise ParameterError(
            f"link_placements.{name}", value, "its rotation must be orthonormal, det +1"
        )
    return checked
