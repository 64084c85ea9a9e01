"""A user's hexapod read from its URDF or Xacro: six general legs, masses, limits, ratings.

:func:`import_robot` reads the file (:mod:`.source`), its tree (:mod:`.description`),
its six legs (:mod:`.chains`), each leg's foot (:mod:`.feet`) and general leg
(:mod:`.legs`), and names the legs as hexaleg does (``lf lm lr rf rm rr``: by where they
point around the body, :mod:`.leg_names`).
Masses are the file's: each segment's links (the joint's child and every link fixed to
it) are lumped into one rigid body in the segment's link frame.
"""

from __future__ import annotations

import warnings
import xml.etree.ElementTree as ET
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.exceptions import RobotImportError, RobotImportWarning
from hexaleg.layouts import LEG_NAMES
from hexaleg.robot.body_shape import BodyBox, body_box
from hexaleg.robot.chains import LegChain, find_chains
from hexaleg.robot.description import RobotDescription, parse_urdf, plain_urdf
from hexaleg.robot.feet import FootSearch, find_foot
from hexaleg.robot.file_defaults import (
    locked_as_fixed,
    refuse_reversed,
    unlimited_joints,
    warn_locked,
    warn_unlimited,
)
from hexaleg.robot.leg_names import leg_directions, leg_names
from hexaleg.robot.legs import LegReading, read_leg
from hexaleg.robot.packages import PackageFolders
from hexaleg.robot.source import Packages, read_robot_text

if TYPE_CHECKING:
    from hexaleg.robot.resize import SegmentChange


@dataclass(frozen=True, eq=False)
class SegmentMass:
    """A segment's links lumped into one rigid body, in the segment's link frame.

    Attributes:
        mass: Mass [kg].
        com: Centre of mass (3,) [m].
        inertia: Rotational inertia (3, 3) about the centre of mass [kg·m²].

    """

    mass: float
    com: ArrayF
    inertia: ArrayF


@dataclass(frozen=True, eq=False)
class ImportedLeg:
    """One leg of an imported robot.

    Attributes:
        name: hexaleg's name for it (``lf`` … ``rr``).
        chain: Its joints and links as the file draws them.
        reading: Its general leg, mount, joint map and foot.
        masses: Each segment's lumped mass (coxa, femur, tibia).

    """

    name: str
    chain: LegChain
    reading: LegReading
    masses: tuple[SegmentMass, SegmentMass, SegmentMass]

    @property
    def joint_names(self) -> tuple[str, str, str]:
        """The file's three joint names, from the body out."""
        a, b, c = (j.name for j in self.chain.joints)
        return (a, b, c)

    @property
    def file_limits(self) -> tuple[ArrayF, ArrayF]:
        """The file's joint limits (lower (3,), upper (3,)) [rad], ±inf if continuous."""
        joints = self.chain.joints
        return np.array([j.lower for j in joints]), np.array([j.upper for j in joints])

    @property
    def theta_limits(self) -> tuple[ArrayF, ArrayF]:
        """The file's joint limits as limits on hexaleg's angles θ (lower, upper) [rad]."""
        return self.reading.joint_map.theta_bounds(*self.file_limits)

    @property
    def ratings(self) -> tuple[tuple[float | None, ...], tuple[float | None, ...]]:
        """The file's ``effort`` [N·m] and ``velocity`` [rad/s] per joint (``None``: not given)."""
        joints = self.chain.joints
        return tuple(j.effort for j in joints), tuple(j.velocity for j in joints)


@dataclass(frozen=True, eq=False)
class ImportedRobot:
    """A hexapod read from a robot file.

    Attributes:
        source: The file it was read from (``None`` for text).
        text: Its URDF text (Xacro expanded).
        description: Its tree.
        legs: The six legs, in hexaleg's order ``lf lm lr rf rm rr``.
        body: The body's links (root and every link fixed or locked to it).
        body_mass: The body's links lumped, in the root link's frame.
        changes: The segments changed from the file's (:mod:`hexaleg.robot.resize`),
            empty for the robot as the file draws it.
        packages: Where its ``package://`` references are found.
        body_shape: The box its body's collision geometry gives (:mod:`.body_shape`).

    """

    source: Path | None
    text: str
    description: RobotDescription
    legs: tuple[ImportedLeg, ...]
    body: tuple[str, ...]
    body_mass: SegmentMass
    changes: tuple[SegmentChange, ...] = ()
    packages: PackageFolders = field(default_factory=PackageFolders)
    body_shape: BodyBox | None = None

    @property
    def leg_names(self) -> tuple[str, ...]:
        """The legs' names (hexaleg's), in order."""
        return tuple(leg.name for leg in self.legs)

    @property
    def mass(self) -> float:
        """The whole robot's mass [kg]: the body's links and every leg's."""
        return self.body_mass.mass + sum(m.mass for leg in self.legs for m in leg.masses)


