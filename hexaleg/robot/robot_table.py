"""A design file's ``[robot]`` table: the robot file it names, read and written.

``hexaleg design import`` writes the table: the robot file and its package folders
relative to the design file's folder, the Xacro arguments and foot options, and what was
read (``[robot.read]``, for reference only). :func:`table_source` reads it back as a
:class:`~hexaleg.robot.recipe.RobotSource`. Besides the file and its reading options,
``lock_joints`` holds joints of the file at their zero (a sensor's, a tool's: glob
patterns), and ``[robot.segments]`` changes the robot's segments along their own lines
(:mod:`hexaleg.robot.resize`), for every leg or per leg::

    [robot.segments]
    femur = 0.08        # every leg's femur [m]
    [robot.segments.lf]
    tibia = 0.1         # leg lf's tibia [m]
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from hexaleg._checks import require_in_range
from hexaleg.design import SEGMENT_RANGE, SEGMENTS, HexapodDesign
from hexaleg.design_file import ROBOT, DesignFile, DesignFileError
from hexaleg.exceptions import ParameterError, shorten
from hexaleg.layouts import LEG_NAMES
from hexaleg.leg_geometry import SEGMENT_NAMES
from hexaleg.robot.imported import ImportedRobot
from hexaleg.robot.recipe import RobotSource, SegmentLength, foot_offset_of
from hexaleg.robot.resize import SAME_LENGTH
from hexaleg.robot.robot_design import robot_record
from hexaleg.table_records import require_table

__all__ = [
    "LOCK_KEY",
    "SEGMENTS_TABLE",
    "check_written_fixed",
    "check_written_lengths",
    "lock_patterns",
    "robot_table",
    "table_source",
]

LOCK_KEY = "lock_joints"
"""A ``[robot]`` table's list of joints (glob patterns) held at their zero as fixed joints."""

SEGMENTS_TABLE = "segments"
"""``[robot.segments]``: segment lengths changed from the robot file's (``coxa``, ``femur``,
``tibia`` [m]) for every leg, or per leg in ``[robot.segments.<leg>]``."""


def table_source(table: Mapping[str, Any], folder: Path, where: str) -> RobotSource:
    """The robot a ``[robot]`` table names, its paths relative to the design file's ``folder``.

    Args:
        table: The ``[robot]`` table.
        folder: The design file's folder.
        where: The design file, as errors name it.

    Raises:
        DesignFileError: No ``urdf``.
        ParameterError: Naming the key: a ``urdf`` that is no path, ``xacro_args`` or
            ``packages`` that are no tables of text, a bad foot offset or frame, or a bad
            ``[robot.segments]`` key or length.

    """
    urdf = table.get("urdf")
    if urdf is None:
        raise DesignFileError(f"{where}: [robot] needs urdf = FILE, the robot file")
    if not isinstance(urdf, str) or not urdf:
        raise ParameterError(f"{ROBOT}.urdf", urdf, "must be the robot file's path (text)")
    xacro_args = _text_table(table, "xacro_args", "NAME = VALUE")
    packages = {
        k: str(folder / v) for k, v in _text_table(table, "packages", "NAME = FOLDER").items()
    }
    offset = table.get("foot_offset")
    if offset is not None:
        offset = foot_offset_of(offset, f"{ROBOT}.foot_offset")
    frame = table.get("foot_frame")
    if frame is not None and not isinstance(frame, str):
        raise ParameterError(f"{ROBOT}.foot_frame", frame, "must be a glob pattern (text)")
    segments = segment_lengths(table)
    try:
        path = (folder / urdf).resolve()
    except (OSError, ValueError):  # a NUL in the path, a loop of links
        raise ParameterError(f"{ROBOT}.urdf", urdf, "must be the robot file's path") from None
    return RobotSource.of(
        str(path), xacro_args, packages, offset, frame, segments, lock_patterns(table, where)
    )


def _text_table(table: Mapping[str, Any], key: str, form: str) -> dict[str, str]:
    """``[robot.<key>]``: names to text (a number is taken as its text), else refused."""
    given = table.get(key, {})
    if not isinstance(given, dict):
        raise ParameterError(f"{ROBOT}.{key}", given, f"must be a table of {form}")
    for name, value in given.items():
        if isinstance(value, bool) or not isinstance(value, str | int | float):
            raise ParameterError(f"{ROBOT}.{key}.{name}", value, f"must be text: {form}")
    return {str(name): str(value) for name, value in given.items()}


def lock_patterns(table: Mapping[str, Any], where: str) -> tuple[str, ...]:
    """``[robot] lock_joints``: the joints held at their zero (glob patterns).

    Raises:
        DesignFileError: Not a list of joint names.

    """
    saved = table.get(LOCK_KEY, [])
    if not isinstance(saved, list) or not all(isinstance(p, str) and p for p in saved):
        raise DesignFileError(f"{where}: [{ROBOT}] {LOCK_KEY} must be a list of joint names")
    return tuple(saved)


def segment_lengths(table: Mapping[str, Any]) -> tuple[SegmentLength, ...]:
    """The ``[robot.segments]`` lengths, per leg and segment, each naming its key.

    A segment given for every leg is overridden by the same segment given for one leg.

    Raises:
        ParameterError: A key that is no segment or leg, or a length out of its range.

    """
    segments = table.get(SEGMENTS_TABLE)
    if segments is None:
        return ()
    where = f"{ROBOT}.{SEGMENTS_TABLE}"
    segments = require_table(where, segments, "segment lengths [m] and leg tables")
    every: dict[str, tuple[float, str]] = {}
    legs: dict[str, dict[str, tuple[float, str]]] = {}
    for key, value in segments.items():
        if key in SEGMENT_NAMES:
            every[key] = (_length(f"{where}.{key}", value), f"{where}.{key}")
        elif key in LEG_NAMES:
            table_ = require_table(f"{where}.{key}", value, "segment lengths [m]")
            legs[key] = {
                s: (_length(f"{where}.{key}.{s}", v), f"{where}.{key}.{s}")
                for s, v in table_.items()
            }
        else:
            known = ", ".join((*SEGMENT_NAMES, *LEG_NAMES))
            raise ParameterError(f"{where}.{key}", value, f"known keys: {known}")
    return tuple(
        SegmentLength(leg, segment, length, given_as)
        for leg in LEG_NAMES
        for segment, (length, given_as) in {**every, **legs.get(leg, {})}.items()
    )


