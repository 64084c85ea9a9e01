"""Where a robot file's ROS packages are: ``package://NAME/`` and Xacro's ``$(find NAME)``.

A package is looked for as a ROS workspace holds it, first match wins:

1. the folders the user gives (``--package NAME=DIR``, a ``[robot]`` table's ``packages``);
2. the robot file's own folder and each folder above it: one holding a ``package.xml``
   whose ``<name>`` is NAME, or one named NAME (a description package's ``urdf/`` file
   finds its package two folders up);
3. the folders of ``ROS_PACKAGE_PATH`` (the ROS convention a user of a ROS workspace
   expects, read in one place, :func:`ros_package_path`) and the folders below them, as
   rospkg crawls them: a folder with a ``package.xml`` naming NAME (or, holding one, named
   NAME) is the package; its subfolders are not searched further.

yourdfpy's filename handlers were considered: they drop the package's name and try the
path below every folder above the file, so ``package://other/x.stl`` would find this
package's ``x.stl``; here a package is found only by its name.

A package not found is named once, with how to give it (:func:`missing_packages_note`).
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from urllib.parse import unquote, urlparse

from hexaleg._input import read_input_file
from hexaleg.exceptions import HexalegError

__all__ = [
    "PackageFolders",
    "missing_packages_note",
    "package_name",
    "resolve_resource",
    "ros_package_path",
]

ROS_PACKAGE_PATH = "ROS_PACKAGE_PATH"
"""The environment variable ROS tools read their package folders from (``os.pathsep`` apart)."""

MANIFEST = "package.xml"
"""A ROS package's manifest (REP 140 / REP 149), holding its ``<name>``."""

MAX_MANIFEST_BYTES = 1 << 20
"""A ``package.xml`` larger than this is not read (no package manifest is that big) [B]."""

MAX_CRAWL_DEPTH = 6
"""Folders below a ``ROS_PACKAGE_PATH`` entry searched for packages, at most [-]."""

MAX_CRAWL_FOLDERS = 20_000
"""Folders visited per ``ROS_PACKAGE_PATH`` entry, at most: a path of ``/`` stays quick [-]."""


def ros_package_path() -> tuple[str, ...]:
    """The folders of ``ROS_PACKAGE_PATH``, in order (none when it is unset).

    The one place hexaleg reads the environment for a robot file: ROS users expect their
    workspace's packages found as ``rospack`` finds them.
    """
    value = os.environ.get(ROS_PACKAGE_PATH, "")
    return tuple(entry for entry in value.split(os.pathsep) if entry)


@dataclass(frozen=True)
class PackageFolders:
    """The package folders of one robot file (picklable, hashable).

    Attributes:
        given: The folders the user gave, (name, folder), in order.
        start: The robot file's folder, whose ancestors are searched; ``None``: none.
        search_path: ``ROS_PACKAGE_PATH``'s folders (:func:`ros_package_path`).

    """

    given: tuple[tuple[str, str], ...] = ()
    start: str | None = None
    search_path: tuple[str, ...] = ()

    @classmethod
    def of(
        cls,
        given: Mapping[str, str | Path] | PackageFolders | None,
        folder: str | Path | None = None,
        search_path: Iterable[str] | None = None,
    ) -> PackageFolders:
        """The package folders of a robot file in ``folder``, the user's ``given`` first.

        ``search_path``: ``ROS_PACKAGE_PATH``'s folders (:func:`ros_package_path`) when
        omitted. ``given`` may already be a :class:`PackageFolders`: it is kept, its start
        set to ``folder`` if it has none.
        """
        if isinstance(given, PackageFolders):
            if given.start is not None or folder is None:
                return given
            return cls(given.given, str(folder), given.search_path)
        pairs = tuple((str(k), str(v)) for k, v in dict(given or {}).items())
        path = ros_package_path() if search_path is None else tuple(search_path)
        return cls(pairs, None if folder is None else str(folder), path)

    @property
    def names(self) -> tuple[str, ...]:
        """The packages the user gave, by name."""
        return tuple(name for name, _ in self.given)

    def as_dict(self) -> dict[str, str]:
        """The user's folders, name → folder."""
        return dict(self.given)

    def find(self, name: str) -> Path | None:
        """The folder of package ``name``, or ``None`` if it is found nowhere."""
        for given, folder in self.given:
            if given == name:
                return Path(folder)
        if self.start is not None:
            found = _above(Path(self.start).resolve(), name)
            if found is not None:
                return found
        for entry in self.search_path:
            crawled = _crawled(os.path.abspath(entry)).get(name)
            if crawled is not None:
                return Path(crawled)
        return None

    def resolve(self, reference: str, base_dir: Path | None) -> Path | None:
        """The local file a mesh reference names, or ``None`` if it names none that exists.

        ``package://NAME/rest`` below package NAME's folder (:meth:`find`), ``file://`` and
        absolute paths as they are, relative paths against the robot file's folder
        ``base_dir``.
        """
        name = package_name(reference)
        if name is not None:
            folder = self.find(name)
            rest = reference[len("package://") + len(name) :].lstrip("/")
            candidate = None if folder is None else folder / rest
        elif reference.startswith("file://"):
            candidate = Path(unquote(urlparse(reference).path))
        elif "://" in reference:
            candidate = None
        else:
            path = Path(reference)
            candidate = path if path.is_absolute() or base_dir is None else base_dir / path
        return candidate if candidate is not None and candidate.is_file() else None

    def missing(self, references: Iterable[str]) -> tuple[str, ...]:
        """The packages ``references`` name that are found nowhere, each once, in order."""
        names = dict.fromkeys(n for n in map(package_name, references) if n is not None)
        return tuple(name for name in names if self.find(name) is None)


