"""Where the six legs sit on the body: leg mounts and the body layouts that place them.

A layout turns a few body fields into six :class:`LegMount` (leg-root position and
coxa direction in the body frame, x forward, y left, z up):

- ``"rectangle"``: legs at the four corners and the two side mid-points of a
  ``body_length`` × ``body_width`` box's mid-plane (the paper's robot); the middle legs
  may sit ``middle_leg_offset`` further out and the front/rear legs point at
  ``front_yaw``/``rear_yaw`` (left side; the right side mirrors them);
- ``"hexagon"``: legs every 60° at ``body_radius`` from the centre, the first at
  ``first_leg_angle`` from straight ahead, each pointing radially; the body is a
  cylinder of that radius;
- ``"custom"``: the six mounts given one by one.

Legs are named ``lf lm lr rf rm rr`` (left/right, front/middle/rear) in every layout
but ``"custom"``, so the tripods (lf, rm, lr) and (rf, lm, rr) alternate around the body.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal, cast

import numpy as np
import numpy.typing as npt

from hexaleg._checks import require_in_range
from hexaleg._typing import choices, require_choice
from hexaleg.exceptions import ParameterError

Layout = Literal["rectangle", "hexagon", "custom"]
"""How the legs are placed on the body."""

LAYOUTS: tuple[str, ...] = choices(Layout)

LEG_NAMES: tuple[str, ...] = ("lf", "lm", "lr", "rf", "rm", "rr")
"""Leg names of the built-in layouts: left/right × front/middle/rear."""

TRIPODS: tuple[tuple[str, str, str], tuple[str, str, str]] = (
    ("lf", "rm", "lr"),
    ("rf", "lm", "rr"),
)
"""The two alternating tripods of the built-in layouts' leg names."""

LEGS_AROUND: tuple[str, ...] = ("lf", "lm", "lr", "rr", "rm", "rf")
"""The built-in layouts' legs counter-clockwise around the body from straight ahead."""

MOUNT_RANGE = 100.0
"""Largest leg-root offset from the body centre along any axis [m]."""

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
            raise ParameterError(
                "mount.name", self.name, "a lower-case identifier like 'lf' (letters, digits, _)"
            )
        for name in ("x", "y", "z", "yaw"):
            value = getattr(self, name)
            field = f"mounts[{self.name}].{name}"
            limit = math.pi if name == "yaw" else MOUNT_RANGE
            unit = "rad" if name == "yaw" else "m"
            object.__setattr__(self, name, require_in_range(field, value, -limit, limit, unit))

    @property
    def position(self) -> npt.NDArray[np.float64]:
        """Root position in the body frame [m]."""
        return np.array([self.x, self.y, self.z])


def rectangle_mounts(
    body_length: float,
    body_width: float,
    middle_leg_offset: float = 0.0,
    front_yaw: float = math.pi / 4,
    rear_yaw: float = 3 * math.pi / 4,
) -> tuple[LegMount, ...]:
    """Legs at the corners and side mid-points of a rectangular body's mid-plane.

    Args:
        body_length: Body extent along x [m].
        body_width: Body extent along y [m].
        middle_leg_offset: How much further out than the body's side the middle legs sit [m].
        front_yaw: Direction of the left front coxa (the right one mirrors it) [rad].
        rear_yaw: Direction of the left rear coxa (the right one mirrors it) [rad].

    """
    hx, hy = body_length / 2, body_width / 2
    wide = hy + middle_leg_offset
    return (
        LegMount("lf", hx, hy, 0.0, front_yaw),
        LegMount("lm", 0.0, wide, 0.0, math.pi / 2),
        LegMount("lr", -hx, hy, 0.0, rear_yaw),
        LegMount("rf", hx, -hy, 0.0, -front_yaw),
        LegMount("rm", 0.0, -wide, 0.0, -math.pi / 2),
        LegMount("rr", -hx, -hy, 0.0, -rear_yaw),
    )


def default_mounts(body_length: float, body_width: float) -> tuple[LegMount, ...]:
    """The paper's rectangle: legs at the corners and side mid-points, pointing outward.

    Args:
        body_length: Body extent along x [m].
        body_width: Body extent along y [m].

    """
    return rectangle_mounts(body_length, body_width)


def hexagon_mounts(
    body_radius: float, first_leg_angle: float = math.pi / 6
) -> tuple[LegMount, ...]:
    """Legs every 60° at ``body_radius`` from the body centre, each pointing radially.

    Counter-clockwise from ``first_leg_angle`` (measured from straight ahead) the legs
    are lf, lm, lr, rr, rm, rf; they are returned in the order lf, lm, lr, rf, rm, rr.

    Args:
        body_radius: Distance of every leg root from the body's vertical axis [m].
        first_leg_angle: Direction of the left front leg from the x axis [rad].

    """
    mounts = {}
    for k, name in enumerate(LEGS_AROUND):
        angle = first_leg_angle + k * math.pi / 3
        yaw = math.atan2(math.sin(angle), math.cos(angle))
        x, y = (_clean(body_radius * f(angle), body_radius) for f in (math.cos, math.sin))
        mounts[name] = LegMount(name, x, y, 0.0, yaw)
    return tuple(mounts[name] for name in LEG_NAMES)


