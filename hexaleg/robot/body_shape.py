"""The body the stance extremes stop at: a box read from a robot file's body geometry.

The stance analyses stop the body where its lowest point touches the ground: a box centred
on the design's body frame (the root link's axes, on the leg roots' mean plane). A robot
file's box is read from the collision geometry of its body's links (the root link and
every link fixed to it), in this order:

1. its collision boxes, cylinders, capsules and spheres (their corners and rims);
2. else its collision meshes' vertices (a box fitted to them, said so);
3. else none: a box spanning the leg roots, :data:`DEFAULT_HEIGHT` deep, said so.

The box is the smallest centred on the body frame that holds every point: half extents
max |x| and max |y| [m], and, as only its bottom can touch the ground, half height the
depth of the lowest point below the roots' plane (at least :data:`MIN_HALF`; its top is
then as high above the plane, which nothing touches).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.robot.description import Collision, RobotDescription
from hexaleg.robot.feet import FootSearch, mesh_vertices
from hexaleg.robot.packages import PackageFolders

__all__ = ["BodyBox", "body_box"]

MIN_HALF = 5e-3
"""Smallest half extent of a body box [m] (a body drawn flat, or only above the roots)."""

DEFAULT_HEIGHT = 0.05
"""Depth of the box spanning the leg roots when the file draws no body geometry [m]."""

RIM_POINTS = 16
"""Points on each rim of a cylinder or capsule the box must hold [-]."""


@dataclass(frozen=True, eq=False)
class BodyBox:
    """The body's box, centred on the design's body frame.

    Attributes:
        half_extents: Its half sizes along x, y, z (3,) [m].
        source: What it was read from, in words (for ``design show`` and the report).

    """

    half_extents: ArrayF
    source: str

    @property
    def size(self) -> tuple[float, float, float]:
        """Its full size (x, y, z) [m]."""
        x, y, z = (float(2 * h) for h in self.half_extents)
        return (x, y, z)

    def as_dict(self) -> dict[str, object]:
        """JSON-ready: ``size`` (x, y, z) [m] and what it was read ``from``."""
        return {"size": list(self.size), "from": self.source}


def body_box(
    description: RobotDescription,
    body: tuple[str, ...],
    plane: float,
    roots: ArrayF,
    base_dir: Path | None = None,
    packages: PackageFolders | None = None,
) -> BodyBox:
    """The body box of the links ``body`` of ``description`` (see the module docstring).

    Args:
        description: The robot file's tree.
        body: The body's links (the root link first).
        plane: The leg roots' mean height above the root link [m]: the body frame's.
        roots: The leg roots (N, 3) in the root link's frame [m], for a body drawn as none.
        base_dir: The robot file's folder (relative mesh paths).
        packages: Where ``package://`` meshes are.

    """
    frames = description.frames_at_zero()
    shapes = [(frames[link], c) for link in body for c in description.links[link].collisions]
    primitive = [(f, c) for f, c in shapes if c.shape != "mesh"]
    if primitive:
        points = np.vstack([_points(f, c) for f, c in primitive])
        names = sorted({c.shape for _, c in primitive})
        return _fitted(points, plane, f"the body's collision {', '.join(names)}")
    search = FootSearch(base_dir=base_dir, packages=packages or PackageFolders())
    meshes = [(f, c, mesh_vertices(c.filename or "", search)) for f, c in shapes]
    read = [_placed(f, c, v) for f, c, v in meshes if v is not None]
    if read:
        return _fitted(np.vstack(read), plane, "a box fitted to the body's collision meshes")
    span = np.abs(np.asarray(roots, dtype=float)[:, :2]).max(axis=0)
    half = np.array([max(span[0], MIN_HALF), max(span[1], MIN_HALF), DEFAULT_HEIGHT / 2])
    return BodyBox(half, "a box spanning the leg roots (the file gives the body no collision)")


def _fitted(points: ArrayF, plane: float, source: str) -> BodyBox:
    """The centred box holding ``points`` (M, 3) in the root link's frame [m]."""
    local = points - np.array([0.0, 0.0, plane])
    half = np.array(
        [
            max(float(np.abs(local[:, 0]).max()), MIN_HALF),
            max(float(np.abs(local[:, 1]).max()), MIN_HALF),
            max(float(-local[:, 2].min()), MIN_HALF),
        ]
    )
    return BodyBox(half, source)


def _placed(frame: ArrayF, shape: Collision, vertices: ArrayF) -> ArrayF:
    """A mesh's vertices (N, 3), scaled, in the root link's frame [m]."""
    placement = frame @ shape.origin
    points = vertices * np.asarray(shape.size)
    return points @ placement[:3, :3].T + placement[:3, 3]


def _points(frame: ArrayF, shape: Collision) -> ArrayF:
    """The points of a primitive shape a box must hold, in the root link's frame [m]."""
    placement = frame @ shape.origin
    local = _outline(shape)
    return local @ placement[:3, :3].T + placement[:3, 3]


def _outline(shape: Collision) -> ArrayF:
    """A primitive's extreme points in its own frame (box corners, rims, sphere poles)."""
    if shape.shape == "box":
        half = np.asarray(shape.size) / 2
        return np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
    if shape.shape == "sphere":
        (radius,) = shape.size
        return np.vstack([np.eye(3), -np.eye(3)]) * radius
    radius, length = shape.size
    turns = np.linspace(0.0, 2 * math.pi, RIM_POINTS, endpoint=False)
    rim = np.column_stack((radius * np.cos(turns), radius * np.sin(turns)))
    ends = (length / 2, -length / 2)
    points = [np.column_stack((rim, np.full(RIM_POINTS, z))) for z in ends]
    if shape.shape == "capsule":
        points.append(np.array([[0.0, 0.0, z + math.copysign(radius, z)] for z in ends]))
    return np.vstack(points)
