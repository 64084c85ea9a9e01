"""A robot file's URDF text: read as is, or expanded from Xacro in-process.

A Xacro file (``.xacro``, or one that declares the ``xacro`` namespace) is expanded by
the ``xacro`` package with the given arguments (``NAME:=VALUE``) and package folders
(``NAME=DIR``), which serve ``$(find NAME)`` in the file and ``package://NAME/`` in its
mesh references (:func:`resolve_resource`). Nothing is looked up in the environment:
without a folder, ``$(find NAME)`` is refused naming the package.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from urllib.parse import unquote, urlparse

from hexaleg.exceptions import RobotImportError

_XACRO_LOCK = threading.Lock()
"""xacro keeps its arguments and file stack in module globals: one expansion at a time."""

Packages = Mapping[str, str | Path]
"""Package name → its folder, for ``$(find NAME)`` and ``package://NAME/``."""


def read_robot_text(
    path: str | Path,
    args: Mapping[str, str] | None = None,
    packages: Packages | None = None,
) -> str:
    """The URDF text of the file at ``path``, Xacro expanded.

    Args:
        path: A URDF or Xacro file.
        args: Xacro arguments, name → value (``NAME:=VALUE`` on a command line).
        packages: Package folders, name → folder.

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
    return expand_xacro(path, args or {}, packages or {})


def is_xacro(path: Path, text: str) -> bool:
    """Whether the file is Xacro: its name ends in ``.xacro`` or it uses the namespace."""
    return path.suffix == ".xacro" or "ros.org/wiki/xacro" in text or "<xacro:" in text


def expand_xacro(path: Path, args: Mapping[str, str], packages: Packages) -> str:
    """URDF text of the Xacro file at ``path`` with ``args`` and ``packages``."""
    import xacro

    for name, value in args.items():
        if not isinstance(name, str) or not isinstance(value, str):
            raise RobotImportError(f"xacro argument {name!r} := {value!r}: both must be text")
    try:
        with _xacro_finds(packages):
            document = xacro.process_file(str(path), mappings=dict(args))
    except RobotImportError:
        raise
    except Exception as err:  # xacro raises XacroException, NameError, KeyError, ...
        raise RobotImportError(f"xacro failed on {path.name}: {_one_line(err)}") from None
    return str(document.toxml())


def resolve_resource(reference: str, base_dir: Path | None, packages: Packages) -> Path | None:
    """The local file a mesh reference names, or ``None`` if it names none that exists.

    ``package://NAME/rest`` is looked up in ``packages``, ``file://`` and absolute paths
    as they are, relative paths against the robot file's folder ``base_dir``.
    """
    if reference.startswith("package://"):
        name, _, rest = reference[len("package://") :].partition("/")
        folder = packages.get(name)
        candidate = Path(folder) / rest if folder is not None else None
    elif reference.startswith("file://"):
        candidate = Path(unquote(urlparse(reference).path))
    elif "://" in reference:
        candidate = None
    else:
        path = Path(reference)
        candidate = path if path.is_absolute() or base_dir is None else base_dir / path
    return candidate if candidate is not None and candidate.is_file() else None


@contextmanager
def _xacro_finds(packages: Packages) -> Iterator[None]:
    """``$(find NAME)`` answered from ``packages`` while xacro runs, then restored."""
    from xacro import substitution_args

    def find(name: str) -> str:
        if name not in packages:
            given = ", ".join(sorted(packages)) or "none"
            raise RobotImportError(
                f"the file uses $(find {name}): give the package folder as {name}=DIR "
                f"(packages given: {given})"
            )
        return str(Path(packages[name]).resolve())

    with _XACRO_LOCK:
        saved = substitution_args._eval_find, substitution_args._eval_dict["find"]
        substitution_args._eval_find = find
        substitution_args._eval_dict["find"] = find
        try:
            yield
        finally:
            substitution_args._eval_find, substitution_args._eval_dict["find"] = saved


def _one_line(err: BaseException) -> str:
    """An exception's message on one line."""
    return " ".join(str(err).split()) or type(err).__name__
