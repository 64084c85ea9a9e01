"""An imported robot as hexaleg's Pinocchio model: the file's masses, joints and feet.

:class:`ImportedHexapodModel` is a :class:`~hexaleg.robot.model.HexapodModel` built from
the robot file itself (:func:`~hexaleg.robot.imported.urdf_with_feet`: its joints, zeros,
signs, masses and inertias, and a ``hexaleg_<leg>_foot`` frame at each foot; the changed file
when segments were changed, :mod:`~hexaleg.robot.resize`), with three things
added so that every analysis written for hexaleg's model reads it unchanged:

- a massless link ``hexaleg_body`` carried by the free flyer, the design's body frame
  (:func:`~hexaleg.robot.robot_design.robot_design`: the root link's axes, its origin
  raised to the mounts' mean plane), to which the file's root link is fixed;
- a fixed frame ``hexaleg_<leg>_root_joint`` per leg at its leg-root frame (z up along the yaw
  axis, x toward the hip at θ1 = 0);
- each leg's joint map ``q = s·θ + o``: configurations take hexaleg's angles θ, torques
  are given on θ (the file's torque times s).

Each leg stands at its own nominal posture: the design's nominal angles moved inside that
leg's file limits, or the nearest that stands (:mod:`~hexaleg.robot.standing`); the body stands
level at the height that puts the feet, on average, on the ground.
"""

from __future__ import annotations

import math
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._typing import ArrayF
from hexaleg.design import SEGMENTS, HexapodDesign
from hexaleg.exceptions import RobotImportError, RobotImportWarning, one_line
from hexaleg.leg_geometry import SEGMENT_NAMES, LegGeometry
from hexaleg.robot.geometry_model import (
    GeometryKind,
    file_geometry,
    missing_meshes_note,
    with_resolved_meshes,
)
from hexaleg.robot.imported import (
    ImportedRobot,
    fixed_joint,
    link_element,
    urdf_with_feet,
    with_elements,
)
from hexaleg.robot.inertia import set_armature
from hexaleg.robot.model import ROOT_JOINT, HexapodModel, _LegIndex
from hexaleg.robot.model import root_frame_name as _root
from hexaleg.robot.robot_design import NO_MASSES, body_depth, mount_plane, robot_design
from hexaleg.robot.standing import LEVEL_FEET, standing_posture

PREFIX = "hexaleg_"
"""Before the name of every link, joint and frame hexaleg adds to a robot file."""

BODY_LINK = PREFIX + "body"
"""The link added as the body frame of an imported robot's model."""

CONTACT_RADIUS = 0.005
"""The sphere each foot point touches the ground with in a simulation [m]: small beside a
robot's legs, so that the contact is where the file's foot point is."""


def imported_model_urdf(robot: ImportedRobot, design: HexapodDesign) -> str:
    """The robot's URDF with its feet, a body link at ``design``'s body frame, leg-root frames.

    Raises:
        RobotImportError: The file already has a link or joint of one of the added names.

    """
    text = urdf_with_feet(robot, PREFIX)
    plane = robot_plane(robot, design)
    names = [BODY_LINK, f"{BODY_LINK}_joint"]
    names += [PREFIX + n for leg in robot.legs for n in (f"{leg.name}_root", _root(leg.name))]
    taken = [n for n in names if n in robot.description.links or n in robot.description.joints]
    if taken:
        raise RobotImportError(
            f"the file already has a link or joint named {taken[0]!r}: hexaleg adds it"
        )
    added = [
        link_element(BODY_LINK),
        _fixed(f"{BODY_LINK}_joint", BODY_LINK, robot.description.root, _shift(-plane)),
    ]
    for leg in robot.legs:
        link = f"{PREFIX}{leg.name}_root"
        mount = _shift(-plane) @ leg.reading.mount
        added += [link_element(link), _fixed(PREFIX + _root(leg.name), BODY_LINK, link, mount)]
    text = with_elements(text, "hexaleg: body and leg-root frames", added)
    joints = robot.description.joints
    continuous = [
        n for leg in robot.legs for n in leg.joint_names if joints[n].kind == "continuous"
    ]
    return _bounded_continuous(text, continuous) if continuous else text


CONTINUOUS_RANGE = (-math.pi, math.pi)
"""The range a continuous leg joint is analysed over: every angle once, about its zero [rad]."""


