"""Design files: a :class:`~hexaleg.design.HexapodDesign` kept in TOML (or JSON) in version control.

TOML is the designer's format: every field of the design, SI units and radians, each
key commented with its unit; an angle may be given in degrees instead under the same
key with ``_deg`` appended (``first_leg_angle_deg = 30``). JSON is the ``design`` object
of any hexaleg JSON output (or the whole output), so a result can be reproduced from
what it printed. The extension tells them apart.

A file is read whole and checked key by key: an unknown key, a value of the wrong type
or out of its range is refused with a :class:`DesignFileError` that names the file, the
line (where it can be found) and the key.
"""

from __future__ import annotations

import difflib
import json
import math
import os
import re
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar, cast

from hexaleg._checks import require_finite
from hexaleg._input import read_input_file
from hexaleg.actuators import Actuators
from hexaleg.battery import Battery
from hexaleg.design import DESIGN_FIELDS, HexapodDesign, LegMount
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.field_spec import FieldSpec
from hexaleg.leg_structure import Structure
from hexaleg.limits import JOINT_NAMES, JointLimits

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

T = TypeVar("T")

SUFFIXES = (".toml", ".json")
"""Extensions of design files: TOML written by hand, JSON printed by hexaleg."""

MAX_FILE_BYTES = 16 * 2**20
"""Largest design file read [bytes]: a hand-written design is a few kB, a whole hexaleg
JSON output (a study's table included) well under this."""

DEGREES_SUFFIX = "_deg"

_DEFAULT = HexapodDesign()

FIELDS: dict[str, FieldSpec] = {spec.key: spec for spec in DESIGN_FIELDS}
"""Every design field by its key in a file."""

SCALARS: dict[str, str] = {k: s.described for k, s in FIELDS.items() if s.kind == "number"}
"""Every number-valued key with its comment (unit in brackets)."""

TRIPLES: dict[str, str] = {k: s.described for k, s in FIELDS.items() if s.kind == "triple"}
"""Keys holding three numbers."""

LIMIT_SETS: dict[str, str] = {k: s.described for k, s in FIELDS.items() if s.kind == "limits"}
"""Joint-limit tables: theta1, theta2, theta3 (lower and upper bound [rad]), coupled_knee, name."""

MOUNT_KEYS: dict[str, str] = {
    "name": "leg name: a lower-case identifier",
    "x": "forward [m]",
    "y": "left [m]",
    "z": "up [m] (the same for every leg)",
    "yaw": "coxa direction at θ1 = 0 [rad]",
}

ANGLES = {k for k, s in FIELDS.items() if s.angle} | {*JOINT_NAMES, "yaw"}
"""Keys that are angles [rad]: each also accepted in degrees as ``<key>_deg``."""

RECORDS: dict[str, Callable[[Any], Any]] = {
    "actuators": Actuators.from_table,
    "battery": Battery.from_table,
    "structure": Structure.from_table,
}
"""How each table of its own keys is read (``[actuators.root]``, ``[battery]``, ``[structure]``)."""

REQUIREMENTS = "requirements"
"""The table of what the robot must do: handed over as it is, read by
:meth:`hexaleg.evaluation.requirements.Requirements.from_table`."""

ROBOT = "robot"
"""An imported robot's table (``hexaleg design import``), read by the commands that take one."""

GAIT = "gait"
"""The gait table: read by :meth:`hexaleg.gait.spec.Gait.from_table` (:func:`load_table`)."""

TOP_KEYS = (*FIELDS, "mount", REQUIREMENTS, ROBOT, GAIT)
"""Keys of a design file: every field's, ``mount`` for the ``[[mount]]`` tables, the
``[requirements]`` and the ``[robot]`` tables."""


class DesignFileError(HexalegError):
    """A design file that cannot be read, or that describes no valid design."""


class UnknownKeyError(ParameterError):
    """A key that no design field has (a typo, most often)."""

    def __init__(self, field: str, hint: str) -> None:
        super().__init__(field, None, hint)
        self.args = (f"unknown key {field!r}: {hint}",)

    def __str__(self) -> str:
        return str(self.args[0])

    def __reduce__(self) -> tuple[Any, ...]:
        return (type(self), (self.field, self.allowed))


