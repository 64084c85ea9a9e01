"""What a command's design options resolve to, once: the robot, the requirements, the gait.

Every command that takes a design reads it here, the same way: the ``--design`` file is
read and parsed once (:func:`~hexaleg.design_file.read_design_file`), its design,
``[requirements]``, ``[gait]``, ``[structure]`` and ``[robot]`` tables taken from that one
reading; the options given beside it override its values; ``--best-posture`` stands the
robot at ``hexaleg posture``'s answer (:func:`~hexaleg.cli.best_posture.pose_if_asked`);
the legs' tubes are sized then, where the file asks and the command measures them
(``size = true``, :func:`~hexaleg.cli.structure_options.size_if_asked`); and the robot is
built once
(:meth:`~hexaleg.robot.robot.Robot.build`) from ``--urdf FILE`` (or the file's ``[robot]``
table) and its reading options, or is hexaleg's template at the design. The gait it walks is
the file's ``[gait]`` over the robot's own default gait
(:func:`~hexaleg.gait.defaults.default_gait`), found once, when first asked.
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any

from hexaleg.cli.best_posture import pose_if_asked
from hexaleg.cli.options import DESIGN_FLAGS, UsageError, note
from hexaleg.cli.structure_options import IMPORTED, size_if_asked
from hexaleg.design import DEFAULT_LEG_LENGTH, SEGMENTS, HexapodDesign
from hexaleg.design_file import GAIT, REQUIREMENTS, DesignFile, read_design_file
from hexaleg.evaluation.requirements import Requirements
from hexaleg.gait.defaults import default_gait
from hexaleg.gait.spec import Gait
from hexaleg.layouts import LEG_NAMES
from hexaleg.leg_geometry import SEGMENT_NAMES
from hexaleg.robot.recipe import RobotSource, SegmentLength
from hexaleg.robot.robot import Robot
from hexaleg.robot.robot_table import table_source

if TYPE_CHECKING:
    from hexaleg.structure.sizing import SizedStructure

__all__ = ["Inputs", "design_from_args", "inputs_from_args", "study_total"]

READING_OPTIONS = ("xacro_arg", "package", "foot_frame", "foot_offset", "lock_joint")
"""How a robot file is read: options that need one."""


@dataclass(frozen=True)
class Inputs:
    """What the design options and the ``--design`` file resolve to.

    Attributes:
        robot: The robot to analyse, built once (its tubes sized if asked).
        written: The file's ``[requirements]`` as written (none given: nothing required),
            walking the file's ``[gait]`` over :class:`~hexaleg.gait.spec.Gait`'s defaults.
        file: The ``--design`` file as read, if one was given.
        sized: How the tubes were sized, where the file's ``[structure]`` asked and the
            command measures them.

    """

    robot: Robot
    written: Requirements
    file: DesignFile | None = None
    sized: SizedStructure | None = None

    @property
    def design(self) -> HexapodDesign:
        """The robot's design."""
        return self.robot.design

    @cached_property
    def default_gait(self) -> Gait:
        """The gait the robot walks without a ``[gait]`` table, found once.

        :class:`Gait`'s defaults for hexaleg's template; a robot file's own, scaled to its
        legs (:func:`~hexaleg.gait.defaults.default_gait`).
        """
        return default_gait(self.robot.model)

    @cached_property
    def gait(self) -> Gait:
        """The gait walked: the file's ``[gait]`` keys over :attr:`default_gait`."""
        base = self.default_gait
        if self.file is None:
            return base
        if base == Gait():  # the file's [gait] over Gait()'s, as read already
            return self.written.walked
        return self.file.table(GAIT, lambda table: Gait.from_table(table, base))

    @property
    def gait_given(self) -> bool:
        """Whether the design file gives a ``[gait]`` table."""
        return self.file is not None and GAIT in self.file.data

    @cached_property
    def requirements(self) -> Requirements:
        """The file's requirements, walking :attr:`gait`."""
        return self.written.walking(self.gait)


def inputs_from_args(args: argparse.Namespace, *, size: bool = False) -> Inputs:
    """The robot, requirements and gait that the design options and ``--design`` describe.

    The file is read once, and every command reads it the same way: a bad
    ``[requirements]`` or ``[gait]`` table, or a ``[structure]`` on a robot file whose links
    are its own, is refused by a command that does not use it too.

    Args:
        args: The parsed options.
        size: Size the legs' tubes first where the file's ``[structure]`` says
            ``size = true`` (the commands that measure the tubes), for the file's required
            payload and slope.

    Raises:
        HexalegError: A bad option, design file or robot file, in one line.

    """
    path = getattr(args, "design", None)
    file = None if path is None else read_design_file(path)
    base = HexapodDesign() if file is None else file.design()
    requirements = (
        Requirements() if file is None else file.table(REQUIREMENTS, Requirements.from_table)
    )
    if file is not None:
        requirements = requirements.walking(file.table(GAIT, Gait.from_table))
    source = _source(args, file)
    design = _design(args, base, source)
    robot = Robot.build(source, design)
    if design.structure is not None and not robot.design_links:
        raise UsageError(IMPORTED)
    robot = pose_if_asked(args, robot, requirements)  # --best-posture: tubes sized as it stands
    sized = None
    if size:
        sized_design, sized = size_if_asked(robot.design, requirements)
        if sized is not None:
            robot = Robot.build(source, sized_design)
    table = None if file is None or getattr(args, "urdf", None) else file.robot_table()
    if table is not None and file is not None:
        given = {name for name in SEGMENTS if getattr(args, name, None) is not None}
        robot.check_written_lengths(file.data, given, str(file.path))
    return Inputs(robot, requirements, file, sized)


