"""An imported robot with segments lengthened or shortened along their own lines ("what if").

:func:`resize_robot` changes a leg's coxa, femur or tibia (the lengths of
:class:`~hexaleg.leg_geometry.LegGeometry`: the yaw → hip axis distance, the hip → knee
axis distance, the knee axis → foot distance) by rewriting the robot's URDF and reading
the result again, so that every analysis sees a robot file like any other.

The rule, for a segment of length L changed to L' (k = L'/L), with K its segment frame
(:func:`~hexaleg.leg_frames.segment_frames` at the file's zero: origin on the joint's
axis, x along the segment):

- the segment is stretched along x by k: a point at (x, y, z) in K goes to (k·x, y, z).
  The next joint's axis (or the foot) lies at x = L, so it moves along the segment by
  L' − L, and everything beyond — the next joint's origin, every child link, the foot —
  moves with it; the offsets (hip height, lateral offset) and bends (joint zeros, link
  placements) stay as the file draws them;
- every link of the segment (the joint's child and each link fixed to it) is stretched
  with it, keeping its density and cross-section: mass × k, its centre of mass moved
  along the segment in proportion (x × k, measured from the joint's axis), and its second
  moments about the centre of mass Σ = ∫ r rᵀ dm turned into k · S Σ S with
  S = 1 + (k − 1)·d dᵀ (d the segment's direction): along the segment × k³, across × k
  (a uniform rod's m L²/12 becomes m' L'²/12);
- the segment's meshes (visual and collision, on every link of it) no longer fit: they
  are replaced by one cylinder along the segment (radius :data:`CYLINDER_RADIUS` of its
  length), ending at the next joint's origin or the foot, and an XML comment says so.

A change smaller than :data:`SAME_LENGTH` is no change: the robot comes back as read.
A segment of length 0 (a hip axis that meets the yaw axis) has nothing to stretch and is
refused.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable, Mapping
from dataclasses import replace

import numpy as np
import pinocchio as pin

from hexaleg._checks import require_in_range
from hexaleg._typing import ArrayF
from hexaleg.design import SEGMENT_RANGE
from hexaleg.exceptions import ParameterError
from hexaleg.leg_geometry import SEGMENT_NAMES
from hexaleg.robot.chains import LegChain
from hexaleg.robot.description import Inertial, RobotDescription, parse_urdf
from hexaleg.robot.feet import Foot
from hexaleg.robot.imported import ImportedLeg, ImportedRobot, SegmentChange, segment_masses
from hexaleg.robot.legs import read_leg

SAME_LENGTH = 1e-9
"""A change smaller than this is no change [m]."""

CYLINDER_RADIUS = 0.1
"""Radius of the cylinder drawn for a changed segment, as a fraction of its length [-]."""

Lengths = Mapping[str, Mapping[str, float]]
"""New segment lengths [m] by leg name (``lf`` … ``rr``), then segment (coxa, femur, tibia)."""


def resize_robot(
    robot: ImportedRobot, lengths: Lengths, field: Callable[[str, str], str] | None = None
) -> ImportedRobot:
    """``robot`` with the segments of ``lengths`` changed along their own lines (module rule).

    Args:
        robot: The robot as read from its file.
        lengths: New lengths [m] by leg, then segment; legs and segments not named keep
            the file's.
        field: How the caller names a leg's segment in errors (default ``"lf.femur"``).

    Raises:
        ParameterError: A leg or segment that the robot has not, a length outside
            :data:`SEGMENT_RANGE`, or a change of a segment of length 0.

    """
    changes = _changes(robot, lengths, field or "{}.{}".format)
    if not changes:
        return robot
    root = _parse(robot.text)
    elements = {(e.tag, e.get("name")): e for e in root if e.tag in ("link", "joint")}
    frames = robot.description.frames_at_zero()
    feet = {}
    for leg in robot.legs:
        point = np.asarray(leg.reading.foot.point, dtype=float)
        for change in (c for c in changes if c.leg == leg.name):
            k = SEGMENT_NAMES.index(change.segment)
            stretch = _Stretch(leg, k, change.ratio)
            end = _stretch_segment(robot.description, leg.chain, k, frames, stretch, elements)
            if k == 2:  # the tibia ends at the foot
                point = stretch.point(point)
                end = point
            _draw_cylinder(elements[("link", leg.chain.segments[k][0])], change, stretch, end)
        foot = leg.reading.foot
        feet[leg.name] = replace(foot, point=(float(point[0]), float(point[1]), float(point[2])))
    root.insert(0, ET.Comment(_summary(changes)))
    ET.indent(root, space="  ")
    text = ET.tostring(root, encoding="unicode") + "\n"
    return _read_again(robot, text, feet, changes)


def _changes(
    robot: ImportedRobot, lengths: Lengths, field: Callable[[str, str], str]
) -> tuple[SegmentChange, ...]:
    """The changes asked for, checked; those within :data:`SAME_LENGTH` of the file dropped."""
    legs = {leg.name: leg for leg in robot.legs}
    changes = []
    for name, asked in lengths.items():
        for segment, value in asked.items():
            where = field(name, segment)
            if name not in legs:
                raise ParameterError(where, value, f"the robot's legs are {', '.join(legs)}")
            geometry = legs[name].reading.geometry
            if segment not in SEGMENT_NAMES:
                raise ParameterError(
                    where, value, f"a leg's segments are {', '.join(SEGMENT_NAMES)}"
                )
            length = require_in_range(where, value, *SEGMENT_RANGE, "m")
            before = getattr(geometry, segment)
            if abs(length - before) <= SAME_LENGTH:
                continue
            if before <= SAME_LENGTH:
                raise ParameterError(
                    where,
                    value,
                    f"leg {name}'s {segment} is 0 m in the file (the axes meet): hexaleg "
                    f"changes a segment by stretching it, and cannot stretch one of length 0",
                )
            changes.append(SegmentChange(name, segment, before, length))
    return tuple(changes)


class _Stretch:
    """The stretch of segment ``k`` of ``leg`` by ``ratio``, in its link's frame (at q = 0)."""

    def __init__(self, leg: ImportedLeg, k: int, ratio: float) -> None:
        geometry = leg.reading.geometry
        self.to_segment = geometry.link_placement(k)  # link coordinates → segment frame K's
        self.from_segment = np.linalg.inv(self.to_segment)
        self.ratio = ratio
        self.direction = geometry.segment_directions()[k]  # d, in the link's frame

    def point(self, p: ArrayF) -> ArrayF:
        """A point (3,) in the link's frame, stretched [m]."""
        local = self.to_segment[:3, :3] @ p + self.to_segment[:3, 3]
        local[0] *= self.ratio
        return self.from_segment[:3, :3] @ local + self.from_segment[:3, 3]

    def linear(self) -> ArrayF:
        """S = 1 + (k − 1)·d dᵀ (3, 3): the stretch of directions, in the link's axes."""
        return np.eye(3) + (self.ratio - 1.0) * np.outer(self.direction, self.direction)