# -- reading ------------------------------------------------------------------------------


@dataclass(frozen=True)
class DesignFile:
    """A design file as read and parsed, once: its design and its tables as written.

    Attributes:
        path: The file.
        text: Its text (errors name the line of a key in it).
        is_json: Whether it is JSON (a hexaleg output's ``design``) rather than TOML.
        data: Its table of design keys and tables, as parsed.

    """

    path: Path
    text: str
    is_json: bool
    data: Mapping[str, Any]

    @property
    def folder(self) -> Path:
        """The folder of the file, where the paths it gives start."""
        return self.path.parent

    def design(self) -> HexapodDesign:
        """The design it describes (validated).

        Raises:
            DesignFileError: naming the file, the line where it can be found and the key.

        """
        try:
            return design_from_mapping(self.data)
        except ParameterError as err:
            raise self._located(err) from None

    def table(self, name: str, read: Callable[[Mapping[str, Any]], T]) -> T:
        """Its table ``name`` as ``read`` reads it (an empty table if it has none).

        Raises:
            DesignFileError: The table is no table; naming the line and the key ``read``
                refused (a :class:`~hexaleg.exceptions.ParameterError` it raises).

        """
        try:
            table = self.data.get(name, {})
            if not isinstance(table, dict):
                raise ParameterError(name, table, f"must be a [{name}] table")
            return read(table)
        except ParameterError as err:
            raise self._located(err) from None

    def robot_table(self) -> Mapping[str, Any] | None:
        """Its ``[robot]`` table (the robot file it was imported from), ``None`` if it has none.

        Raises:
            DesignFileError: ``robot`` that is no table.

        """
        table = self.data.get(ROBOT)
        if table is not None and not isinstance(table, dict):
            raise DesignFileError(f"{self.path}: robot must be a [robot] table")
        return table

    def _located(self, err: ParameterError) -> DesignFileError:
        line = _line_of(self.text, err.field, self.is_json)
        where = f"{self.path}, line {line}" if line else str(self.path)
        return DesignFileError(f"{where}: {err}")


def read_design_file(path: str | os.PathLike[str]) -> DesignFile:
    """The design file at ``path``, read and parsed (its design is checked when asked for).

    Raises:
        DesignFileError: A file that is not ``.toml`` or ``.json``, cannot be read or is not
            valid TOML or JSON, naming the file (and the line).

    """
    path = Path(path)
    if path.suffix.lower() not in SUFFIXES:
        raise DesignFileError(f"--design {path}: the file must end in .toml or .json")
    text = read_design_text(path)
    json_file = path.suffix.lower() == ".json"
    try:
        data = json.loads(text) if json_file else tomllib.loads(text)
    except json.JSONDecodeError as err:
        raise DesignFileError(f"{path}, line {err.lineno}: not valid JSON ({err.msg})") from None
    except tomllib.TOMLDecodeError as err:
        raise DesignFileError(f"{path}: not valid TOML ({err})") from None
    except RecursionError:
        raise DesignFileError(f"{path}: values nested too deeply to be a design") from None
    except ValueError as err:  # an integer of thousands of digits
        raise DesignFileError(f"{path}: {_first_sentence(err)}") from None
    if json_file:
        data = _printed_design(data)
    if not isinstance(data, dict):
        raise DesignFileError(f"{path}: expected a table of design keys, got {type(data).__name__}")
    return DesignFile(path, text, json_file, data)


def load_design(path: str | os.PathLike[str]) -> HexapodDesign:
    """The design a TOML or JSON design file describes (validated).

    Raises:
        DesignFileError: naming the file, the line where it can be found and the key.

    """
    return read_design_file(path).design()


def load_design_file(
    path: str | os.PathLike[str], read_requirements: Callable[[Mapping[str, Any]], T]
) -> tuple[HexapodDesign, T]:
    """The design a design file describes, and its ``[requirements]`` table as read.

    Args:
        path: The TOML or JSON design file.
        read_requirements: Reads the table (empty if the file has none); a
            :class:`~hexaleg.exceptions.ParameterError` it raises is reported with the file
            and line like the design's own.

    Raises:
        DesignFileError: naming the file, the line where it can be found and the key.

    """
    file = read_design_file(path)
    return file.design(), file.table(REQUIREMENTS, read_requirements)


