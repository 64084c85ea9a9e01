"""The numbers of a URDF: attribute text read into finite values within a robot's bounds.

Every number is read as C's parsers read it (urdfdom's, which Pinocchio uses): decimal,
finite, nothing Python alone accepts (``1_000``, other scripts' digits). Numbers beyond
:data:`MAX_LENGTH`, :data:`MAX_MASS`, :data:`MAX_INERTIA`, :data:`MAX_POSITION` and
:data:`MAX_RATING` are no robot's, and are refused in one line naming where they are, so
that no later product overflows.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.exceptions import RobotImportError

MAX_LENGTH = 1e4
"""Largest coordinate or size in a robot file [m]: a robot of 10 km is none."""

MAX_MASS = 1e6
"""Largest link mass [kg]: the design's own bound on a body's mass (``body_mass``)."""

MAX_INERTIA = MAX_MASS * MAX_LENGTH**2
"""Largest entry of a link's inertia [kg·m²]: the largest mass at the largest distance."""

MAX_POSITION = 1e16
"""Largest joint position limit [rad or m]: files write ±1e16 for "unbounded"."""

MAX_RATING = 1e9
"""Largest ``effort`` [N·m or N] or ``velocity`` [rad/s or m/s] of a joint."""

_DECIMAL = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")
"""A number as C's parsers read it (urdfdom's): no ``1_000``, no ``inf``, no other digits."""

Bound = tuple[float, str]
"""The largest magnitude a number of the file may have, and its unit."""

LENGTH: Bound = (MAX_LENGTH, "m")
"""The bound of a coordinate or size."""


def rpy_matrix(rpy: ArrayF) -> ArrayF:
    """Rotation (3, 3) of URDF roll-pitch-yaw angles: Rz(yaw) · Ry(pitch) · Rx(roll)."""
    (cr, cp, cy), (sr, sp, sy) = np.cos(rpy), np.sin(rpy)
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def numbers(
    text: str | None, count: int, where: str, default: float = 0.0, bound: Bound | None = None
) -> ArrayF:
    """``count`` numbers from an attribute's text (``default`` each if it is absent).

    ``bound``: the largest magnitude each may have and its unit, else only finite.
    """
    if text is None:
        return np.full(count, default)
    words = text.split()
    if not all(_DECIMAL.fullmatch(word) for word in words):
        raise RobotImportError(f"{where} = {text!r} is not {count} numbers")
    values = np.array([float(word) for word in words])
    if values.shape != (count,) or not np.all(np.isfinite(values)):
        raise RobotImportError(f"{where} = {text!r} is not {count} finite numbers")
    if bound is not None and np.abs(values).max() > bound[0]:
        each = "each within ±" if count > 1 else "at most "
        raise RobotImportError(f"{where} = {text!r} is not valid: {each}{bound[0]:g} [{bound[1]}]")
    return values


def number(
    element: ET.Element | None, attribute: str, where: str, bound: Bound | None = None
) -> float | None:
    """One number attribute of ``element``, ``None`` if the element or attribute is absent."""
    if element is None or element.get(attribute) is None:
        return None
    return float(numbers(element.get(attribute), 1, f"{where} {attribute}", bound=bound)[0])


def origin(element: ET.Element | None, where: str) -> ArrayF:
    """The 4×4 transform of an ``<origin xyz rpy>`` (identity if absent)."""
    matrix = np.eye(4)
    if element is not None:
        matrix[:3, 3] = numbers(element.get("xyz"), 3, f"{where} origin xyz", bound=LENGTH)
        matrix[:3, :3] = rpy_matrix(numbers(element.get("rpy"), 3, f"{where} origin rpy"))
    return matrix
