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

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from hexaleg._checks import require_in_range
from hexaleg.design import SEGMENT_RANGE, SEGMENTS
from hexaleg.design_file import ROBOT, DesignFileError
from hexaleg.exceptions import ParameterError
from hexaleg.layouts import LEG_NAMES
from hexaleg.leg_geometry import SEGMENT_NAMES
from hexaleg.robot.imported import ImportedRobot
from hexaleg.robot.recipe import RobotSource, SegmentLength
from hexaleg.robot.resize import SAME_LENGTH
from hexaleg.robot.robot_design import robot_record
from hexaleg.table_records import require_table

__all__ = [
    "LOCK_KEY",
    "SEGMENTS_TABLE",
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
        DesignFileError: No ``urdf``, or tables that are not of text.
        ParameterError: A bad foot offset or ``[robot.segments]`` key or length.

    """
    try:
        xacro_args = {str(k): str(v) for k, v in dict(table.get("xacro_args", {})).items()}
        packages = {
            str(k): str(folder / str(v)) for k, v in dict(table.get("packages", {})).items()
        }
        urdf = (folder / str(table["urdf"])).resolve()
    except (KeyError, TypeError, ValueError):
        raise DesignFileError(f"{where}: [robot] needs urdf = FILE (and tables of text)") from None
    offset = table.get("foot_offset")
    if offset is not None:
        offset = _foot_offset(offset)
    frame = table.get("foot_frame")
    if frame is not None and not isinstance(frame, str):
        raise ParameterError(f"{ROBOT}.foot_frame", frame, "must be a glob pattern (text)")
    segments = segment_lengths(table)
    return RobotSource.of(
        str(urdf), xacro_args, packages, offset, frame, segments, lock_patterns(table, where)
    )


def lock_patterns(table: Mapping[str, Any], where: str) -> tuple[str, ...]:
    """``[robot] lock_joints``: the joints held at their zero (glob patterns).

    Raises:
        DesignFileError: Not a list of joint names.

    """
    saved = table.get(LOCK_KEY, [])
    if not isinstance(saved, list) or not all(isinstance(p, str) and p for p in saved):
        raise DesignFileError(f"{where}: [{ROBOT}] {LOCK_KEY} must be a list of joint names")
    return tuple(saved)


def _foot_offset(value: Any) -> tuple[float, float, float]:
    """``[robot] foot_offset``: three numbers [m]."""
    if (
        not isinstance(value, list | tuple)
        or len(value) != 3
        or not all(isinstance(v, int | float) and not isinstance(v, bool) for v in value)
    ):
        raise ParameterError(f"{ROBOT}.foot_offset", value, "must be three numbers X, Y, Z [m]")
    x, y, z = (float(v) for v in value)
    return (x, y, z)


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