def load_table(
    path: str | os.PathLike[str], name: str, read: Callable[[Mapping[str, Any]], T]
) -> T:
    """Table ``name`` of a design file as ``read`` reads it (an empty table if it has none).

    Raises:
        DesignFileError: naming the file, the line and the key ``read`` refused.

    """
    return read_design_file(path).table(name, read)


def _printed_design(data: object) -> object:
    """The design a hexaleg JSON output holds: its ``design``, or ``decide``'s ``best`` one."""
    if isinstance(data, dict):
        if isinstance(data.get("design"), dict):
            return data["design"]  # a whole hexaleg JSON output
        best = data.get("best")
        if isinstance(best, dict) and isinstance(best.get("design"), dict):
            return best["design"]  # decide's answer
    return data


def read_design_text(path: Path) -> str:
    """The text of a regular file of at most :data:`MAX_FILE_BYTES`; never opens a FIFO."""
    data = read_input_file(path, MAX_FILE_BYTES, f"--design {path}", DesignFileError)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise DesignFileError(f"--design {path}: cannot read it ({_reason(err)})") from None


def _first_sentence(err: Exception) -> str:
    return str(err).split(";")[0].split(": value has")[0]


def design_from_mapping(data: Mapping[str, Any]) -> HexapodDesign:
    """The design of a mapping of design keys (a parsed TOML file or a JSON ``design``)."""
    data = _radians({k: v for k, v in data.items() if k not in (REQUIREMENTS, ROBOT, GAIT)}, "")
    unknown = [key for key in data if key not in TOP_KEYS]
    if unknown:
        raise _unknown(unknown[0], TOP_KEYS, "")
    if "mount" in data and "mounts" in data:
        raise ParameterError("mount", "given twice", "give the mounts as [[mount]] or mounts, once")
    kwargs: dict[str, Any] = {}
    for key, value in data.items():
        kind = "mounts" if key == "mount" else FIELDS[key].kind
        if kind == "number":
            kwargs[key] = _number(key, value, FIELDS[key].unit)
        elif kind == "triple" and value is None and FIELDS[key].optional:
            kwargs[key] = None  # JSON's null: not given (a robot file's rating)
        elif kind == "triple":
            kwargs[key] = _numbers(key, value, FIELDS[key].items, FIELDS[key].unit)
        elif kind == "limits":
            kwargs[key] = _limits(key, value)
        elif kind == "mounts":
            kwargs["mounts"] = _mounts(key, value)
        elif kind == "record":
            kwargs[key] = None if value is None else RECORDS[key](value)  # JSON's null: none
        else:
            kwargs[key] = value  # HexapodDesign names the choices it knows
    design = HexapodDesign(**kwargs)
    for key in ("rated_torques", "rated_speeds") if design.actuators is not None else ():
        given, derived = kwargs.get(key, getattr(design, key)), getattr(design, key)
        if not all(math.isclose(a, b, rel_tol=1e-9) for a, b in zip(given, derived, strict=True)):
            raise ParameterError(key, list(given), "comes from [actuators] when they are given")
    return design


def _radians(table: Mapping[str, Any], prefix: str) -> dict[str, Any]:
    """``table`` with every ``<angle>_deg`` key turned into ``<angle>`` in radians."""
    out: dict[str, Any] = {}
    for key, value in table.items():
        if not key.endswith(DEGREES_SUFFIX):
            out[key] = value
            continue
        base = key[: -len(DEGREES_SUFFIX)]
        if base not in ANGLES:
            raise ParameterError(prefix + key, value, "only angle keys take degrees (_deg)")
        if base in table:
            raise ParameterError(
                prefix + key, value, f"give {base} in radians or degrees, not both"
            )
        if isinstance(value, list):
            out[base] = [_degrees(f"{prefix}{key}", v) for v in value]
        else:
            out[base] = _degrees(prefix + key, value)
    return out


def _degrees(key: str, value: Any) -> float:
    return math.radians(require_finite(key, _number(key, value, "°")))


