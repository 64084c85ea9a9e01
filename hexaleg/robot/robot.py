"""The robot every command analyses: hexaleg's template at a design, or a robot file as read.

A :class:`Robot` is built once (:meth:`Robot.build`) from its recipe, a
:class:`~hexaleg.robot.recipe.RobotSource`, and the design its numbers go over (joint-limit
sets, posture, ratings; for the template, the whole design). It holds its design, its
Pinocchio model, each leg's general leg, its masses and limits, and what it says of itself
(:meth:`Robot.record`, :meth:`Robot.fingerprint`); :meth:`Robot.at` derives the robot at
other segment lengths, posture or ratings, as a study, a decision and the explorer ask.

Everything that differs between the two kinds lives here and in the models
(:class:`~hexaleg.robot.model.HexapodModel`, its subclass
:class:`~hexaleg.robot.imported_model.ImportedHexapodModel`): the template's design is
rendered through Xacro and its models derive from one another in closed form; a robot
file's design is read from the file (:func:`~hexaleg.robot.robot_design.robot_design`), and
at other lengths it is the file with every leg's segments changed along their own lines
(:mod:`hexaleg.robot.resize`).
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from dataclasses import fields
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
import tomli_w

from hexaleg._checks import require_instance
from hexaleg._typing import ArrayF
from hexaleg.design import SEGMENT_RANGE, SEGMENTS, HexapodDesign, ratio_lengths
from hexaleg.design_file import DesignFile
from hexaleg.design_text import design_toml
from hexaleg.exceptions import ParameterError
from hexaleg.leg_geometry import SEGMENT_NAMES, LegGeometry
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.imported import ImportedRobot, urdf_with_feet
from hexaleg.robot.imported_model import (
    ImportedHexapodModel,
    imported_design,
    resized_model,
    robot_mass,
)
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.model_cache import model_of
from hexaleg.robot.recipe import TEMPLATE_NAME, RobotSource
from hexaleg.robot.resize import SAME_LENGTH, changes_note
from hexaleg.robot.robot_design import robot_design, robot_record
from hexaleg.robot.robot_table import check_written_fixed, check_written_lengths, robot_table
from hexaleg.robot.urdf import render_hexapod

__all__ = [
    "FILE_FIXES",
    "FILE_TAKES",
    "POSTURE_FIELD",
    "SEGMENT_SPAN",
    "Robot",
    "as_robot",
    "derived_numbers",
    "robot_of",
    "template_robot",
]

SEGMENT_SPAN = 0.5
"""A decision searches a robot file's segment within this share of its own length either
side of it [-]: its l1, l2, l3 are the centre of the bounds."""

POSTURE_FIELD = "nominal_angles"
"""The design field of a robot's posture (θ1, θ2, θ3) [rad]: what a posture search frees."""

FILE_TAKES = frozenset((*SEGMENTS, POSTURE_FIELD))
"""The design fields a robot file's robot takes from a caller: its segments (every leg's,
changed along their own lines) and its posture. Its body, mounts, masses, limits and
ratings are the file's (and the design file's overrides it was built over)."""

FILE_FIXES = frozenset(
    (
        "body_length",
        "body_width",
        "layout",
        "body_radius",
        "first_leg_angle",
        "middle_leg_offset",
        "front_yaw",
        "rear_yaw",
        "mounts",
        "stance_limits",
        "link_linear_density",
        "link_radius",
    )
)
"""The design fields a robot file never takes from the design it is built over: its body's
size and layout and its legs' mounts are its file's, each leg stands within its own joint
limits, and its links' masses and shapes are the file's. (Its body height is the file's leg's
below the design's; its body mass and ratings may be overridden, :mod:`.robot_design`.)"""

FIXED = "not for a robot file: its body, mounts, stance limits and links are its file's"
"""Why a field of :data:`FILE_FIXES` given over a robot file is refused."""

Lengths = tuple[float, float, float]
"""(l1, l2, l3): coxa, femur and tibia [m]."""

SegmentChanges = tuple[tuple[str, float], ...]
"""A robot file's segments changed on every leg: (``coxa``/``femur``/``tibia``, length [m])."""


