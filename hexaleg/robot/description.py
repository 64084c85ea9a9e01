"""A robot file's URDF as a tree of links and joints, read once and checked.

:func:`parse_urdf` turns URDF text into a :class:`RobotDescription`: every link (its
inertial in its own frame, its collision shapes) and every joint (type, parent, child,
origin, unit axis, limits), the root link and each link's child joints. A file that is
not a URDF tree — not XML, no ``<robot>``, a joint naming a missing link, two roots, a
loop, a number that is not one — is refused in one line naming what was found.

What Pinocchio's URDF parser (urdfdom) and model refuse is refused here first, naming the
joint and attribute: a ``<limit>`` without ``effort`` or ``velocity`` (the URDF
specification requires both in every ``<limit>``, ROS wiki ``urdf/XML/joint``; urdfdom's
``parseJointLimits`` fails without them, whatever the joint's type), a negative effort or
velocity (Pinocchio: "min_effort greater than max_effort"), a tree deeper than
:data:`MAX_TREE_DEPTH` (urdfdom and Pinocchio recurse once a link: a 4 000-deep chain
overflows an 8 MiB stack). Numbers beyond a robot's bounds are refused
(:mod:`~hexaleg.robot.urdf_numbers`). XML's own internal entities (``<!DOCTYPE robot
[<!ENTITY ...>]>``) are XML: :func:`plain_urdf` expands them for the parsers that do not
(urdfdom's TinyXML).
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from types import MappingProxyType
from typing import Literal

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.exceptions import RobotImportError
from hexaleg.robot.urdf_numbers import (
    LENGTH,
    MAX_INERTIA,
    MAX_LENGTH,
    MAX_MASS,
    MAX_POSITION,
    MAX_RATING,
    number,
    numbers,
    origin,
)

MOVABLE = ("revolute", "continuous", "prismatic", "floating", "planar")
"""URDF joint types that move; ``fixed`` is the only other one."""

JOINT_TYPES = ("fixed", *MOVABLE)

MAX_TREE_DEPTH = 1000
"""Most joints between the root link and any link [-]: Pinocchio builds a 1 000-deep chain
on an 8 MiB stack (tested), and crashed (SIGSEGV) on 4 000; a hexapod is about 10 deep."""

Shape = Literal["sphere", "box", "cylinder", "capsule", "mesh"]


@dataclass(frozen=True, eq=False)
class Inertial:
    """A link's mass and inertia, in its own link frame.

    Attributes:
        mass: Mass [kg].
        com: Centre of mass (3,) in the link frame [m].
        inertia: Rotational inertia (3, 3) about the centre of mass, link axes [kg·m²].

    """

    mass: float
    com: ArrayF
    inertia: ArrayF


@dataclass(frozen=True, eq=False)
class Collision:
    """One collision shape of a link.

    Attributes:
        origin: The shape's placement (4, 4) in the link frame [m].
        shape: Its kind.
        size: Sphere (radius,), box (x, y, z), cylinder and capsule (radius, length),
            mesh the scale (sx, sy, sz) [m or -].
        filename: A mesh's file reference as written (``package://``, relative, ...).

    """

    origin: ArrayF
    shape: Shape
    size: tuple[float, ...]
    filename: str | None = None


@dataclass(frozen=True, eq=False)
class Link:
    """A link: its name, inertial (``None`` if the file gives none) and collision shapes."""

    name: str
    inertial: Inertial | None
    collisions: tuple[Collision, ...]


@dataclass(frozen=True, eq=False)
class Joint:
    """A joint as the file writes it.

    Attributes:
        name: Its name.
        kind: Its URDF type (``revolute``, ``continuous``, ``fixed``, ...).
        parent: Parent link's name.
        child: Child link's name.
        origin: The child frame (4, 4) in the parent frame at q = 0 [m].
        axis: Unit axis (3,) in the joint (child) frame.
        lower: Lower position limit [rad or m]; −inf if unbounded.
        upper: Upper position limit [rad or m]; +inf if unbounded.
        effort: Effort limit [N·m or N]; ``None`` if not given.
        velocity: Velocity limit [rad/s or m/s]; ``None`` if not given.

    """

    name: str
    kind: str
    parent: str
    child: str
    origin: ArrayF
    axis: ArrayF
    lower: float
    upper: float
    effort: float | None
    velocity: float | None

    @property
    def movable(self) -> bool:
        """Whether the joint moves (any type but ``fixed``)."""
        return self.kind != "fixed"


@dataclass(frozen=True, eq=False)
class RobotDescription:
    """A URDF's tree: links, joints, root link and each link's child joints."""

    name: str
    links: MappingProxyType[str, Link]
    joints: MappingProxyType[str, Joint]
    root: str
    children: MappingProxyType[str, tuple[Joint, ...]]

    def frames_at_zero(self) -> dict[str, ArrayF]:
        """Every link's frame (4, 4) in the root link's frame with every joint at q = 0 [m]."""
        frames = {self.root: np.eye(4)}
        stack = [self.root]
        while stack:
            link = stack.pop()
            for joint in self.children[link]:
                frames[joint.child] = frames[link] @ joint.origin
                stack.append(joint.child)
        return frames


def parse_urdf(text: str, source: str = "<string>") -> RobotDescription:
    """The tree of URDF ``text``; a :class:`RobotImportError` naming what is wrong if none."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as err:
        raise RobotImportError(f"{source} is not XML: {err}") from None
    if root.tag != "robot":
        raise RobotImportError(f"{source} is not a URDF: its root element is <{root.tag}>")
    links = {}
    for element in root.findall("link"):
        link = _link(element)
        if link.name in links:
            raise RobotImportError(f"{source}: link {link.name!r} is defined twice")
        links[link.name] = link
    joints = {}
    for element in root.findall("joint"):
        joint = _joint(element)
        if joint.name in joints:
            raise RobotImportError(f"{source}: joint {joint.name!r} is defined twice")
        joints[joint.name] = joint
    if not links:
        raise RobotImportError(f"{source}: the URDF has no links")
    description = RobotDescription(
        name=root.get("name", ""),
        links=MappingProxyType(links),
        joints=MappingProxyType(joints),
        root=_root_link(links, joints, source),
        children=MappingProxyType(_children(links, joints)),
    )
    _check_depth(description, source)
    unreached = sorted(set(links) - set(description.frames_at_zero()))
    if unreached:
        raise RobotImportError(
            f"{source}: links {', '.join(unreached[:4])} are not connected to the root (a loop)"
        )
    return description