def _bounded_continuous(text: str, joints: Sequence[str]) -> str:
    """``text`` with the continuous joints ``joints`` revolute over ``CONTINUOUS_RANGE``.

    Pinocchio models a continuous joint by (cos q, sin q); the whole-robot analyses need
    one coordinate per joint and bounds to search within. Its ``effort`` and ``velocity``
    are kept.
    """
    root = ET.fromstring(text)
    for joint in root.iter("joint"):
        if joint.get("name") not in joints:
            continue
        joint.set("type", "revolute")
        limit = joint.find("limit")
        if limit is None:
            limit = ET.SubElement(joint, "limit", effort="0", velocity="0")
        limit.set("lower", repr(CONTINUOUS_RANGE[0]))
        limit.set("upper", repr(CONTINUOUS_RANGE[1]))
    return ET.tostring(root, encoding="unicode")


def resized_model(
    robot: ImportedRobot, lengths: Mapping[str, float], over: HexapodDesign
) -> ImportedHexapodModel:
    """The model of ``robot`` with every leg's segments at ``lengths``, over ``over``.

    ``lengths``: coxa, femur, tibia [m] (those named), the same on every leg, each changed
    along its own line (:func:`~hexaleg.robot.resize.resize_robot`); a segment within
    :data:`~hexaleg.robot.resize.SAME_LENGTH` of a leg's own is kept as it is. A length is
    named in errors by its design field (``l2``), as every leg changes alike.

    Raises:
        ParameterError: A length out of range, or a coxa of length 0 changed.

    """
    from hexaleg.robot.resize import SAME_LENGTH, resize_robot

    changed = {}
    for leg in robot.legs:
        own = dict(zip(SEGMENT_NAMES, leg.reading.geometry.lengths, strict=True))
        asked = {s: float(v) for s, v in lengths.items() if abs(v - own[s]) > SAME_LENGTH}
        if asked:
            changed[leg.name] = asked
    if changed:
        robot = resize_robot(robot, changed, _design_field)
    return ImportedHexapodModel(robot, over)


def _design_field(leg: str, segment: str) -> str:
    """A changed segment's name in errors: its design field (``l2``), the same on every leg."""
    return SEGMENTS[SEGMENT_NAMES.index(segment)]


def has_masses(model: HexapodModel) -> bool:
    """Whether any link has a mass (a kinematics-only file's do not; the template's do)."""
    return float(pin.computeTotalMass(model.model)) > 0.0


def robot_mass(model: HexapodModel) -> float:
    """The whole robot's mass [kg]: every link of its model.

    Raises:
        RobotImportError: A robot file without masses (:func:`has_masses`): statics,
            walking and simulation need them, kinematics do not.

    """
    mass = float(pin.computeTotalMass(model.model))
    if mass <= 0.0:
        source = model.robot.source if isinstance(model, ImportedHexapodModel) else None
        raise RobotImportError(
            f"{source or 'the robot file'} gives no masses (no link has an <inertial> with a "
            f"mass): statics, walking and simulation need them; give each link an <inertial> "
            f"with its mass and inertia (workspace, manipulability, flexibility, view, urdf "
            f"and design show need none)"
        )
    return mass


def robot_plane(robot: ImportedRobot, design: HexapodDesign) -> float:
    """Height of ``design``'s body frame above the file's root link [m] (the mounts' plane)."""
    return mount_plane(robot) - design.legs[0].z