class Robot:
    """A hexapod to analyse: its design, its Pinocchio model, its legs and what it is made of.

    Built by :meth:`build` (or derived by :meth:`at`), never by hand.

    Attributes:
        source: How to build it again (in another process).
        over: The design it was built over: the template's whole design, or the design a
            robot file's numbers go over (limit sets, posture, a design file's ratings).

    """

    def __init__(
        self,
        source: RobotSource,
        over: HexapodDesign,
        model: HexapodModel | None = None,
        given: ImportedRobot | None = None,
        design: HexapodDesign | None = None,
        lengths: SegmentChanges = (),
    ) -> None:
        self.source, self.over = source, over
        self._model, self._given = model, given
        self._design = over if design is None else design
        self._lengths = lengths  # a robot file's segments changed by at(), every leg

    def __reduce__(self) -> tuple[Any, ...]:
        """A robot crosses processes as its recipe, built again there once (:func:`robot_of`)."""
        return (robot_of, self._recipe)

    def __eq__(self, other: object) -> bool:
        """Robots of the same recipe are the same robot."""
        return isinstance(other, Robot) and self._recipe == other._recipe

    def __hash__(self) -> int:
        """The recipe's hash."""
        return hash(self._recipe)

    @property
    def _recipe(self) -> tuple[RobotSource, HexapodDesign, SegmentChanges]:
        return (self.source, self.over, self._lengths)

    @classmethod
    def build(cls, source: RobotSource | None = None, over: HexapodDesign | None = None) -> Robot:
        """The robot of ``source`` over ``over`` (default: the template, the default design).

        A robot file is read now (once per process; its warnings, placeholder masses and
        inertias, shown) and its design made; its model, on first use (a file whose legs do
        not stand level is refused then, as its URDF is written without one).

        Raises:
            HexalegError: The file cannot be read or changed, in one line.

        """
        source = RobotSource() if source is None else source
        over = HexapodDesign() if over is None else over
        if source.path is None:
            return cls(source, over)
        given, caught = source.read()
        for warning in caught:
            warnings.warn(warning.message, warning.category, stacklevel=2)
        return cls(source, over, None, given, imported_design(given, over))

    # -- what it is ---------------------------------------------------------------------------

    @property
    def model(self) -> HexapodModel:
        """Its Pinocchio model, built on first use."""
        if self._model is None:
            self._model = (
                model_of(self.over)
                if self._given is None
                else ImportedHexapodModel(self._given, self.over, self._design)
            )
        return self._model

    @property
    def design(self) -> HexapodDesign:
        """The design its analyses go over: its segments, body, mounts, posture, ratings."""
        return self._design

    @property
    def name(self) -> str:
        """What names it: its robot file, or hexaleg's template."""
        return TEMPLATE_NAME if self.source.path is None else self.source.path

    def titled(self, what: str) -> str:
        """A title naming the robot where it is a file's: ``"Statics of FILE"``."""
        return what if self.source.path is None else f"{what} of {self.source.path}"

    @property
    def leg_names(self) -> tuple[str, ...]:
        """Its legs' names, in order."""
        return self.design.leg_names if self._given is None else self._given.leg_names

    @property
    def own_legs(self) -> dict[str, LegGeometry] | None:
        """Each leg's own general leg where the legs are not the design's (see the model's)."""
        if self._given is None:
            return None
        return {leg.name: leg.reading.geometry for leg in self._read.legs}

    @property
    def lengths(self) -> Lengths:
        """Its own (l1, l2, l3) [m]: the design's, or a robot file's first leg's (l1 may be 0)."""
        if self._given is None:
            return self.design.lengths
        a, b, c = self._read.legs[0].reading.geometry.lengths
        return (float(a), float(b), float(c))

    @property
    def fixed_coxa(self) -> bool:
        """Whether its coxa cannot change: 0 in its file (the yaw and hip axes meet)."""
        return self.lengths[0] <= SAME_LENGTH

    @property
    def design_links(self) -> bool:
        """Whether its leg links are built from its design, ``[structure]`` tubes included.

        The template's are; a robot file's links are its file's (see the model's).
        """
        return self._given is None

    def require_masses(self) -> None:
        """Refuse a robot without masses, before what needs them (statics, walking, a study).

        Raises:
            RobotImportError: A robot file whose links have no mass, in one line
                (:func:`~hexaleg.robot.imported_model.robot_mass`).

        """
        robot_mass(self.model)

    @property
    def body_sweepable(self) -> bool:
        """Whether its body's fields may be varied (a sensitivity table): the template's."""
        return self._given is None

    def takes(self, field: str) -> bool:
        """Whether :meth:`at` changes design field ``field`` (a file fixes its body)."""
        return self._given is None or field in FILE_TAKES

    # -- other robots of the same source ------------------------------------------------------

    def at(self, design: HexapodDesign | None = None, /, **changes: Any) -> Robot:
        """The robot with the design fields ``changes`` changed (segments, posture, …).

        ``design``: a design whose fields that differ from the robot's are changes too (a
        query's design, made from this robot's).

        The template: the model of its design so changed, derived in closed form from a
        model of the same body (:func:`~hexaleg.robot.model_cache.model_of`). A robot file:
        every leg's segments ``l1 l2 l3`` changed along their own lines (a coxa of 0 stays 0)
        and its posture over its file's, as :meth:`build` makes it; a field it fixes
        (:meth:`takes`) is refused.

        Raises:
            ParameterError: A value out of range, or a field the robot fixes.

        """
        if self._given is None:
            design = self.design if design is None else design
            design = design.replace(**changes) if changes else design
            return Robot(self.source, design, model_of(design))
        if design is not None:
            changes = _differing(self.design, design) | changes
        refused = [name for name in changes if not self.takes(name)]
        if refused:
            raise ParameterError(
                refused[0],
                changes[refused[0]],
                "not for a robot file: its body, mounts, masses, limits and ratings are its "
                "file's (its segments and posture change)",
            )
        lengths = dict(self._lengths)
        for name, segment in zip(SEGMENTS, SEGMENT_NAMES, strict=True):
            if name in changes and not (name == "l1" and self.fixed_coxa):
                lengths[segment] = float(changes.pop(name))
        changes.pop("l1", None)  # a coxa of 0 stays 0
        over = self.over.replace(**changes) if changes else self.over
        return _derived(self.source, over, tuple(sorted(lengths.items())))

    def at_ratios(self, l1_ratio: float, l3_ratio: float, total: float | None = None) -> Robot:
        """The robot with its segments at these ratios of a total leg length [m] (its own).

        Raises:
            ParameterError: A ratio or length out of range (:meth:`at`'s too).

        """
        total = self.design.leg_length if total is None else total
        lengths = ratio_lengths(l1_ratio, l3_ratio, total)
        return self.at(**dict(zip(SEGMENTS, lengths, strict=True)))

    def rebuilt(self) -> Robot:
        """The robot measured again from its own URDF, nothing derived.

        The template's model rendered and built from its design; a robot file's model is
        built from its own (changed) file already.
        """
        if self._given is not None:
            return self
        return Robot(self.source, self.design, HexapodModel(self.design))

    def searches(self, field: str) -> bool:
        """Whether a decision may free design field ``field`` (the template's: any).

        A robot file's segments only: its posture stands within its own limits and its
        motors and body are its file's.
        """
        return self._given is None or field in SEGMENTS

    def segment_bounds(self, floor: float, leg_length: float) -> dict[str, tuple[float, float]]:
        """Each free segment's search bounds [m], at least ``floor``, at most ``leg_length``.

        The template's span the whole leg; a robot file's lie within :data:`SEGMENT_SPAN`
        of its own, and a coxa of 0 is not free.

        Raises:
            ParameterError: ``leg_length`` below a segment's lower bound.

        """
        if self._given is None:
            return dict.fromkeys(SEGMENTS, (floor, leg_length))
        bounds = {}
        for name, length in zip(SEGMENTS, self.lengths, strict=True):
            if name == "l1" and self.fixed_coxa:
                continue
            lower = max(floor, (1 - SEGMENT_SPAN) * length)
            upper = min((1 + SEGMENT_SPAN) * length, leg_length, SEGMENT_RANGE[1])
            if upper <= lower:
                raise ParameterError(
                    "leg_length", leg_length, f"above {lower:.4g} m, where {name} is searched from"
                )
            bounds[name] = (lower, upper)
        return bounds

    def check_over(self, given: Mapping[str, Any], file: DesignFile | None = None) -> None:
        """Refuse what a robot file fixes, given over it: silently ignored, it would mislead.

        Args:
            given: The design fields given over the design (a command's options), with
                their values: none of :data:`FILE_FIXES`.
            file: The design file written from this robot file (its ``[robot]`` table's),
                if it is: its keys of :data:`FILE_FIXES` must hold the file's values, and
                its ``l1 l2 l3`` the file's segments unless ``given``
                (:func:`~hexaleg.robot.robot_table.check_written_lengths`). The template
                takes everything: nothing to check.

        Raises:
            ParameterError: A field of ``given`` the robot file fixes.
            DesignFileError: A key of ``file`` edited from the robot file's value.

        """
        if self._given is None:
            return
        for name, value in given.items():
            if name in FILE_FIXES:
                raise ParameterError(name, value, FIXED)
        if file is None:
            return
        overridden = {name for name in SEGMENTS if name in given}
        check_written_lengths(_file_lengths(self._given), file.data, overridden, str(file.path))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # shown when the robot was built
            reference = robot_design(self._given)
        check_written_fixed(reference, file, FILE_FIXES, FIXED)

    # -- what it says of itself -----------------------------------------------------------------

    def fingerprint(self) -> dict[str, Any]:
        """What a journal keys on beside its design (``{}``: the template's design is all).

        A robot file's: ``{"robot": ...}``, the file, its text's hash and how it is read.
        """
        if self._given is None:
            return {}
        return {"robot": self.source.fingerprint(self._given.text)}

    def record(self) -> dict[str, Any]:
        """What ``design show --json`` prints: the design and its derived numbers.

        A robot file's also lists each leg as read (``design.legs``) and the file
        (``robot``); its derived numbers are the file's (its mass is Pinocchio's).
        """
        shown: dict[str, Any] = {
            "design": self.design.as_dict(),
            "derived": derived_numbers(self.design, self.model),
        }
        if self._given is None:
            return shown
        read = robot_record(self._read, self.design.nominal_angles)
        shown["design"]["legs"] = read.pop("legs")
        shown["robot"] = read
        return shown

    def posture(self) -> dict[str, Any]:
        """A robot file's name and nominal posture for a command's JSON, ``{}`` for the template.

        ``robot`` (the file), ``joint_angles`` (hexaleg's θ) and ``urdf_joint_angles`` (the
        file's q = s·θ + o), per leg [rad].
        """
        if self._given is None:
            return {}
        model = self.model
        nominal = {leg: list(model.nominal_angles(leg)) for leg in model.leg_names}
        return self.named() | {"joint_angles": nominal} | self.in_file_joints(nominal)

    def named(self) -> dict[str, Any]:
        """``{"robot": FILE}`` for a command's JSON where the robot is a file's, else ``{}``."""
        return {} if self._given is None else {"robot": self.name}

    def in_file_joints(self, angles: Mapping[str, Any]) -> dict[str, Any]:
        """Angles θ by leg [rad] also in a robot file's own joints, for a command's JSON.

        ``{"urdf_joint_angles": {leg: q}}`` with q = s·θ + o per leg; ``{}`` for the
        template, whose joints are θ.
        """
        if self._given is None:
            return {}
        model = self.model
        return {
            "urdf_joint_angles": {
                leg: model.joint_values(leg, theta).tolist() for leg, theta in angles.items()
            }
        }

    def file_columns(
        self, legs: Sequence[str], joint_angles: ArrayF, joint_torques: ArrayF
    ) -> dict[str, ArrayF]:
        """A motion in a robot file's own joints, as named columns (N,) each.

        ``{}`` for the template, whose joints are θ.

        Args:
            legs: The legs of the motion's columns, in order (L,).
            joint_angles: Angles θ (N, L, 3) [rad].
            joint_torques: Torques on θ (N, L, 3) [N·m].

        Returns:
            Per leg and joint ``<leg>_<joint>_urdf_q`` (q = s·θ + o) [rad] and ``_urdf_tau``
            (s·τ, the torque about the file's joint axis) [N·m].

        """
        if self._given is None:
            return {}
        model, columns = self.model, {}
        for i, leg in enumerate(legs):
            values = model.joint_values(leg, joint_angles[:, i])
            torques = model.joint_signs(leg) * joint_torques[:, i]
            for j, joint in enumerate(LEG_JOINTS):
                columns[f"{leg}_{joint}_urdf_q"] = np.asarray(values)[:, j]
                columns[f"{leg}_{joint}_urdf_tau"] = torques[:, j]
        return columns

    def urdf(self) -> str:
        """Its URDF: the template rendered at its design, or the file with its feet marked.

        A robot file's is its own text (joints, zeros, signs, masses, meshes) with a link
        ``<leg>_foot`` at each foot point, its changed segments drawn as cylinders.
        """
        if self._given is None:
            return render_hexapod(self.design)
        return urdf_with_feet(self._read)

    @property
    def notes(self) -> tuple[str, ...]:
        """What a command says of the robot once: the segments changed from its file's."""
        if self._given is None or not self._read.changes:
            return ()
        return (changes_note(self._read.changes),)

    def design_text(self, at: Path | None = None) -> str:
        """A design file (TOML) that reads back as this robot, written at ``at``.

        A robot file's: the design with the file's own segments, and its ``[robot]`` table
        (paths relative to ``at``'s folder, absolute without it) whose
        ``[robot.segments]`` hold the segments changed from the file's.
        """
        if self._given is None:
            return design_toml(self.design)
        read = self._read
        lengths = _file_lengths(read)
        written = self.design.replace(l1=lengths[0], l2=lengths[1], l3=lengths[2])
        table = robot_table(self.source, read, at)
        segments = _segments_table(read)
        if segments:
            table["segments"] = segments
        return design_toml(written) + "\n" + ROBOT_COMMENT + tomli_w.dumps({"robot": table})

    @property
    def _read(self) -> ImportedRobot:
        """The robot file as this robot stands (its segments as changed)."""
        model = self._model
        if isinstance(model, ImportedHexapodModel):
            return model.robot  # at other lengths than the file's as given
        assert self._given is not None
        return self._given


