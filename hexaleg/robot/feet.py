"""Where a leg's foot is: the point, in the last link's frame, and the rule that found it.

The rules, first match wins:

1. ``foot_offset``: the caller's point (X, Y, Z) in the last link's frame;
2. ``frame``: the caller's foot link (a glob pattern matching one link of the leg's last
   segment), else the link fixed beyond the last joint farthest from the knee axis;
3. ``sphere``: the centre of the collision sphere farthest from the knee axis;
4. ``box`` / ``cylinder``: the far end of a collision box (the face centre along its
   longest side) or cylinder or capsule (its end along its axis), farthest from the knee;
5. ``mesh``: the collision mesh's vertex farthest from the knee axis (STL, OBJ, DAE via
   trimesh, at the file's scale: a mesh drawn in millimetres has scale 0.001; a file over
   :data:`~hexaleg.robot.source.MAX_MESH_BYTES` is refused by its size, never read).

Without any of them the leg is refused, naming the ``foot_offset`` option.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from fnmatch import fnmatchcase
from pathlib import Path
from typing import Literal

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.exceptions import RobotImportError
from hexaleg.robot.chains import LegChain
from hexaleg.robot.description import Collision, RobotDescription
from hexaleg.robot.packages import PackageFolders, missing_packages_note, resolve_resource
from hexaleg.robot.source import Packages, check_mesh_file

FootRule = Literal["foot_offset", "frame", "sphere", "box", "cylinder", "mesh"]
"""How a leg's foot point was found."""

_RULES: dict[str, FootRule] = {
    "sphere": "sphere",
    "box": "box",
    "cylinder": "cylinder",
    "capsule": "cylinder",
}

MIN_FOOT_DISTANCE = 1e-6
"""A foot link closer than this to the knee axis is no foot [m]."""


@dataclass(frozen=True)
class Foot:
    """A leg's foot point and how it was found.

    Attributes:
        rule: The rule that found it.
        source: What it was read from: the link, the shape and its link, the mesh file.
        point: The foot (3,) in the last link's frame (the knee joint's child) [m].

    """

    rule: FootRule
    source: str
    point: tuple[float, float, float]


@dataclass(frozen=True)
class FootSearch:
    """What the caller says about feet, and where meshes are.

    Attributes:
        offset: The foot (X, Y, Z) in each leg's last link's frame [m], or ``None``.
        frame: A glob pattern naming each leg's foot link, or ``None``.
        base_dir: The robot file's folder, for relative mesh paths.
        packages: Package folders, for ``package://`` mesh paths.

    """

    offset: tuple[float, float, float] | None = None
    frame: str | None = None
    base_dir: Path | None = None
    packages: Packages = field(default_factory=dict)


def find_foot(
    description: RobotDescription,
    chain: LegChain,
    frames: Mapping[str, ArrayF],
    search: FootSearch,
) -> Foot:
    """The foot of ``chain`` (``frames``: every link at q = 0, from the description)."""
    last = chain.segments[2][0]
    if search.offset is not None:
        return Foot("foot_offset", "foot_offset option", _triple(search.offset))
    inverse = np.linalg.inv(frames[last])
    local = {name: inverse @ frames[name] for name in chain.segments[2]}
    axis = chain.joints[2].axis
    if search.frame is not None:
        return _named_frame(chain, local, search.frame)
    found = _fixed_link(chain, local, axis)
    if found is None:
        shapes = [
            (name, c) for name in chain.segments[2] for c in description.links[name].collisions
        ]
        found = _primitive(shapes, local, axis)
        if found is None:
            found, missing = _mesh(shapes, local, axis, search)
            if found is None:
                raise RobotImportError(_no_foot(chain, missing, search))
    return found


def distance_from_axis(points: npt.ArrayLike, axis: ArrayF) -> ArrayF:
    """Distance [m] of points (..., 3) from the line through the origin along unit ``axis``."""
    p = np.asarray(points, dtype=float)
    return np.linalg.norm(p - (p @ axis)[..., None] * axis, axis=-1)


def _triple(point: Sequence[float] | ArrayF) -> tuple[float, float, float]:
    x, y, z = (float(v) for v in point)
    return (x, y, z)


def _named_frame(chain: LegChain, local: Mapping[str, ArrayF], pattern: str) -> Foot:
    matches = [name for name in chain.segments[2] if fnmatchcase(name, pattern)]
    if len(matches) != 1:
        found = ", ".join(matches) if matches else "none"
        raise RobotImportError(
            f"foot_frame {pattern!r} must match one link of the last segment of the leg from "
            f"joint {chain.joints[0].name} ({', '.join(chain.segments[2])}); it matches {found}"
        )
    return Foot("frame", f"link {matches[0]}", _triple(local[matches[0]][:3, 3]))