class ImportedHexapodModel(HexapodModel):
    """The hexapod of a robot file on a free flyer, in hexaleg's angles.

    Args:
        robot: The imported robot.
        base: The design its numbers go over (:func:`robot_design`); the default design's
            if omitted.
        design: ``robot``'s design over ``base``, if already made (:func:`imported_design`).

    A continuous leg joint is analysed as a revolute one over :data:`CONTINUOUS_RANGE`
    (every angle once); legs of different segments each by their own general leg.

    Raises:
        RobotImportError: No posture stands within the file's limits
            (:func:`~hexaleg.robot.standing.standing_posture`, naming what breaks).

    """

    def __init__(
        self,
        robot: ImportedRobot,
        base: HexapodDesign | None = None,
        design: HexapodDesign | None = None,
    ) -> None:
        design = imported_design(robot, base) if design is None else design
        self.robot = robot
        self._text = imported_model_urdf(robot, design)
        try:
            model = pin.buildModelFromXML(self._text, pin.JointModelFreeFlyer(), ROOT_JOINT)
        except (ValueError, RuntimeError) as err:  # what the file's checks did not foresee
            message = f"Pinocchio cannot read the robot's URDF: {one_line(err)}"
            raise RobotImportError(message) from None
        legs = {leg.name: _LegIndex(model, leg.name, leg.joint_names, PREFIX) for leg in robot.legs}
        set_armature(model, [leg.v for leg in legs.values()], design)
        super().__init__(design, _model=model, _legs=legs, _base=BODY_LINK)
        self.leg_names = robot.leg_names
        self._maps = {leg.name: leg.reading.joint_map for leg in robot.legs}
        standing = standing_posture(robot, design.nominal_angles, body_depth(robot))
        self._nominal = dict(zip(robot.leg_names, standing.angles, strict=True))
        self._feet = self.foot_positions(self.configuration(pin.SE3.Identity()))[:, 2]
        self._geometry = {leg.name: leg.reading.geometry for leg in robot.legs}
        shape = robot.body_shape
        box = [design.body_length, design.body_width, design.body_height]
        self.body_box = np.array(box) / 2 if shape is None else shape.half_extents.copy()

    def leg_geometry(self, leg: str) -> LegGeometry:
        """``leg``'s general leg, as read from the file."""
        return self._geometry[self._leg(leg).name]

    @property
    def own_legs(self) -> dict[str, LegGeometry]:
        """Each leg's general leg as the file draws it (offsets, bends), by name."""
        return {name: self._geometry[name] for name in self.leg_names}

    @property
    def stance_limits(self) -> None:
        """None: each leg's own file limits hold it standing as they hold it swinging."""
        return None

    @property
    def own_default_gait(self) -> bool:
        """True: the template's default gait is a 1 m leg's; a robot file walks one sized to it."""
        return True

    @property
    def design_links(self) -> bool:
        """False: a robot file's links are its file's (a ``[structure]`` describes none)."""
        return False

    @property
    def mirror_symmetric(self) -> bool:
        """False: a robot file's parts may not be drawn mirror-symmetric."""
        return False

    @property
    def total_mass(self) -> float:
        """Mass of the robot [kg]: Pinocchio's total of the file's links (its design's none)."""
        return float(pin.computeTotalMass(self.model))

    @property
    def body_mass(self) -> float:
        """Mass of the body's links in the file [kg] (a placeholder's, if the file has one)."""
        return float(self.robot.body_mass.mass)

    @property
    def nominal_footholds(self) -> ArrayF:
        """Every foot at the nominal posture, body frame at the origin (6, 3) [m]."""
        return self.foot_positions(self.configuration(pin.SE3.Identity()))

    def contact_radius(self, leg: str) -> float:
        """:data:`CONTACT_RADIUS` [m]: the file's feet draw no sphere hexaleg reads."""
        self._leg(leg)
        return CONTACT_RADIUS

    @property
    def simulation_draws_links(self) -> bool:
        """False: the simulated file has no shapes but its feet (:attr:`simulation_urdf`)."""
        return False

    @property
    def simulation_urdf(self) -> str:
        """The URDF without its links' shapes (masses and joints kept): only the feet touch.

        A file's meshes would need their files and make poor contact shapes.
        """
        tree = ET.fromstring(self._text)
        for link in tree.iter("link"):
            for shape in link.findall("visual") + link.findall("collision"):
                link.remove(shape)
        return ET.tostring(tree, encoding="unicode")

    @property
    def urdf(self) -> str:
        """The URDF the model was built from (the file's, with feet, body and root frames)."""
        return self._text

    def collision_model(self) -> pin.GeometryModel:
        """A copy of the file's collision geometry, its meshes found as the import finds them.

        A ``<collision>`` whose mesh names no file is left out, with a warning
        (:func:`~hexaleg.robot.geometry_model.file_geometry`).
        """
        if self._collision is None:
            geometry, missing = self._file_geometry("collision")
            if missing:
                what = "those parts are not checked for contact"
                warnings.warn(
                    missing_meshes_note(missing, self.robot.packages, what),
                    RobotImportWarning,
                    stacklevel=2,
                )
            self._collision = geometry
        return self._collision.copy()

    def visual_model(self) -> pin.GeometryModel:
        """The file's visuals, each mesh read from its local file (:attr:`missing_meshes`).

        A visual whose mesh file is not found (``package://`` without its ``--package``,
        meshes not shipped with the file) is left out.
        """
        return self._file_geometry("visual")[0]

    @property
    def missing_meshes(self) -> tuple[str, ...]:
        """The visual mesh references whose files were not found, each once (no mesh read)."""
        return with_resolved_meshes(self._text, "visual", self._folder, self.robot.packages)[1]

    def missing_meshes_note(self, what: str) -> str | None:
        """One sentence on the visual meshes not found (``what`` that means); ``None``: none."""
        missing = self.missing_meshes
        return missing_meshes_note(missing, self.robot.packages, what) if missing else None

    @property
    def _folder(self) -> Path | None:
        """The robot file's folder, where its relative mesh paths start."""
        return None if self.robot.source is None else self.robot.source.parent

    def _file_geometry(self, kind: GeometryKind) -> tuple[pin.GeometryModel, tuple[str, ...]]:
        return file_geometry(self.model, self._text, kind, self._folder, self.robot.packages)

    def with_design(self, design: HexapodDesign) -> ImportedHexapodModel:
        """The robot with every leg's segments at ``design``'s l1, l2, l3, over ``design``.

        The segments change along their own lines (:func:`~hexaleg.robot.resize.resize_robot`:
        offsets and bends kept, the segments' links stretched); ``design``'s posture and
        payload-independent fields go over the file's as for the robot as read. A segment
        within :data:`~hexaleg.robot.resize.SAME_LENGTH` of its length is kept as it is.

        Raises:
            ParameterError: A length out of range, or a coxa of length 0 changed.

        """
        lengths = dict(zip(SEGMENT_NAMES, design.lengths, strict=True))
        return resized_model(self.robot, lengths, design)

    def nominal_angles(self, leg: str) -> tuple[float, float, float]:
        """``leg``'s nominal angles θ [rad]: the design's, moved inside the leg's file limits."""
        a, b, c = (float(t) for t in self._nominal[self._leg(leg).name])
        return (a, b, c)

    def joint_values(self, leg: str, theta: npt.ArrayLike) -> ArrayF:
        """The file's joint values q = s·θ + o (..., 3) [rad] of ``leg``."""
        return self._maps[self._leg(leg).name].to_file(theta)

    def leg_angles(self, leg: str, values: npt.ArrayLike) -> ArrayF:
        """The angles θ = s·(q − o) (..., 3) [rad] of ``leg``."""
        return self._maps[self._leg(leg).name].from_file(values)

    def joint_signs(self, leg: str) -> ArrayF:
        """The joint map's signs s (3,) of ``leg``."""
        return self._maps[self._leg(leg).name].sign_array

    def joint_limits(self, leg: str) -> tuple[ArrayF, ArrayF]:
        """(lower, upper) limits on hexaleg's angles θ of ``leg`` [rad], from the file's."""
        lower, upper = super().joint_limits(leg)
        return self._maps[self._leg(leg).name].theta_bounds(lower, upper)

    def nominal_base_pose(self) -> pin.SE3:
        """The body level, at the height that puts the feet on the ground (their mean).

        Raises:
            RobotImportError: The nominal posture does not put the feet level: the robot
                cannot stand as the analyses stand it.

        """
        spread = self._feet.max() - self._feet.min()
        if spread > LEVEL_FEET:
            raise RobotImportError(
                f"the nominal posture puts the feet {1000 * spread:.1f} mm apart in height "
                f"(at most {1000 * LEVEL_FEET:g} mm): the legs do not stand level"
            )
        return pin.SE3(np.eye(3), np.array([0.0, 0.0, self.nominal_height]))

    @property
    def nominal_height(self) -> float:
        """The body's height that puts the feet, on average, on the ground [m]."""
        return float(-self._feet.mean())


def imported_design(robot: ImportedRobot, base: HexapodDesign | None) -> HexapodDesign:
    """The design of ``robot`` over ``base`` (:func:`robot_design`), its warnings shown.

    A placeholder body's mass is said to be the file's here: the model weighs the file's.
    """
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        design = robot_design(robot, base)
    for warning in caught:
        message = str(warning.message)
        if message.startswith(NO_MASSES):
            continue  # what needs masses refuses (robot_mass), in one line of its own
        if message.startswith("the file's body weighs"):
            message = (
                f"the file's body weighs {robot.body_mass.mass:.3g} kg: the statics use the "
                f"file's masses as given"
            )
        warnings.warn(message, warning.category, stacklevel=3)
    return design


def _shift(z: float) -> ArrayF:
    matrix = np.eye(4)
    matrix[2, 3] = z
    return matrix


def _fixed(name: str, parent: str, child: str, placement: ArrayF) -> str:
    rpy = pin.rpy.matrixToRpy(placement[:3, :3])
    return fixed_joint(name, parent, child, placement[:3, 3], rpy)
