"""A design file's ``[robot]`` table: the imported robot that ``hexaleg design import`` wrote.

Besides the file and its reading options, ``[robot.segments]`` changes the robot's
segments along their own lines (:mod:`hexaleg.robot.resize`), for every leg or per leg::

    [robot.segments]
    femur = 0.08        # every leg's femur [m]
    [robot.segments.lf]
    tibia = 0.1         # leg lf's tibia [m]
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any

from hexaleg._checks import require_in_range
from hexaleg.design import SEGMENT_RANGE
from hexaleg.design_file import ROBOT, DesignFileError, read_design_text
from hexaleg.exceptions import ParameterError
from hexaleg.layouts import LEG_NAMES
from hexaleg.leg_geometry import SEGMENT_NAMES
from hexaleg.table_records import require_table

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib


def load_robot_table(path: str | os.PathLike[str]) -> dict[str, Any] | None:
    """A TOML design file's ``[robot]`` table, or ``None`` if it has none (or is JSON)."""
    table = _toml(path).get(ROBOT)
    if table is not None and not isinstance(table, dict):
        raise DesignFileError(f"{path}: robot must be a [robot] table")
    return table


def file_segments(path: str | os.PathLike[str]) -> dict[str, Any]:
    """The design file's own ``l1``, ``l2``, ``l3`` (those it gives), as written."""
    data = _toml(path)
    return {key: data[key] for key in ("l1", "l2", "l3") if key in data}


def _toml(path: str | os.PathLike[str]) -> dict[str, Any]:
    """A TOML design file's contents; empty if it is JSON or unreadable as TOML."""
    path = Path(path)
    if path.suffix.lower() != ".toml":
        return {}
    try:
        return tomllib.loads(read_design_text(path))
    except (tomllib.TOMLDecodeError, ValueError, RecursionError):
        return {}  # the design's own reading reports it


SEGMENTS_TABLE = "segments"
"""``[robot.segments]``: segment lengths changed from the robot file's (``coxa``, ``femur``,
``tibia`` [m]) for every leg, or per leg in ``[robot.segments.<leg>]``."""


def segment_lengths(table: dict[str, Any]) -> dict[str, dict[str, tuple[float, str]]]:
    """The ``[robot.segments]`` lengths by leg, then segment: (length [m], the key's name).

    A segment given for every leg is overridden by the same segment given for one leg.

    Raises:
        ParameterError: A key that is no segment or leg, or a length out of its range.

    """
    segments = table.get(SEGMENTS_TABLE)
    if segments is None:
        return {}
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
    return {leg: {**every, **legs.get(leg, {})} for leg in LEG_NAMES if every or leg in legs}


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