def import_robot(
    path: str | Path,
    xacro_args: Mapping[str, str] | None = None,
    packages: Packages | None = None,
    foot: FootSearch | None = None,
    lock: Sequence[str] = (),
) -> ImportedRobot:
    """The hexapod of the URDF or Xacro file at ``path``.

    Raises:
        RobotImportError: The file cannot be read, is no URDF tree, or its legs are not six
            yaw–pitch–pitch legs with a foot each; the message says what was found.

    """
    path = Path(path)
    folders = PackageFolders.of(packages, path.parent)
    text = read_robot_text(path, xacro_args, folders)
    search = foot or FootSearch()
    if search.base_dir is None:
        search = FootSearch(search.offset, search.frame, path.parent, folders)
    return robot_from_text(text, search, lock, source=path)


def robot_from_text(
    text: str,
    foot: FootSearch | None = None,
    lock: Sequence[str] = (),
    source: Path | None = None,
) -> ImportedRobot:
    """The hexapod of URDF ``text`` (see :func:`import_robot`).

    What the file leaves unsaid (:mod:`.file_defaults`): leg joints without limits get
    hexaleg's, and the joints locked (``lock``, and those beyond a knee that are not the
    leg's) are made fixed, in the robot's text itself, each said once.
    """
    text = plain_urdf(text, str(source) if source else "<string>")
    description = parse_urdf(text, str(source) if source else "<string>")
    chains = find_chains(description, lock)
    frames = description.frames_at_zero()
    search = foot or FootSearch()
    readings = [read_leg(c, frames, find_foot(description, c, frames, search)) for c in chains.legs]
    limits = unlimited_joints(list(zip(chains.legs, readings, strict=True)))
    refuse_reversed(description, [j.name for c in chains.legs for j in c.joints])
    fixed = [name for name in chains.locked if name not in chains.accessories]
    if limits or fixed:
        warn_unlimited(limits)
        warn_locked(chains.beyond, description)
        return robot_from_text(locked_as_fixed(text, fixed, limits), search, (), source)
    reaches = [r.geometry.coxa + r.geometry.femur for r in readings]
    names = leg_names(leg_directions([r.mount for r in readings], reaches))
    legs = [
        ImportedLeg(name, chain, reading, segment_masses(description, chain, frames))
        for name, chain, reading in zip(names, chains.legs, readings, strict=True)
    ]
    legs.sort(key=lambda leg: LEG_NAMES.index(leg.name))
    body = lumped_mass(description, chains.body, frames, np.eye(4))
    _warn_implausible_inertias(description)
    packages = PackageFolders.of(search.packages, search.base_dir)
    roots = np.array([r.mount[:3, 3] for r in readings])
    shape = body_box(
        description, chains.body, float(roots[:, 2].mean()), roots, search.base_dir, packages
    )
    return ImportedRobot(
        source, text, description, tuple(legs), chains.body, body, (), packages, shape
    )


def lumped_mass(
    description: RobotDescription,
    links: Sequence[str],
    frames: Mapping[str, ArrayF],
    reference: ArrayF,
) -> SegmentMass:
    """The links' inertials as one rigid body in the frame ``reference`` (4, 4) [kg, m]."""
    inverse = np.linalg.inv(reference)
    mass, first, second = 0.0, np.zeros(3), np.zeros((3, 3))
    for name in links:
        inertial = description.links[name].inertial
        if inertial is None or inertial.mass == 0.0:
            continue
        local = inverse @ frames[name]
        com = local[:3, :3] @ inertial.com + local[:3, 3]
        inertia = local[:3, :3] @ inertial.inertia @ local[:3, :3].T
        mass += inertial.mass
        first += inertial.mass * com
        second += inertia + inertial.mass * (com @ com * np.eye(3) - np.outer(com, com))
    com = first / mass if mass > 0 else np.zeros(3)
    about_com = second - mass * (com @ com * np.eye(3) - np.outer(com, com))
    return SegmentMass(mass, com, about_com)


def implausible_inertias(description: RobotDescription) -> list[str]:
    """The links whose principal moments break the triangle inequality (or are negative)."""
    bad = []
    for name, link in description.links.items():
        if link.inertial is None or link.inertial.mass == 0.0:
            continue
        moments = np.linalg.eigvalsh(link.inertial.inertia)
        slack = 1e-9 * max(float(np.abs(moments).max()), 1e-300)
        if moments[0] < -slack or moments[2] > moments[0] + moments[1] + slack:
            bad.append(name)
    return bad


