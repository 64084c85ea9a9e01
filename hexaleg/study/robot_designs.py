"""The designs of an imported robot: its own file with its three segments changed.

A study's or a decision's design of hexaleg's template is a
:class:`~hexaleg.design.HexapodDesign` rendered through the Xacro template, whose models
derive from one another in closed form. An imported robot's design at lengths
(l1, l2, l3) is something else: the robot file with every leg's coxa, femur and tibia
changed along their own lines (:func:`~hexaleg.robot.resize.resize_robot`) and a new
:class:`~hexaleg.robot.imported_model.ImportedHexapodModel` of it, its masses, joints,
limits and feet the changed file's. :class:`RobotDesigns` turns lengths into that
(design, model) pair for the study, the decision and the report alike.

It travels to worker processes as the file's recipe (:class:`RobotFile`: the path, its
reading options and the segments changed from the file), from which each process reads
the robot once; a parsed robot does not pickle, and would be sent with every task.
"""

from __future__ import annotations

import hashlib
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from hexaleg.design import SEGMENT_RANGE, SEGMENTS, HexapodDesign
from hexaleg.exceptions import ParameterError
from hexaleg.leg_geometry import SEGMENT_NAMES
from hexaleg.robot.feet import FootSearch
from hexaleg.robot.imported import ImportedRobot, import_robot
from hexaleg.robot.imported_model import ImportedHexapodModel, resized_model, robot_mass
from hexaleg.robot.resize import SAME_LENGTH, resize_robot

__all__ = ["ROBOT_SPAN", "RobotDesigns", "RobotFile"]

ROBOT_SPAN = 0.5
"""A decision searches an imported robot's segment within this share of its own length
either side of it [-]: its l1, l2, l3 are the centre of the bounds."""

Lengths = tuple[float, float, float]
"""(l1, l2, l3): coxa, femur and tibia of every leg [m]."""


@dataclass(frozen=True)
class RobotFile:
    """How to read an imported robot again, in any process (picklable, hashable).

    Attributes:
        path: The URDF or Xacro file.
        xacro_args: Its Xacro arguments (name, value).
        packages: ROS package folders (name, folder).
        foot_offset: The foot point in each leg's last link frame [m], if given.
        foot_frame: The glob pattern of the foot links, if given.
        segments: The segments changed from the file's (leg, segment, length [m]).
        lock: The joints locked at their zero (glob patterns).

    """

    path: str
    xacro_args: tuple[tuple[str, str], ...] = ()
    packages: tuple[tuple[str, str], ...] = ()
    foot_offset: tuple[float, float, float] | None = None
    foot_frame: str | None = None
    segments: tuple[tuple[str, str, float], ...] = ()
    lock: tuple[str, ...] = ()

    @classmethod
    def of(
        cls,
        path: str,
        xacro_args: Mapping[str, str],
        packages: Mapping[str, str],
        foot: FootSearch,
        segments: Mapping[str, Mapping[str, float]],
        lock: Sequence[str] = (),
    ) -> RobotFile:
        """The recipe of a robot read with these options and segments changed."""
        return cls(
            str(path),
            tuple(sorted(xacro_args.items())),
            tuple(sorted(packages.items())),
            foot.offset,
            foot.frame,
            tuple((leg, s, float(v)) for leg, asked in segments.items() for s, v in asked.items()),
            tuple(lock),
        )

    def robot(self) -> ImportedRobot:
        """The robot, read once per process (its warnings were shown when first read)."""
        return _read(self)


@lru_cache(maxsize=4)
def _read(file: RobotFile) -> ImportedRobot:
    packages = dict(file.packages)
    foot = FootSearch(offset=file.foot_offset, frame=file.foot_frame, packages=packages)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        robot = import_robot(file.path, dict(file.xacro_args), packages, foot, file.lock)
    changes: dict[str, dict[str, float]] = {}
    for leg, segment, length in file.segments:
        changes.setdefault(leg, {})[segment] = length
    return resize_robot(robot, changes) if changes else robot


