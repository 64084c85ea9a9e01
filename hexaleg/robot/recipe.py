"""How to build a robot again, in any process: hexaleg's template, or a robot file as read.

A :class:`RobotSource` is a small frozen, hashable value: it travels to worker processes
with every task of a study or a decision (a parsed robot or a Pinocchio model would be
megabytes each way), and each process reads the robot file it names once
(:meth:`RobotSource.read`). Hexaleg's template needs nothing but the design, so its source
is the empty one, ``RobotSource()``.
"""

from __future__ import annotations

import hashlib
import os
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

from hexaleg.exceptions import ParameterError
from hexaleg.robot.feet import FootSearch
from hexaleg.robot.imported import ImportedRobot, import_robot
from hexaleg.robot.resize import resize_robot

__all__ = ["TEMPLATE_NAME", "RobotSource", "SegmentLength"]

TEMPLATE_NAME = "hexaleg's template"
"""What names the robot hexaleg renders from its Xacro templates at a design's numbers."""


@dataclass(frozen=True)
class SegmentLength:
    """One leg's segment changed from the robot file's length.

    Attributes:
        leg: The leg (``lf`` … ``rr``).
        segment: ``coxa``, ``femur`` or ``tibia``.
        length: Its new length [m].
        given_as: Where the user gave it, to name in errors (``--l2``,
            ``robot.segments.lf.tibia``); not part of the recipe's identity.

    """

    leg: str
    segment: str
    length: float
    given_as: str = field(default="", compare=False)


@dataclass(frozen=True)
class RobotSource:
    """How to build a robot: a robot file and how to read it, or hexaleg's template.

    Attributes:
        path: The URDF or Xacro file; ``None`` for hexaleg's template.
        xacro_args: Its Xacro arguments (name, value), sorted.
        packages: ROS package folders (name, folder), sorted.
        foot_offset: The foot point in each leg's last link frame [m], if given.
        foot_frame: The glob pattern of the foot links, if given.
        segments: The segments changed from the file's, per leg.
        lock: The joints held at their zero as fixed joints (glob patterns, in the order
            given: the design file's ``lock_joints``, then ``--lock-joint``).

    Raises:
        ParameterError: Reading options without a file, or a foot given both ways.

    """

    path: str | None = None
    xacro_args: tuple[tuple[str, str], ...] = ()
    packages: tuple[tuple[str, str], ...] = ()
    foot_offset: tuple[float, float, float] | None = None
    foot_frame: str | None = None
    segments: tuple[SegmentLength, ...] = ()
    lock: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "xacro_args", tuple(sorted(dict(self.xacro_args).items())))
        object.__setattr__(self, "packages", tuple(sorted(dict(self.packages).items())))
        object.__setattr__(self, "lock", tuple(dict.fromkeys(self.lock)))
        if self.foot_offset is not None:
            x, y, z = (float(v) for v in self.foot_offset)
            object.__setattr__(self, "foot_offset", (x, y, z))
        if self.foot_frame is not None and self.foot_offset is not None:
            raise ParameterError(
                "foot_offset", self.foot_offset, "excludes foot_frame (--foot-frame): give one"
            )
        if self.path is None:
            given = [name for name in _OPTIONS if getattr(self, name)]
            if given:
                raise ParameterError(given[0], getattr(self, given[0]), "needs a robot file")

    @classmethod
    def of(
        cls,
        path: str,
        xacro_args: Mapping[str, str] | None = None,
        packages: Mapping[str, str] | None = None,
        foot_offset: tuple[float, float, float] | None = None,
        foot_frame: str | None = None,
        segments: tuple[SegmentLength, ...] = (),
        lock: Sequence[str] = (),
    ) -> RobotSource:
        """The source of the robot file at ``path`` read with these options."""
        return cls(
            str(path),
            tuple((xacro_args or {}).items()),
            tuple((str(k), str(v)) for k, v in (packages or {}).items()),
            foot_offset,
            foot_frame,
            tuple(segments),
            tuple(lock),
        )

    def read(self) -> tuple[ImportedRobot, tuple[warnings.WarningMessage, ...]]:
        """The robot file as read and changed, once per process, and the warnings it raised.

        Read once per file as it stands: a relative path named again from another folder, or
        the file replaced since, is read anew (the cache is keyed by :func:`_file_now`).

        Raises:
            HexalegError: The template has no file; the file cannot be read as six legs; a
                segment change out of range (named as the user gave it).

        """
        if self.path is None:
            raise ParameterError("path", None, "hexaleg's template is rendered, not read")
        return _read(self, _file_now(self.path))

    def fingerprint(self, text: str) -> dict[str, Any]:
        """What determines the robot, JSON-ready, ``text`` being the file's URDF as read."""
        return {
            "urdf": self.path,
            "sha256": hashlib.sha256(text.encode()).hexdigest(),
            "xacro_args": dict(self.xacro_args),
            "foot_offset": self.foot_offset,
            "foot_frame": self.foot_frame,
            "segments": [[s.leg, s.segment, s.length] for s in self.segments],
            **({"lock": list(self.lock)} if self.lock else {}),
        }


_OPTIONS = ("xacro_args", "packages", "foot_offset", "foot_frame", "segments", "lock")
"""The fields that say how a robot file is read: none of them applies to the template."""


def _file_now(path: str) -> tuple[object, ...]:
    """Which file ``path`` names now: its real path, device, inode, size and change time [ns].

    A path not there (or not stat-able) is its absolute path alone: reading it says why.
    """
    try:
        found = os.stat(path)
    except OSError:
        return (os.path.abspath(path),)
    return (os.path.realpath(path), found.st_dev, found.st_ino, found.st_size, found.st_mtime_ns)


@lru_cache(maxsize=4)
def _read(
    source: RobotSource, file: tuple[object, ...]
) -> tuple[ImportedRobot, tuple[warnings.WarningMessage, ...]]:
    """``source`` read; ``file``, the file it names as it stands, keys the cache only."""
    assert source.path is not None
    packages = dict(source.packages)
    foot = FootSearch(offset=source.foot_offset, frame=source.foot_frame, packages=packages)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        robot = import_robot(source.path, dict(source.xacro_args), packages, foot, source.lock)
        changes: dict[str, dict[str, float]] = {}
        named: dict[tuple[str, str], str] = {}
        for change in source.segments:
            changes.setdefault(change.leg, {})[change.segment] = change.length
            named[change.leg, change.segment] = change.given_as or f"{change.leg}.{change.segment}"
        if changes:
            robot = resize_robot(robot, changes, lambda leg, segment: named[leg, segment])
    return robot, tuple(caught)