def _clean(value: float, scale: float) -> float:
    """``value`` with rounding noise (cos 90° = 6e-17) set to an exact zero."""
    return 0.0 if abs(value) < 1e-12 * scale else value


def legs_around(mounts: tuple[LegMount, ...]) -> tuple[str, ...]:
    """The legs counter-clockwise around the body, from straight ahead.

    The built-in names give :data:`LEGS_AROUND`; custom legs are sorted by their root's
    direction from the body centre.
    """
    if {m.name for m in mounts} == set(LEG_NAMES):
        return LEGS_AROUND
    return tuple(m.name for m in sorted(mounts, key=lambda m: math.atan2(m.y, m.x) % (2 * math.pi)))


def first_tripod(mounts: tuple[LegMount, ...]) -> tuple[str, ...]:
    """The tripod (every other leg around the body) that holds the first leg.

    The built-in layouts' names give :data:`TRIPODS` ``[0]``; custom legs are every other
    one of :func:`legs_around`.
    """
    if {m.name for m in mounts} == set(LEG_NAMES):
        return TRIPODS[0]
    return legs_around(mounts)[0::2]


def same_mounts(a: tuple[LegMount, ...], b: tuple[LegMount, ...], tol: float = 1e-9) -> bool:
    """Whether two mount sets have the same names, in order, at the same places (± tol)."""
    if [m.name for m in a] != [m.name for m in b]:
        return False
    return all(
        abs(getattr(m, f) - getattr(n, f)) <= tol
        for m, n in zip(a, b, strict=True)
        for f in ("x", "y", "z", "yaw")
    )


def require_apart(
    what: str, names: tuple[str, ...], points: npt.ArrayLike, distance: float, unit_note: str
) -> None:
    """Refuse two of ``points`` (N, 2) closer than ``distance`` [m], naming the legs."""
    points = np.asarray(points, dtype=float)
    gaps = np.hypot(*(points[:, None, :] - points[None, :, :]).transpose(2, 0, 1))
    gaps[np.diag_indices(len(points))] = np.inf
    if gaps.min() >= distance:
        return
    i, j = sorted(np.unravel_index(int(np.argmin(gaps)), gaps.shape))
    raise ParameterError(
        what,
        f"{names[i]} and {names[j]} {gaps[i, j]:.4g} m apart",
        f"legs must be at least {distance:.4g} m apart ({unit_note})",
    )


def resolve_layout(layout: Any, mounts: Any) -> Layout:
    """The layout a design names; ``None`` means custom with mounts, else the rectangle."""
    if layout is None:
        return "rectangle" if mounts is None else "custom"
    return cast(Layout, require_choice("layout", layout, Layout))


def checked_mounts(
    layout: Layout, mounts: Any, placed: tuple[LegMount, ...] | None, link_radius: float
) -> tuple[LegMount, ...]:
    """The six mounts of a design, checked: those given, or those its layout placed.

    Args:
        layout: The design's layout.
        mounts: The mounts given (``None``: placed by the layout).
        placed: The mounts the layout places; ``None`` for a custom layout.
        link_radius: Radius of the links [m]: two leg roots must be two radii apart.

    """
    if mounts is None:
        if placed is None:
            raise ParameterError("mounts", None, 'layout "custom" needs the six mounts')
        mounts = placed
    if not isinstance(mounts, Sequence) or not all(isinstance(m, LegMount) for m in mounts):
        raise ParameterError("mounts", mounts, "a sequence of six LegMount")
    mounts = tuple(mounts)
    if placed is not None and not same_mounts(mounts, placed):
        raise ParameterError(
            "mounts",
            "given",
            f"the {layout} layout places the legs itself: drop the mounts, or set "
            'layout = "custom" to place them by hand',
        )
    if len(mounts) != 6:
        raise ParameterError("mounts", len(mounts), "exactly 6 legs (a hexapod)")
    names = [m.name for m in mounts]
    if len(set(names)) != len(names):
        raise ParameterError("mounts", names, "leg names must be unique")
    heights = {m.z for m in mounts}
    if len(heights) != 1:
        raise ParameterError(
            "mounts[*].z",
            sorted(heights),
            "every leg root at the same height, so that all feet reach level ground [m]",
        )
    spacing = "two link radii, so that their coxas do not overlap"
    require_apart("mounts", tuple(names), [(m.x, m.y) for m in mounts], 2 * link_radius, spacing)
    return mounts
