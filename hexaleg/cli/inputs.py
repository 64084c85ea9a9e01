"""A command's design options, parsed into what resolves them: the design, the robot file.

The ``--design`` file is read and parsed once (:func:`~hexaleg.design_file.read_design_file`);
the options given beside it set design fields over its design, and say which robot file to
read and how (``--urdf FILE`` and its reading options over the file's ``[robot]`` table);
the commands that offer ``--best-posture`` pass how the robot then stands
(:func:`~hexaleg.cli.best_posture.posing`: the search is theirs to import). What they
resolve to, the robot built once with its requirements and gait, is
:func:`hexaleg.evaluation.inputs.resolve_inputs`' to say; this module only parses.
"""

from __future__ import annotations

import argparse
from typing import Any

from hexaleg.cli.options import DESIGN_FLAGS, UsageError, note
from hexaleg.design import DEFAULT_LEG_LENGTH, SEGMENTS, HexapodDesign
from hexaleg.design_file import DesignFile, read_design_file
from hexaleg.evaluation.inputs import Inputs, Posing, Sizing, resolve_inputs
from hexaleg.layouts import LEG_NAMES
from hexaleg.leg_geometry import SEGMENT_NAMES
from hexaleg.robot.recipe import RobotSource, SegmentLength
from hexaleg.robot.robot_table import table_source

__all__ = ["Inputs", "design_from_args", "inputs_from_args", "study_total"]

READING_OPTIONS = ("xacro_arg", "package", "foot_frame", "foot_offset", "lock_joint")
"""How a robot file is read: options that need one."""


def inputs_from_args(
    args: argparse.Namespace, *, posing: Posing | None = None, sizing: Sizing | None = None
) -> Inputs:
    """The robot, requirements and gait that the design options and ``--design`` describe.

    Args:
        args: The parsed options.
        posing: How the robot stands before it is sized, for a command with
            ``--best-posture`` (:func:`~hexaleg.cli.best_posture.posing`); ``None``: as
            designed.
        sizing: How a command that measures the legs' tubes sizes them first, where the
            file's ``[structure]`` says ``size = true``
            (:func:`~hexaleg.evaluation.sizing.sized_for`).

    Raises:
        HexalegError: A bad option, design file or robot file, in one line.

    """
    path = getattr(args, "design", None)
    file = None if path is None else read_design_file(path)
    base = HexapodDesign() if file is None else file.design()
    source = _source(args, file)
    given = _given(args)
    design = _design(args, base, source, given)
    of_file = file is not None and source.path is not None and getattr(args, "urdf", None) is None
    return resolve_inputs(
        design, source, file, given=given, robot_of_file=of_file, posing=posing, sizing=sizing
    )


def design_from_args(args: argparse.Namespace) -> HexapodDesign:
    """The design the options describe (validated): :func:`inputs_from_args`' robot's."""
    return inputs_from_args(args).design


def _given(args: argparse.Namespace) -> dict[str, Any]:
    """The design fields the options set, with their values (a list of numbers a tuple)."""
    names = (*SEGMENTS, *DESIGN_FLAGS)
    return {
        name: _value(getattr(args, name)) for name in names if getattr(args, name, None) is not None
    }


def _design(
    args: argparse.Namespace, base: HexapodDesign, source: RobotSource, given: dict[str, Any]
) -> HexapodDesign:
    """The design the options set over ``base``: a robot file's segments go to its source."""
    changes = {name: value for name, value in given.items() if name not in SEGMENTS}
    path = getattr(args, "design", None)
    if getattr(args, "ratios", None) is not None:
        typed = [f"--{n}" for n in SEGMENTS if n in given]
        if typed:
            raise UsageError(f"--ratios cannot be combined with {', '.join(typed)}")
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
        changes |= {name: value for name, value in given.items() if name in SEGMENTS}
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