def design_from_args(args: argparse.Namespace) -> HexapodDesign:
    """The design the options describe (validated): :func:`inputs_from_args`' robot's."""
    return inputs_from_args(args).design


def _design(args: argparse.Namespace, base: HexapodDesign, source: RobotSource) -> HexapodDesign:
    """The design the options set over ``base``: a robot file's segments go to its source."""
    changes: dict[str, Any] = {
        name: _value(getattr(args, name))
        for name in DESIGN_FLAGS
        if getattr(args, name, None) is not None
    }
    path = getattr(args, "design", None)
    if getattr(args, "ratios", None) is not None:
        given = [f"--{n}" for n in SEGMENTS if getattr(args, n) is not None]
        if given:
            raise UsageError(f"--ratios cannot be combined with {', '.join(given)}")
        if source.path is not None:
            raise UsageError("--ratios with --urdf: give --l1 --l2 --l3 to change the segments")
        total = study_total(args, base)
        design = base.replace(**changes).with_ratios(args.ratios[0], args.ratios[1], total)
        if args.total is None and path is None:  # said once the design stands: errors stay 1 line
            note(f"--ratios without --total: total leg length {DEFAULT_LEG_LENGTH:g} m")
        return design
    if getattr(args, "total", None) is not None and hasattr(args, "ratios"):
        raise UsageError("--total only applies together with --ratios")
    if source.path is None:  # a robot file's --l1 --l2 --l3 change its file (_source)
        changes |= {n: getattr(args, n) for n in SEGMENTS if getattr(args, n, None) is not None}
    return base.replace(**changes) if changes else base


def _source(args: argparse.Namespace, file: DesignFile | None) -> RobotSource:
    """The robot file and how it is read: the command line's over the ``[robot]`` table's."""
    urdf = getattr(args, "urdf", None)
    table = None if file is None or urdf is not None else file.robot_table()
    if urdf is None and table is None:
        given = [name for name in READING_OPTIONS if getattr(args, name, None)]
        if given:
            flag = "--" + given[0].replace("_", "-")
            raise UsageError(f"{flag} only applies together with --urdf FILE")
        return RobotSource()
    if table is not None and file is not None:
        base = table_source(table, file.folder, str(file.path))
    else:
        base = RobotSource(str(urdf))
    xacro_args = _pairs(args.xacro_arg, ":=", "--xacro-arg", "NAME:=VALUE")
    packages = _pairs(args.package, "=", "--package", "NAME=DIR")
    offset = base.foot_offset if args.foot_offset is None else tuple(args.foot_offset)
    return RobotSource(
        base.path,
        (*base.xacro_args, *xacro_args.items()),
        (*base.packages, *packages.items()),
        offset,
        base.foot_frame if args.foot_frame is None else args.foot_frame,
        _segments(args, base.segments),
        (*base.lock, *args.lock_joint),
    )


def _segments(
    args: argparse.Namespace, written: tuple[SegmentLength, ...]
) -> tuple[SegmentLength, ...]:
    """The file's ``[robot.segments]``, then ``--l1 --l2 --l3`` on every leg over them."""
    segments = {(s.leg, s.segment): s for s in written}
    for flag, segment in zip(SEGMENTS, SEGMENT_NAMES, strict=True):
        given = getattr(args, flag, None)
        if given is not None:
            for leg in LEG_NAMES:
                segments[leg, segment] = SegmentLength(leg, segment, float(given), f"--{flag}")
    return tuple(segments.values())


def _pairs(given: list[str], separator: str, flag: str, form: str) -> dict[str, str]:
    pairs = {}
    for text in given:
        name, found, value = text.partition(separator)
        if not found or not name or not value:
            raise UsageError(f"{flag} {text!r}: expected {form}")
        pairs[name] = value
    return pairs


def _value(given: Any) -> Any:
    """An option's value as the design takes it: a list of numbers becomes a tuple."""
    return tuple(given) if isinstance(given, list) else given


def study_total(args: argparse.Namespace, design: HexapodDesign) -> float:
    """Total leg length [m]: ``--total``, else the ``--design`` file's, else the default."""
    if args.total is not None:
        return float(args.total)
    return design.leg_length if getattr(args, "design", None) else DEFAULT_LEG_LENGTH