def _number(key: str, value: Any, unit: str) -> int | float:
    """A number of the file, as given: the design checks its range (and a huge int's)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ParameterError(key, value, f"must be a number{f' [{unit}]' if unit else ''}")
    return value


def _numbers(key: str, value: Any, items: tuple[str, ...], unit: str) -> tuple[int | float, ...]:
    if not isinstance(value, list) or len(value) != len(items):
        listed = f"{', '.join(items)} [{unit}]"
        raise ParameterError(key, value, f"must be a list of {len(items)} numbers ({listed})")
    return tuple(_number(key, v, unit) for v in value)


def _limits(key: str, value: Any) -> JointLimits:
    default: JointLimits = getattr(_DEFAULT, key)
    if not isinstance(value, dict):
        raise ParameterError(key, value, "must be a table of theta1, theta2, theta3 [rad]")
    table = _radians(value, f"{key}.")
    known = ("theta1", "theta2", "theta3", "coupled_knee", "name")
    unknown = [k for k in table if k not in known]
    if unknown:
        raise _unknown(unknown[0], known, f"{key}.")
    bounds = {
        joint: _numbers(f"{key}.{joint}", table[joint], ("lower", "upper"), "rad")
        if joint in table
        else getattr(default, joint)
        for joint in JOINT_NAMES
    }
    coupled = table.get("coupled_knee", default.coupled_knee)
    if not isinstance(coupled, bool):
        raise ParameterError(f"{key}.coupled_knee", coupled, "must be true or false")
    name = table.get("name", default.name)
    if not isinstance(name, str):
        raise ParameterError(f"{key}.name", name, "must be a string")
    limits = JointLimits(
        cast(tuple[float, float], bounds["theta1"]),
        cast(tuple[float, float], bounds["theta2"]),
        cast(tuple[float, float], bounds["theta3"]),
        coupled_knee=coupled,
        name=name,
    )
    return default if limits == default else limits


def _mounts(key: str, value: Any) -> tuple[LegMount, ...]:
    if not isinstance(value, list) or not all(isinstance(m, dict) for m in value):
        raise ParameterError(key, value, "must be six [[mount]] tables of name, x, y, z, yaw")
    mounts = []
    for i, raw in enumerate(value):
        table = _radians(raw, f"{key}[{i}].")
        unknown = [k for k in table if k not in MOUNT_KEYS]
        if unknown:
            raise _unknown(unknown[0], tuple(MOUNT_KEYS), f"{key}[{i}].")
        missing = [k for k in MOUNT_KEYS if k not in table]
        if missing:
            raise ParameterError(f"{key}[{i}]", raw, f"needs {', '.join(missing)} as well")
        numbers = {k: _number(f"{key}[{i}].{k}", table[k], "m") for k in "xyz"}
        yaw = _number(f"{key}[{i}].yaw", table["yaw"], "rad")
        mounts.append(LegMount(table["name"], yaw=yaw, **numbers))
    return tuple(mounts)


def _unknown(key: str, known: tuple[str, ...], prefix: str) -> ParameterError:
    close = difflib.get_close_matches(key.removesuffix(DEGREES_SUFFIX), known, n=1)
    hint = f"did you mean {close[0]!r}?" if close else "known keys: " + ", ".join(known)
    return UnknownKeyError(prefix + key, hint)


def _line_of(text: str, field: str, json_file: bool) -> int | None:
    """First line of ``text`` that sets the key ``field`` names (best effort)."""
    parts = [p for p in re.split(r"[.\[\]*]+", field) if p and not p.isdigit()]
    if not parts:
        return None
    key = {"mounts": "mount"}.get(parts[0], parts[0]) if not json_file else parts[0]
    last = parts[-1]
    patterns = [last, key] if last != key else [key]
    for name in patterns:
        for variant in (name, name + DEGREES_SUFFIX):
            if json_file:
                pattern = rf'"{re.escape(variant)}"\s*:'
            else:
                pattern = rf"^\s*(\[\[?\s*{re.escape(variant)}\s*\]\]?|{re.escape(variant)}\s*=)"
            for number, line in enumerate(text.splitlines(), start=1):
                if re.search(pattern, line):
                    return number
    return None


def _reason(err: Exception) -> str:
    return err.strerror if isinstance(err, OSError) and err.strerror else str(err)