def resolve_resource(
    reference: str, base_dir: Path | None, packages: Mapping[str, str | Path] | PackageFolders
) -> Path | None:
    """The local file a mesh reference of a robot file in ``base_dir`` names, if it exists.

    :meth:`PackageFolders.resolve` with ``packages`` (the user's folders, or a robot's).
    """
    return PackageFolders.of(packages, base_dir).resolve(reference, base_dir)


def package_name(reference: str) -> str | None:
    """The package a ``package://NAME/...`` reference names; ``None`` for any other."""
    if not reference.startswith("package://"):
        return None
    name = reference[len("package://") :].partition("/")[0]
    return name or None


def missing_packages_note(names: Iterable[str], robot_file: str | Path | None = None) -> str:
    """One sentence naming the packages not found and how to give them."""
    names = tuple(names)
    where = "above the robot file" if robot_file is None else f"above {Path(robot_file).name}"
    listed = ", ".join(names)
    give = " ".join(f"--package {name}=DIR" for name in names)
    noun = "package" if len(names) == 1 else "packages"
    return (
        f"ROS {noun} {listed} not found (looked in --package, the folders {where} for a "
        f"{MANIFEST} naming it, and {ROS_PACKAGE_PATH}): give {give}"
    )


def _above(folder: Path, name: str) -> Path | None:
    """The first of ``folder`` and its ancestors that is package ``name``."""
    for candidate in (folder, *folder.parents):
        manifest = candidate / MANIFEST
        declared = _manifest_name(str(manifest)) if manifest.is_file() else None
        if (declared or candidate.name) == name:
            return candidate
    return None


def _manifest_name(path: str) -> str | None:
    """The ``<name>`` a ``package.xml`` declares; ``None`` if it cannot be read."""
    try:
        stat = os.stat(path)
    except OSError:
        return None
    return _declared_name(path, stat.st_mtime_ns, stat.st_size)


@lru_cache(maxsize=64)
def _declared_name(path: str, mtime_ns: int, size: int) -> str | None:
    """:func:`_manifest_name` of the file as it was at ``mtime_ns`` and ``size`` (cached)."""
    del mtime_ns, size  # the cache's key only: a file changed since is read anew
    try:  # a regular file within the cap only, never waited on (as a robot file is read)
        data = read_input_file(path, MAX_MANIFEST_BYTES, path)
        if b"<!ENTITY" in data:
            return None
        node = ET.fromstring(data).find("name")
    except (HexalegError, ET.ParseError):
        return None
    text = None if node is None or node.text is None else node.text.strip()
    return text or None


@lru_cache(maxsize=8)
def _crawled(entry: str) -> dict[str, str]:
    """Every package at or below folder ``entry``: name → folder (the first found wins).

    A folder holding a ``package.xml`` is a package (its manifest's name, else its own)
    and is not searched further; hidden folders are skipped; the walk stops at
    :data:`MAX_CRAWL_DEPTH` levels and :data:`MAX_CRAWL_FOLDERS` folders.
    """
    found: dict[str, str] = {}
    level = [entry]
    visited = 0
    for _ in range(MAX_CRAWL_DEPTH + 1):
        below = []
        for folder in level:
            visited += 1
            if visited > MAX_CRAWL_FOLDERS:
                return found
            manifest = os.path.join(folder, MANIFEST)
            if os.path.isfile(manifest):
                name = _manifest_name(manifest) or os.path.basename(folder)
                found.setdefault(name, folder)
                continue
            below += _subfolders(folder)
        level = below
    return found


def _subfolders(folder: str) -> list[str]:
    """``folder``'s visible subfolders, sorted (none if it cannot be listed)."""
    try:
        with os.scandir(folder) as entries:
            return sorted(e.path for e in entries if not e.name.startswith(".") and e.is_dir())
    except OSError:
        return []