@dataclass(frozen=True)
class RobotDesigns:
    """An imported robot's designs: its file at other segment lengths.

    Attributes:
        file: The robot file and the segments the user changed (the robot "as given").
        over: The design its numbers go over (joint-limit sets, posture, gait ratings),
            as every single-design command takes it
            (:func:`~hexaleg.robot.robot_design.robot_design`).

    """

    file: RobotFile
    over: HexapodDesign

    @property
    def robot(self) -> ImportedRobot:
        """The robot as given (its file, with the user's segment changes)."""
        return self.file.robot()

    @property
    def lengths(self) -> Lengths:
        """The robot's own (l1, l2, l3) [m] (its first leg's; a design has one leg)."""
        a, b, c = self.robot.legs[0].reading.geometry.lengths
        return (float(a), float(b), float(c))

    @property
    def fixed_coxa(self) -> bool:
        """Whether the coxa cannot change: it is 0 in the file (the yaw and hip axes meet)."""
        return self.lengths[0] <= SAME_LENGTH

    def lengths_at(self, values: Mapping[str, float]) -> Lengths:
        """(l1, l2, l3) [m]: the segments ``values`` names (``"l2"``), the robot's own else."""
        l1, l2, l3 = (
            float(values.get(name, own)) for name, own in zip(SEGMENTS, self.lengths, strict=True)
        )
        return (l1, l2, l3)

    def segment_bounds(self, floor: float, leg_length: float) -> dict[str, tuple[float, float]]:
        """Each free segment's search bounds [m]: within :data:`ROBOT_SPAN` of its own.

        At least ``floor`` and at most ``leg_length`` [m]; a coxa of 0 is not free.

        Raises:
            ParameterError: ``leg_length`` below a segment's lower bound.

        """
        bounds = {}
        for name, length in zip(SEGMENTS, self.lengths, strict=True):
            if name == "l1" and self.fixed_coxa:
                continue
            lower = max(floor, (1 - ROBOT_SPAN) * length)
            upper = min((1 + ROBOT_SPAN) * length, leg_length, SEGMENT_RANGE[1])
            if upper <= lower:
                raise ParameterError(
                    "leg_length", leg_length, f"above {lower:.4g} m, where {name} is searched from"
                )
            bounds[name] = (lower, upper)
        return bounds

    def point(self, lengths: Lengths | None = None) -> tuple[HexapodDesign, ImportedHexapodModel]:
        """The design and model of the robot with every leg's segments at ``lengths`` [m].

        ``None``: the robot as given. A coxa of 0 in the file stays 0 (``l1`` ignored).

        Raises:
            HexalegError: A length out of range, a robot that cannot stand at them, or a
                robot file without masses.

        """
        model = _model(self, None if lengths is None else tuple(float(v) for v in lengths))
        robot_mass(model)  # every design point is weighed: a file without masses is refused
        return model.design, model

    def fingerprint(self) -> dict[str, Any]:
        """What determines the designs, JSON-ready (a resumed journal must match it)."""
        text = self.robot.text.encode()
        return {
            "urdf": self.file.path,
            "sha256": hashlib.sha256(text).hexdigest(),
            "xacro_args": dict(self.file.xacro_args),
            "foot_offset": self.file.foot_offset,
            "foot_frame": self.file.foot_frame,
            "segments": [list(s) for s in self.file.segments],
        }


@lru_cache(maxsize=8)
def _model(designs: RobotDesigns, lengths: tuple[float, ...] | None) -> ImportedHexapodModel:
    asked = {} if lengths is None else dict(zip(SEGMENT_NAMES, lengths, strict=True))
    if designs.fixed_coxa:  # a coxa of 0 stays 0
        asked.pop("coxa", None)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # shown once, when the robot was first read
        return resized_model(designs.robot, asked, designs.over)