def _length(field: str, value: Any) -> float:
    """A segment length [m] in its range; a key that is no segment is refused by the caller."""
    segment = field.rsplit(".", 1)[1]
    if segment not in SEGMENT_NAMES:
        raise ParameterError(field, value, f"a leg's segments are {', '.join(SEGMENT_NAMES)}")
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ParameterError(
            field, value, f"must be a length in [{SEGMENT_RANGE[0]:g}, {SEGMENT_RANGE[1]:g}] [m]"
        )
    return require_in_range(field, float(value), *SEGMENT_RANGE, "m")


def check_written_lengths(
    lengths: tuple[float, float, float],
    written: Mapping[str, Any],
    overridden: set[str],
    where: str,
) -> None:
    """Refuse a design file whose ``l1 l2 l3`` were edited: a ``[robot]``'s are its file's.

    Args:
        lengths: The robot file's own first leg's coxa, femur and tibia [m].
        written: The design file's own top-level keys.
        overridden: The segments (``l2``) the command line sets itself.
        where: The design file, as errors name it.

    Raises:
        DesignFileError: Naming the key, its value and the robot file's length.

    """
    for name, segment, own in zip(SEGMENTS, SEGMENT_NAMES, lengths, strict=True):
        value = written.get(name)
        if name in overridden or isinstance(value, bool) or not isinstance(value, int | float):
            continue
        if abs(value - own) > SAME_LENGTH:
            raise DesignFileError(
                f"{where}: {name} = {value:g} is not the robot file's {segment} "
                f"({own:.6g} m): an imported robot's segments are read from its file; "
                f"change them in [robot.segments] or with --{name}"
            )


SAME_NUMBER = 1e-9
"""Numbers of a design file this close to the robot file's are its file's [m or rad]."""


def check_written_fixed(
    reference: HexapodDesign, file: DesignFile, fixed: Iterable[str], why: str
) -> None:
    """Refuse a design file of a robot file whose keys the robot file fixes were edited.

    ``design import`` writes every field, those the robot file fixes (its body, mounts,
    stance limits) at the file's values; a robot file never takes them from the design
    file, so a value other than the file's would be silently ignored.

    Args:
        reference: The robot file's design over hexaleg's defaults (what import writes).
        file: The design file.
        fixed: The design fields the robot file fixes.
        why: What the refusal says of them.

    Raises:
        DesignFileError: Naming the key as written, its value and the robot file's.

    """
    written = file.design()
    for name in fixed:
        written_as = ("mount",) if name == "mounts" else (name, f"{name}_deg")  # [[mount]]
        keys = [key for key in written_as if key in file.data]
        if keys and not _same(getattr(written, name), getattr(reference, name)):
            own = getattr(reference, name)
            theirs = f" ({own:.6g})" if isinstance(own, float) else ""
            raise DesignFileError(
                f"{file.path}: {keys[0]} = {shorten(file.data[keys[0]])} is not the robot "
                f"file's{theirs}: {why}; remove it from the design file"
            )


def _same(value: Any, other: Any) -> bool:
    """Equal, numbers within :data:`SAME_NUMBER` (a file written on another machine)."""
    if isinstance(value, float) and isinstance(other, float):
        return math.isclose(value, other, rel_tol=SAME_NUMBER, abs_tol=SAME_NUMBER)
    if isinstance(value, tuple) and isinstance(other, tuple):
        return len(value) == len(other) and all(map(_same, value, other))
    if dataclasses.is_dataclass(value) and type(value) is type(other):
        return all(
            _same(getattr(value, f.name), getattr(other, f.name)) for f in dataclasses.fields(value)
        )
    return bool(value == other)


def robot_table(source: RobotSource, robot: ImportedRobot, at: Path | None) -> dict[str, Any]:
    """The ``[robot]`` table of a design file at ``at`` that reads ``robot`` back.

    The robot file and the package folders relative to ``at``'s folder (absolute without
    ``at``), the Xacro arguments and foot options, and what was read (``read``, for
    reference only). Its ``segments`` are the caller's to add.
    """

    def where(path: str) -> str:
        found = os.path.abspath(path)
        return found if at is None else os.path.relpath(found, at.resolve().parent)

    assert source.path is not None, "hexaleg's template has no [robot] table"
    written: dict[str, Any] = {
        "urdf": where(source.path),
        "xacro_args": dict(source.xacro_args),
        "packages": {name: where(path) for name, path in source.packages},
    }
    if source.foot_frame is not None:
        written["foot_frame"] = source.foot_frame
    if source.foot_offset is not None:
        written["foot_offset"] = list(source.foot_offset)
    if source.lock:
        written[LOCK_KEY] = list(source.lock)
    record = robot_record(robot)
    written["read"] = _toml_ready({k: v for k, v in record.items() if k != "source"})
    return written


def _toml_ready(value: Any) -> Any:
    """``value`` with every ``None`` (an unbounded limit, a rating not given) as "none"."""
    if isinstance(value, dict):
        return {k: _toml_ready(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_toml_ready(v) for v in value]
    return "none" if value is None else value