ROBOT_COMMENT = (
    "# [robot]: the robot file this design was read from (hexaleg design import);\n"
    "# [robot.read] records what was read, for reference: editing it changes nothing.\n"
    "# What if: [robot.segments] coxa/femur/tibia = M (every leg) or\n"
    "# [robot.segments.<leg>] change the segments along their own lines [m].\n"
)
"""The comment above a design file's ``[robot]`` table."""


def derived_numbers(design: HexapodDesign, model: HexapodModel) -> dict[str, Any]:
    """What follows from the robot: leg length, nominal height, mass, mounts, footholds.

    The masses, standing height and footholds are the model's (a robot file's: Pinocchio's
    total of its links, the height that puts its feet on the ground, each foot at its own
    nominal posture); the template's model carries its design's.
    """
    feet = model.nominal_footholds
    return {
        "layout": design.layout,
        "body": design.body_description,
        "leg_length": design.leg_length,
        "nominal_height": model.nominal_height,
        "total_mass": model.total_mass,
        "body_mass": model.body_mass,
        "mounts": {
            m.name: {"x": m.x, "y": m.y, "z": m.z, "yaw": m.yaw, "foothold": list(foot)}
            for m, foot in zip(design.legs, feet, strict=True)
        },
        "units": {"lengths": "m", "angles": "rad", "mass": "kg"},
    }