def plain_urdf(text: str, source: str = "<string>") -> str:
    """URDF ``text`` without its document type: XML's internal entities expanded.

    Text without a ``<!DOCTYPE`` is returned as it is; otherwise it is parsed (comments
    kept) and written again, every ``&name;`` replaced by its value. An external entity
    is not read: its use is refused as undefined.
    """
    if "<!DOCTYPE" not in text:
        return text
    parser = ET.XMLParser(target=ET.TreeBuilder(insert_comments=True))
    try:
        root = ET.fromstring(text, parser=parser)
    except ET.ParseError as err:
        raise RobotImportError(f"{source} is not XML: {err}") from None
    return ET.tostring(root, encoding="unicode") + "\n"


def _check_depth(description: RobotDescription, source: str) -> None:
    """Refuse a tree with a link more than :data:`MAX_TREE_DEPTH` joints below the root."""
    stack = [(description.root, 0)]
    while stack:
        link, depth = stack.pop()
        if depth > MAX_TREE_DEPTH:
            raise RobotImportError(
                f"{source}: link {link} lies {depth} joints below the root link "
                f"{description.root}; hexaleg reads trees at most {MAX_TREE_DEPTH} joints deep "
                "(MAX_TREE_DEPTH)"
            )
        stack.extend((joint.child, depth + 1) for joint in description.children.get(link, ()))


def _named(element: ET.Element, what: str) -> str:
    name = element.get("name")
    if not name:
        raise RobotImportError(f"a <{what}> has no name")
    return name


def _link(element: ET.Element) -> Link:
    name = _named(element, "link")
    inertial = None
    node = element.find("inertial")
    if node is not None:
        inertial = _inertial(node, f"link {name!r} inertial")
    collisions = tuple(
        c
        for c in (_collision(n, f"link {name!r} collision") for n in element.findall("collision"))
        if c is not None
    )
    return Link(name, inertial, collisions)


def _inertial(node: ET.Element, where: str) -> Inertial:
    placement = origin(node.find("origin"), where)
    mass_node, tensor = node.find("mass"), node.find("inertia")
    names = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    if mass_node is None or mass_node.get("value") is None:
        raise RobotImportError(f"{where} has no <mass value=...>: URDF requires it in <inertial>")
    if tensor is None or any(tensor.get(n) is None for n in names):
        raise RobotImportError(
            f"{where} has no <inertia> with all of {', '.join(names)}: URDF requires it"
        )
    mass = number(mass_node, "value", f"{where} mass") or 0.0
    if mass < 0:
        raise RobotImportError(f"{where} mass = {mass:g} is negative")
    if mass > MAX_MASS:
        raise RobotImportError(f"{where} mass = {mass:g} is not valid: at most {MAX_MASS:g} [kg]")
    bound = (MAX_INERTIA, "kg·m²")
    values = [(number(tensor, n, f"{where} inertia", bound) or 0.0) for n in names]
    ixx, ixy, ixz, iyy, iyz, izz = values
    local = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
    rotation = placement[:3, :3]
    return Inertial(mass, placement[:3, 3].copy(), rotation @ local @ rotation.T)


def _collision(node: ET.Element, where: str) -> Collision | None:
    placement = origin(node.find("origin"), where)
    geometry = node.find("geometry")
    shape = None if geometry is None or len(geometry) == 0 else geometry[0]
    if shape is None:
        return None
    if shape.tag == "sphere":
        return Collision(placement, "sphere", (_required(shape, "radius", where),))
    if shape.tag == "box":
        box = numbers(shape.get("size"), 3, f"{where} box size", bound=LENGTH)
        return Collision(placement, "box", tuple(float(v) for v in box))
    if shape.tag in ("cylinder", "capsule"):
        size = (_required(shape, "radius", where), _required(shape, "length", where))
        return Collision(placement, "cylinder" if shape.tag == "cylinder" else "capsule", size)
    if shape.tag == "mesh":
        filename = shape.get("filename")
        if not filename:
            raise RobotImportError(f"{where}: a mesh has no filename")
        scale = numbers(shape.get("scale"), 3, f"{where} mesh scale", 1.0, (MAX_LENGTH, "-"))
        return Collision(placement, "mesh", tuple(scale), filename)
    return None  # shapes hexaleg does not read (a foot is looked for on the others)