def _warn_implausible_inertias(description: RobotDescription) -> None:
    bad = implausible_inertias(description)
    if bad:
        listed = ", ".join(bad[:4]) + (f" and {len(bad) - 4} more" if len(bad) > 4 else "")
        warnings.warn(
            f"links {listed} have inertias no rigid body has (a principal moment exceeds the "
            f"sum of the other two): used as given, check them",
            RobotImportWarning,
            stacklevel=3,
        )


def segment_masses(
    description: RobotDescription, chain: LegChain, frames: Mapping[str, ArrayF]
) -> tuple[SegmentMass, SegmentMass, SegmentMass]:
    """Each segment's links lumped in its joint's child link frame (coxa, femur, tibia)."""
    a, b, c = (
        lumped_mass(description, links, frames, frames[links[0]]) for links in chain.segments
    )
    return (a, b, c)


FOOT_MATCH = 1e-9
"""A link this close to a leg's foot point is that foot [m]."""


def carries_foot(leg: ImportedLeg, link: str, frames: Mapping[str, ArrayF]) -> bool:
    """Whether ``link`` is fixed beyond ``leg``'s knee at its foot point (``frames`` at q = 0)."""
    last = leg.chain.segments[2]
    if link not in last[1:]:
        return False
    local = np.linalg.inv(frames[last[0]]) @ frames[link]
    return bool(np.linalg.norm(local[:3, 3] - np.asarray(leg.reading.foot.point)) < FOOT_MATCH)


def urdf_with_feet(robot: ImportedRobot, prefix: str = "") -> str:
    """The robot's own URDF text with a link ``<leg>_foot`` fixed at each leg's foot point.

    Everything else — joint names, zeros and signs, masses, inertias, mesh references — is
    the file's, so the result moves and weighs like the original, joint for joint.
    ``prefix`` goes before each added link's and joint's name.

    A ``<leg>_foot`` link the file already has on that leg at its foot point (hexaleg's
    own output, read back) is kept as it is and not added again.

    Raises:
        RobotImportError: The file already has a link or joint of one of those names that
            is not that leg's foot.

    """
    added = []
    frames = robot.description.frames_at_zero()
    for leg in robot.legs:
        link, joint = f"{prefix}{leg.name}_foot", f"{prefix}{leg.name}_foot_joint"
        if carries_foot(leg, link, frames):
            continue  # the file's own <leg>_foot is this leg's foot: hexaleg's output read back
        for name, kind in ((link, "link"), (joint, "joint")):
            if name in robot.description.links or name in robot.description.joints:
                raise RobotImportError(
                    f"the file already has a {kind} named {name!r}: hexaleg's foot links "
                    f"are <leg>_foot"
                )
        parent = leg.chain.segments[2][0]
        added += [link_element(link), fixed_joint(joint, parent, link, leg.reading.foot.point)]
    if not added:
        return robot.text
    return with_elements(robot.text, "hexaleg: each leg's foot point", added)


def link_element(name: str) -> str:
    """A massless ``<link>`` named ``name``, as XML text (the name escaped)."""
    return ET.tostring(ET.Element("link", name=name), encoding="unicode")


def fixed_joint(
    name: str, parent: str, child: str, xyz: Iterable[float], rpy: Iterable[float] = (0, 0, 0)
) -> str:
    """A fixed ``<joint>`` placing ``child`` at ``xyz`` [m], ``rpy`` [rad] in ``parent``.

    XML text, every name escaped as XML requires: a file's names may hold ``"``, ``<`` or
    ``&``, which pasted as they are would end the attribute or add elements.
    """
    element = ET.Element("joint", name=name, type="fixed")
    ET.SubElement(element, "parent", link=parent)
    ET.SubElement(element, "child", link=child)
    ET.SubElement(
        element,
        "origin",
        xyz=" ".join(repr(float(v)) for v in xyz),
        rpy=" ".join(repr(float(v)) for v in rpy),
    )
    ET.indent(element, space="  ", level=1)
    return ET.tostring(element, encoding="unicode")


def with_elements(text: str, note: str, elements: Sequence[str]) -> str:
    """URDF ``text`` with ``elements`` (XML text) added before ``</robot>``, after ``note``."""
    end = text.rindex("</robot>")
    added = "".join(f"  {element.strip()}\n" for element in elements)
    return f"{text[:end]}  <!-- {note} -->\n{added}{text[end:]}"