def _file_lengths(read: ImportedRobot) -> Lengths:
    """The first leg's segments as the robot file draws them (before any change) [m]."""
    first = read.legs[0]
    own = dict(zip(SEGMENT_NAMES, first.reading.geometry.lengths, strict=True))
    for change in read.changes:
        if change.leg == first.name:
            own[change.segment] = change.file_length
    a, b, c = (float(own[s]) for s in SEGMENT_NAMES)
    return (a, b, c)


def _segments_table(read: ImportedRobot) -> dict[str, Any]:
    """``[robot.segments]`` of the changes: every leg's, or per leg where the legs differ."""
    legs: dict[str, dict[str, float]] = {}
    for change in read.changes:
        legs.setdefault(change.leg, {})[change.segment] = change.length
    tables = list(legs.values())
    if len(legs) == len(read.legs) and all(t == tables[0] for t in tables):
        return dict(tables[0])
    return {leg: dict(table) for leg, table in legs.items()}


@lru_cache(maxsize=32)
def _derived(source: RobotSource, over: HexapodDesign, lengths: SegmentChanges) -> Robot:
    """The robot file of ``source`` with every leg's ``lengths`` changed, over ``over``."""
    given, _ = source.read()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # shown once, when the robot was built
        model = resized_model(given, dict(lengths), over)
    return Robot(source, over, model, given, model.design, lengths)