def _stretch_segment(
    description: RobotDescription,
    chain: LegChain,
    k: int,
    frames: Mapping[str, ArrayF],
    stretch: _Stretch,
    elements: dict[tuple[str, str | None], ET.Element],
) -> ArrayF:
    """Stretch segment ``k``'s links in the XML; the next joint's origin (3,) in its link frame.

    The tibia has no next joint: its end is the foot, which the caller moves (zeros here).
    """
    names = chain.segments[k]
    inverse = np.linalg.inv(frames[names[0]])
    before = {n: inverse @ frames[n] for n in names}  # each link's frame in the segment link's
    after = {n: _moved(f, stretch) for n, f in before.items()}
    after[names[0]] = np.eye(4)  # on the joint's axis, where the stretch moves nothing
    end = np.zeros(3)
    for joint in description.joints.values():
        if joint.parent not in names:
            continue
        child = after[joint.child] if joint.child in names else None
        if child is None:
            child = _moved(before[joint.parent] @ joint.origin, stretch)
        if k < 2 and joint.name == chain.joints[k + 1].name:
            end = child[:3, 3]
        _set_origin(elements[("joint", joint.name)], np.linalg.inv(after[joint.parent]) @ child)
    for name in names:
        link = description.links[name]
        element = elements[("link", name)]
        for shape in element.findall("visual") + element.findall("collision"):
            element.remove(shape)
        if link.inertial is not None and link.inertial.mass > 0.0:
            _stretch_inertial(element, link.inertial, before[name], after[name], stretch)
    return end


def _moved(frame: ArrayF, stretch: _Stretch) -> ArrayF:
    """``frame`` (4, 4) with its origin stretched and its axes kept."""
    moved = frame.copy()
    moved[:3, 3] = stretch.point(frame[:3, 3])
    return moved