def _required(element: ET.Element, attribute: str, where: str) -> float:
    value = number(element, attribute, f"{where} {element.tag}", LENGTH)
    if value is None:
        raise RobotImportError(f"{where}: the {element.tag} has no {attribute}")
    return value


def _joint(element: ET.Element) -> Joint:
    name = _named(element, "joint")
    where = f"joint {name!r}"
    kind = element.get("type", "")
    if kind not in JOINT_TYPES:
        raise RobotImportError(
            f"{where} has type {kind!r}; URDF types are {', '.join(JOINT_TYPES)}"
        )
    parent, child = element.find("parent"), element.find("child")
    if parent is None or not parent.get("link") or child is None or not child.get("link"):
        raise RobotImportError(f"{where} lacks a parent or child link")
    axis_node = element.find("axis")
    xyz = None if axis_node is None else axis_node.get("xyz")
    axis = numbers(xyz, 3, f"{where} axis", bound=(MAX_LENGTH, "-"))
    if axis_node is None or axis_node.get("xyz") is None:
        axis = np.array([1.0, 0.0, 0.0])  # the URDF default
    norm = float(np.linalg.norm(axis))
    if kind != "fixed" and norm == 0.0:
        raise RobotImportError(f"{where} has a zero axis")
    low, high, effort, velocity = _limits(element.find("limit"), kind, where)
    return Joint(  # lower > upper: no limits given on a leg's joint, refused on another
        name=name,
        kind=kind,
        parent=str(parent.get("link")),
        child=str(child.get("link")),
        origin=origin(element.find("origin"), where),
        axis=axis / norm if norm > 0 else axis,
        lower=low,
        upper=high,
        effort=effort,
        velocity=velocity,
    )


RATINGS = {"effort": "N·m or N", "velocity": "rad/s or m/s"}
"""A ``<limit>``'s two ratings and their units (revolute or prismatic joint)."""


def _limits(
    limit: ET.Element | None, kind: str, where: str
) -> tuple[float, float, float | None, float | None]:
    """A joint's position limits [rad or m] (±inf if unbounded) and its two ratings.

    A ``<limit>`` must give ``effort`` and ``velocity`` (the URDF specification; urdfdom
    refuses it otherwise, whatever the joint's type), neither negative.
    """
    bounded = kind in ("revolute", "prismatic")
    if bounded and limit is None:
        raise RobotImportError(f"{where} is {kind} but has no <limit>")
    ratings: list[float | None] = []
    for attribute, unit in RATINGS.items():
        value = number(limit, attribute, f"{where} <limit>", (MAX_RATING, unit))
        if limit is not None and value is None:
            raise RobotImportError(
                f"{where} has a <limit> without {attribute}: URDF requires effort and velocity "
                f"in every <limit> (its rated torque [N·m] and speed [rad/s])"
            )
        if value is not None and value < 0:
            raise RobotImportError(
                f"{where} <limit> {attribute} = {value:g} is negative: a rating is at least 0 "
                f"[{unit}]"
            )
        ratings.append(value)
    position = (MAX_POSITION, "rad or m")
    lower = number(limit, "lower", where, position)
    upper = number(limit, "upper", where, position)
    low = (lower or 0.0) if bounded else -math.inf
    high = (upper or 0.0) if bounded else math.inf
    return low, high, ratings[0], ratings[1]


def _root_link(links: dict[str, Link], joints: dict[str, Joint], source: str) -> str:
    """The one link that is no joint's child; refuse dangling names, two parents, loops."""
    parents: dict[str, str] = {}
    for joint in joints.values():
        for end in (joint.parent, joint.child):
            if end not in links:
                raise RobotImportError(f"{source}: joint {joint.name!r} names no link {end!r}")
        if joint.child in parents:
            raise RobotImportError(
                f"{source}: link {joint.child!r} is the child of joints "
                f"{parents[joint.child]!r} and {joint.name!r}"
            )
        parents[joint.child] = joint.name
    roots = sorted(set(links) - set(parents))
    if len(roots) != 1:
        listed = ", ".join(roots[:4]) + (", ..." if len(roots) > 4 else "")
        found = f"{len(roots)} root links ({listed})" if roots else "no root link (a loop)"
        raise RobotImportError(f"{source}: found {found}; a URDF is one tree")
    return roots[0]


def _children(links: dict[str, Link], joints: dict[str, Joint]) -> dict[str, tuple[Joint, ...]]:
    children: dict[str, list[Joint]] = {name: [] for name in links}
    for joint in joints.values():
        children[joint.parent].append(joint)
    return {name: tuple(kids) for name, kids in children.items()}
