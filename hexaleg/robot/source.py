"""A robot file's URDF text: read as is, or expanded from Xacro in-process.

A Xacro file (``.xacro``, or one that declares the ``xacro`` namespace) is expanded by
the ``xacro`` package with the given arguments (``NAME:=VALUE``); ``$(find NAME)`` is
answered as ROS answers it (:class:`~hexaleg.robot.packages.PackageFolders`: the given
folders, then the folders above the file, then ``ROS_PACKAGE_PATH``), and a package found
nowhere is refused in one line naming it and ``--package NAME=DIR``. xacro's own warnings
come out as one-line :class:`~hexaleg.exceptions.RobotImportWarning` s, except its
"redefining global symbol" (a file's own ``pi`` property, the usual ROS 1 idiom, is what its
author meant).
"""

from __future__ import annotations

import io
import threading
import warnings
from collections.abc import Iterator, Mapping
from contextlib import contextmanager, redirect_stderr
from pathlib import Path

from hexaleg.exceptions import RobotImportError, RobotImportWarning
from hexaleg.robot.packages import PackageFolders, missing_packages_note

_XACRO_LOCK = threading.Lock()
"""xacro keeps its arguments and file stack in module globals: one expansion at a time."""

Packages = Mapping[str, str | Path] | PackageFolders
"""Package name → its folder given by the user, or every package folder of a robot file."""


def read_robot_text(
    path: str | Path,
    args: Mapping[str, str] | None = None,
    packages: Packages | None = None,
) -> str:
    """The URDF text of the file at ``path``, Xacro expanded.

    Args:
        path: A URDF or Xacro file.
        args: Xacro arguments, name → value (``NAME:=VALUE`` on a command line).
        packages: Package folders, name → folder (searched further as
            :class:`~hexaleg.robot.packages.PackageFolders` does).

    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise RobotImportError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise RobotImportError(f"{path} cannot be read: {_one_line(err)}") from None
    if not is_xacro(path, text):
        return text
    return expand_xacro(path, args or {}, PackageFolders.of(packages, path.parent))


def is_xacro(path: Path, text: str) -> bool:
    """Whether the file is Xacro: its name ends in ``.xacro`` or it uses the namespace."""
    return path.suffix == ".xacro" or "ros.org/wiki/xacro" in text or "<xacro:" in text


def expand_xacro(path: Path, args: Mapping[str, str], packages: Packages) -> str:
    """URDF text of the Xacro file at ``path`` with ``args`` and ``packages``."""
    import xacro

    for name, value in args.items():
        if not isinstance(name, str) or not isinstance(value, str):
            raise RobotImportError(f"xacro argument {name!r} := {value!r}: both must be text")
    folders = PackageFolders.of(packages, path.parent)
    missing: list[str] = []
    try:
        with _xacro_finds(folders, missing), _xacro_warnings(path):
            document = xacro.process_file(str(path), mappings=dict(args))
    except RobotImportError:
        raise
    except Exception as err:  # xacro raises XacroException, NameError, KeyError, ...
        if missing:  # xacro wraps what find raised in its own exception: say it plainly
            raise RobotImportError(
                f"{path.name} uses $(find {missing[0]}): {missing_packages_note(missing, path)}"
            ) from None
        raise RobotImportError(f"xacro failed on {path.name}: {_one_line(err)}") from None
    return str(document.toxml())


@contextmanager
def _xacro_finds(packages: PackageFolders, missing: list[str]) -> Iterator[None]:
    """``$(find NAME)`` answered from ``packages`` while xacro runs, then restored.

    A package found nowhere is appended to ``missing`` before xacro is stopped.
    """
    from xacro import substitution_args

    def find(name: str) -> str:
        folder = packages.find(name)
        if folder is None:
            missing.append(name)
            raise RobotImportError(missing_packages_note([name]))
        return str(folder.resolve())

    with _XACRO_LOCK:
        saved = substitution_args._eval_find, substitution_args._eval_dict["find"]
        substitution_args._eval_find = find
        substitution_args._eval_dict["find"] = find
        try:
            yield
        finally:
            substitution_args._eval_find, substitution_args._eval_dict["find"] = saved


REDEFINED = "redefining global symbol"
"""The start of xacro's warning about a file's property named as one of its built-ins."""


@contextmanager
def _xacro_warnings(path: Path) -> Iterator[None]:
    """Xacro's stderr while it runs: each warning one :class:`RobotImportWarning` line.

    xacro prints a warning and then where it was (``when processing file: ...``) as
    lines of their own; the location lines are dropped, and so are redefinitions of its
    global symbols (``pi``): a file's own property is what its author meant.
    """
    captured = io.StringIO()
    try:
        with redirect_stderr(captured):
            yield
    finally:
        _warn_lines(captured.getvalue(), path)


def _warn_lines(printed: str, path: Path) -> None:
    """:func:`_xacro_warnings`' warnings, from what xacro printed."""
    for line in printed.splitlines():
        text = line.strip()
        if text.startswith("warning:") and REDEFINED not in text:
            message = text[len("warning:") :].strip()
            warnings.warn(f"xacro on {path.name}: {message}", RobotImportWarning, stacklevel=5)


def _one_line(err: BaseException) -> str:
    """An exception's message on one line."""
    return " ".join(str(err).split()) or type(err).__name__