def _stretch_inertial(
    element: ET.Element, inertial: Inertial, before: ArrayF, after: ArrayF, stretch: _Stretch
) -> None:
    """Rewrite a link's ``<inertial>``: mass × k, centre of mass and second moments stretched."""
    mass, com, inertia = inertial.mass, inertial.com, inertial.inertia
    rotation = before[:3, :3]  # the link's axes in the segment link's (kept by the stretch)
    centre = stretch.point(rotation @ com + before[:3, 3])
    local_com = rotation.T @ (centre - after[:3, 3])
    about = rotation @ inertia @ rotation.T
    second = np.trace(about) / 2 * np.eye(3) - about  # Σ = ∫ r rᵀ dm
    s = stretch.linear()
    second = stretch.ratio * s @ second @ s.T
    stretched = rotation.T @ (np.trace(second) * np.eye(3) - second) @ rotation
    for old in element.findall("inertial"):
        element.remove(old)
    node = ET.SubElement(element, "inertial")
    ET.SubElement(node, "origin", xyz=_xyz(local_com), rpy="0 0 0")
    ET.SubElement(node, "mass", value=repr(float(stretch.ratio * mass)))
    names = (("ixx", 0, 0), ("ixy", 0, 1), ("ixz", 0, 2), ("iyy", 1, 1), ("iyz", 1, 2))
    values = {n: repr(float(stretched[i, j])) for n, i, j in (*names, ("izz", 2, 2))}
    ET.SubElement(node, "inertia", values)


def _draw_cylinder(
    element: ET.Element, change: SegmentChange, stretch: _Stretch, end: ArrayF
) -> None:
    """A cylinder (visual and collision) along the changed segment, ending at ``end`` [m]."""
    d = stretch.direction
    centre = end - d * change.length / 2
    helper = np.array([1.0, 0.0, 0.0]) if abs(d[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(helper, d)
    x /= np.linalg.norm(x)
    rotation = np.column_stack((x, np.cross(d, x), d))  # z along the segment
    rpy = " ".join(repr(float(v)) for v in pin.rpy.matrixToRpy(rotation))
    element.append(
        ET.Comment(
            f" hexaleg: {change.segment} of leg {change.leg} changed from {change.file_length!r} "
            f"to {change.length!r} m along its own line; its meshes are replaced by this "
            f"cylinder, its mass and inertia stretched by {change.ratio!r} "
            f"(hexaleg.robot.resize) "
        )
    )
    radius = repr(CYLINDER_RADIUS * change.length)
    for tag in ("visual", "collision"):
        node = ET.SubElement(element, tag)
        ET.SubElement(node, "origin", xyz=_xyz(centre), rpy=rpy)
        geometry = ET.SubElement(node, "geometry")
        ET.SubElement(geometry, "cylinder", radius=radius, length=repr(change.length))


def _summary(changes: tuple[SegmentChange, ...]) -> str:
    listed = "; ".join(
        f"{c.leg} {c.segment} {c.file_length:.6g} -> {c.length:.6g} m" for c in changes
    )
    return (
        f" hexaleg: segments changed from the file's ({listed}), each along its own line; "
        f"the changed segments are drawn as cylinders in place of their meshes "
    )


def changes_note(changes: tuple[SegmentChange, ...]) -> str:
    """One line saying which segments changed and that they are drawn as cylinders."""
    segments = sorted({c.segment for c in changes}, key=SEGMENT_NAMES.index)
    legs = sorted({c.leg for c in changes})
    which = f"{' and '.join(segments)} of {'every leg' if len(legs) == 6 else ', '.join(legs)}"
    return f"the {which} changed from the file's: drawn as cylinders in place of their meshes"


def _read_again(
    robot: ImportedRobot, text: str, feet: Mapping[str, Foot], changes: tuple[SegmentChange, ...]
) -> ImportedRobot:
    """The changed robot, each leg read again from ``text`` (same chains, moved feet)."""
    description = parse_urdf(text, str(robot.source) if robot.source else "<string>")
    frames = description.frames_at_zero()
    legs = []
    for leg in robot.legs:
        joints = tuple(description.joints[j.name] for j in leg.chain.joints)
        chain = LegChain(joints, leg.chain.segments)  # type: ignore[arg-type]
        reading = read_leg(chain, frames, feet[leg.name])
        legs.append(
            ImportedLeg(leg.name, chain, reading, segment_masses(description, chain, frames))
        )
    return replace(robot, text=text, description=description, legs=tuple(legs), changes=changes)


def _parse(text: str) -> ET.Element:
    parser = ET.XMLParser(target=ET.TreeBuilder(insert_comments=True))
    return ET.fromstring(text, parser=parser)


def _set_origin(element: ET.Element, placement: ArrayF) -> None:
    for old in element.findall("origin"):
        element.remove(old)
    rpy = " ".join(repr(float(v)) for v in pin.rpy.matrixToRpy(placement[:3, :3]))
    origin = ET.Element("origin", xyz=_xyz(placement[:3, 3]), rpy=rpy)
    element.insert(0, origin)


def _xyz(vector: ArrayF) -> str:
    return " ".join(repr(float(v)) for v in vector)