@lru_cache(maxsize=8)
def robot_of(source: RobotSource, over: HexapodDesign, lengths: SegmentChanges = ()) -> Robot:
    """The robot of a recipe, built once per process, its warnings not shown again.

    What a robot sent to another process (a study's or a decision's worker) is built from
    there (:meth:`Robot.__reduce__`).
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # shown where the robot was first built
        robot = Robot.build(source, over)
        return robot.at(**_fields(lengths)) if lengths else robot


def template_robot(design: HexapodDesign) -> Robot:
    """Hexaleg's template at ``design``, built once per process (:func:`robot_of`)."""
    return robot_of(RobotSource(), design)


def as_robot(given: Robot | HexapodDesign) -> Robot:
    """``given`` if it is a robot, else hexaleg's template at the design given.

    Raises:
        ParameterError: ``given`` is neither.

    """
    if isinstance(given, Robot):
        return given
    require_instance("design", given, HexapodDesign, "a Robot or a HexapodDesign")
    return template_robot(given)


def _differing(design: HexapodDesign, other: HexapodDesign) -> dict[str, Any]:
    """The fields of ``other`` whose values differ from ``design``'s."""
    return {
        f.name: getattr(other, f.name)
        for f in fields(HexapodDesign)
        if getattr(other, f.name) != getattr(design, f.name)
    }


def _fields(lengths: SegmentChanges) -> dict[str, float]:
    """Segment changes (``femur``, 0.08) as design fields (``l2``)."""
    return {SEGMENTS[SEGMENT_NAMES.index(segment)]: value for segment, value in lengths}