def _fixed_link(chain: LegChain, local: Mapping[str, ArrayF], axis: ArrayF) -> Foot | None:
    """The link fixed beyond the last joint farthest from the knee axis, if any is off it."""
    beyond = chain.segments[2][1:]
    if not beyond:
        return None
    points = np.array([local[name][:3, 3] for name in beyond])
    reach = distance_from_axis(points, axis)
    best = int(np.argmax(reach))
    if reach[best] < MIN_FOOT_DISTANCE:
        return None
    return Foot("frame", f"link {beyond[best]}", _triple(points[best]))


def _primitive(
    shapes: list[tuple[str, Collision]], local: Mapping[str, ArrayF], axis: ArrayF
) -> Foot | None:
    """A sphere's centre, else a box's or cylinder's far end, farthest from the knee axis."""
    for kinds in (("sphere",), ("box", "cylinder", "capsule")):
        candidates = []
        for link, shape in shapes:
            if shape.shape in kinds:
                placement = local[link] @ shape.origin
                for point in _shape_ends(shape):
                    candidates.append((placement[:3, :3] @ point + placement[:3, 3], link, shape))
        if candidates:
            reach = distance_from_axis(np.array([c[0] for c in candidates]), axis)
            point, link, shape = candidates[int(np.argmax(reach))]
            return Foot(_RULES[shape.shape], f"{shape.shape} on link {link}", _triple(point))
    return None


def _shape_ends(shape: Collision) -> list[ArrayF]:
    """The points a shape's foot may be, in the shape's own frame."""
    if shape.shape == "sphere":
        return [np.zeros(3)]
    if shape.shape == "box":
        half = np.asarray(shape.size) / 2
        longest = np.flatnonzero(half >= half.max() * (1 - 1e-12))
        return [sign * half[i] * np.eye(3)[i] for i in longest for sign in (1.0, -1.0)]
    radius, length = shape.size
    reach = length / 2 + (radius if shape.shape == "capsule" else 0.0)
    return [np.array([0.0, 0.0, reach]), np.array([0.0, 0.0, -reach])]


def _mesh(
    shapes: list[tuple[str, Collision]],
    local: Mapping[str, ArrayF],
    axis: ArrayF,
    search: FootSearch,
) -> tuple[Foot | None, list[str]]:
    """The mesh vertex farthest from the knee axis, and the meshes that could not be read."""
    best: tuple[float, ArrayF, str] | None = None
    missing = []
    for link, shape in shapes:
        if shape.shape != "mesh" or shape.filename is None:
            continue
        vertices = mesh_vertices(shape.filename, search)
        if vertices is None:
            missing.append(shape.filename)
            continue
        placement = local[link] @ shape.origin
        points = (vertices * np.asarray(shape.size)) @ placement[:3, :3].T + placement[:3, 3]
        reach = distance_from_axis(points, axis)
        i = int(np.argmax(reach))
        if best is None or reach[i] > best[0]:
            best = (float(reach[i]), points[i], f"mesh {shape.filename} on link {link}")
    if best is None:
        return None, missing
    return Foot("mesh", best[2], _triple(best[1])), missing


def mesh_vertices(reference: str, search: FootSearch) -> ArrayF | None:
    """A mesh file's vertices (N, 3) in its own units, or ``None`` if it cannot be read."""
    path = resolve_resource(reference, search.base_dir, search.packages)
    if path is None:
        return None
    check_mesh_file(path, reference)  # a mesh over the cap is refused, never read
    import trimesh

    try:
        mesh = trimesh.load(str(path), force="mesh")
        vertices: ArrayF = np.asarray(getattr(mesh, "vertices", ()), dtype=np.float64)
    except Exception:  # trimesh raises many kinds on a file it cannot read
        return None
    return vertices if vertices.ndim == 2 and len(vertices) else None


def _no_foot(chain: LegChain, missing: list[str], search: FootSearch) -> str:
    last = chain.segments[2][0]
    packages = PackageFolders.of(search.packages, search.base_dir).missing(missing)
    if packages:
        return (
            f"leg from joint {chain.joints[0].name}: no foot found on link {last}, whose "
            f"mesh {missing[0]} is not found: {missing_packages_note(packages)}; or give "
            f"foot_offset X Y Z (--foot-offset), the foot in {last}'s frame [m]"
        )
    unread = f"; its mesh {missing[0]} was not found or not readable" if missing else ""
    return (
        f"leg from joint {chain.joints[0].name}: no foot found on link {last} (no link fixed "
        f"beyond joint {chain.joints[2].name}, no collision sphere, box or cylinder{unread}); "
        f"give foot_offset X Y Z (--foot-offset), the foot in {last}'s frame [m]"
    )
