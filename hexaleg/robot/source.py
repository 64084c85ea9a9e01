"""A robot file's URDF text: read as is, or expanded from Xacro in a process within limits.

A Xacro file (``.xacro``, or one that declares the ``xacro`` namespace) is expanded by
the ``xacro`` package with the given arguments (``NAME:=VALUE``); ``$(find NAME)`` is
answered as ROS answers it (:class:`~hexaleg.robot.packages.PackageFolders`: the given
folders, then the folders above the file, then ``ROS_PACKAGE_PATH``), and a package found
nowhere is refused in one line naming it and ``--package NAME=DIR``. xacro's own warnings
come out as one-line :class:`~hexaleg.exceptions.RobotImportWarning` s (at most
:data:`MAX_XACRO_WARNINGS`), except its "redefining global symbol" (a file's own ``pi``
property, the usual ROS 1 idiom, is what its author meant).

Reading is bounded, whatever the file holds (:mod:`hexaleg._input`): a FIFO or a device is
refused before it is opened, a file over :data:`MAX_ROBOT_FILE_BYTES` by its size, a mesh
over :data:`MAX_MESH_BYTES` before any mesh reader gets it (:func:`check_mesh_file`). Xacro
is a programming language (its ``${...}`` are Python expressions, its macros recurse), so
it runs in a process of its own (:mod:`hexaleg.robot._xacro_process`) stopped after
:data:`XACRO_SECONDS`, holding at most :data:`XACRO_MEMORY_BYTES`, its output at most
:data:`MAX_ROBOT_FILE_BYTES`, every file it includes or loads read as the robot file is;
it costs about 0.1 s a file.
"""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import threading
import warnings
from collections.abc import Iterable, Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from hexaleg._input import check_input_file, read_input_file, size_text
from hexaleg.exceptions import RobotImportError, RobotImportWarning, one_line
from hexaleg.robot.packages import PackageFolders, missing_packages_note

MAX_ROBOT_FILE_BYTES = 16 * 2**20
"""Largest robot file read, file Xacro includes and URDF a Xacro file expands to [bytes].

A real robot's URDF is tens to hundreds of kB; this leaves a hundredfold margin and keeps
the parse of the largest (a fraction of a second, a few hundred MB) within reach."""

MAX_MESH_BYTES = 64 * 2**20
"""Largest mesh file given to a mesh reader (trimesh, Pinocchio's coal/assimp) [bytes]:
a binary STL of 1.4 million triangles, a few hundred MB once read; a robot's meshes are
far smaller, and a larger one is refused by its size, never read."""

XACRO_SECONDS = 20.0
"""Longest a Xacro expansion may run, by the clock (and in CPU time) [s]; the shipped
robots expand in a few hundredths of a second."""

XACRO_MEMORY_BYTES = 2**30
"""Most memory (address space) the Xacro expansion's process may hold [bytes]."""

MAX_XACRO_WARNINGS = 20
"""Most of xacro's warnings passed on for one expansion (the rest are dropped) [-]."""

MAX_XACRO_CHATTER = 64 * 2**10
"""Most of what xacro prints kept to find its warnings in (the rest is dropped) [chars]."""

REDEFINED = "redefining global symbol"
"""The start of xacro's warning about a file's property named as one of its built-ins."""

WARNING_MARK = "xacro-warning\t"
"""How the Xacro process marks a line of its standard error that is one of xacro's warnings."""

_XACRO_LOCK = threading.Lock()
"""xacro keeps its arguments and file stack in module globals: one expansion at a time."""

_PACKAGE_ROOT = Path(__file__).resolve().parents[2]
"""The folder that holds this ``hexaleg``: the Xacro process imports the same one."""

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

    Raises:
        RobotImportError: No such file, not a regular file (a FIFO, a device), larger than
            :data:`MAX_ROBOT_FILE_BYTES`, not UTF-8, or its Xacro fails or passes its limits.

    """
    path = Path(path)
    data = read_input_file(path, MAX_ROBOT_FILE_BYTES, str(path), RobotImportError)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise RobotImportError(f"{path} cannot be read: {one_line(err)}") from None
    if not is_xacro(path, text):
        return text
    return expand_xacro(path, args or {}, PackageFolders.of(packages, path.parent))


def check_mesh_file(path: str | Path, reference: str) -> int:
    """The size [bytes] of the mesh file ``path`` (``reference`` in the robot file).

    Raises:
        RobotImportError: It is not a regular file, or larger than :data:`MAX_MESH_BYTES`.

    """
    return check_input_file(path, MAX_MESH_BYTES, f"mesh {reference}", RobotImportError)


def is_xacro(path: Path, text: str) -> bool:
    """Whether the file is Xacro: its name ends in ``.xacro`` or it uses the namespace."""
    return path.suffix == ".xacro" or "ros.org/wiki/xacro" in text or "<xacro:" in text


def expand_xacro(path: Path, args: Mapping[str, str], packages: Packages) -> str:
    """URDF text of the Xacro file at ``path`` with ``args`` and ``packages``, within limits.

    xacro's warnings (but a redefined global symbol) are each warned as a
    :class:`~hexaleg.exceptions.RobotImportWarning` when the expansion succeeds.

    Raises:
        RobotImportError: xacro fails, a ``$(find NAME)`` names a package found nowhere, or
            it runs past :data:`XACRO_SECONDS`, past :data:`XACRO_MEMORY_BYTES` or past
            :data:`MAX_ROBOT_FILE_BYTES` of output.

    """
    for name, value in args.items():
        if not isinstance(name, str) or not isinstance(value, str):
            raise RobotImportError(f"xacro argument {name!r} := {value!r}: both must be text")
    folders = PackageFolders.of(packages, path.parent)
    request = {
        "path": str(path),
        "args": dict(args),
        "packages": {
            "given": [list(pair) for pair in folders.given],
            "start": folders.start,
            "search_path": list(folders.search_path),
        },
        "seconds": XACRO_SECONDS,
        "memory": XACRO_MEMORY_BYTES,
        "output": MAX_ROBOT_FILE_BYTES,
    }
    environment = dict(os.environ)
    environment["PYTHONPATH"] = os.pathsep.join(
        [str(_PACKAGE_ROOT), *filter(None, [environment.get("PYTHONPATH")])]
    )
    try:
        done = subprocess.run(
            [sys.executable, "-m", "hexaleg.robot._xacro_process"],
            input=json.dumps(request).encode(),
            capture_output=True,
            timeout=XACRO_SECONDS,
            env=environment,
            check=False,
        )
    except subprocess.TimeoutExpired:
        raise RobotImportError(_past_time(path)) from None
    except OSError as err:
        raise RobotImportError(f"xacro on {path.name} could not start: {one_line(err)}") from None
    lines = done.stderr.decode("utf-8", errors="replace").strip().splitlines()
    said = [line for line in lines if not line.startswith(WARNING_MARK)]
    if done.returncode == 0:
        for line in lines[:MAX_XACRO_WARNINGS]:
            if line.startswith(WARNING_MARK):
                message = line[len(WARNING_MARK) :]
                warnings.warn(f"xacro on {path.name}: {message}", RobotImportWarning, stacklevel=2)
        return done.stdout.decode("utf-8")
    if done.returncode > 0 and said:
        raise RobotImportError(said[-1])
    if -done.returncode in (signal.SIGXCPU, signal.SIGKILL):
        raise RobotImportError(_past_time(path))
    raise RobotImportError(f"xacro on {path.name} ended by {_ending(done.returncode)}")


def package_folders(request: Mapping[str, Any]) -> PackageFolders:
    """The package folders :func:`expand_xacro` sends the Xacro process, read back."""
    return PackageFolders(
        tuple((str(name), str(folder)) for name, folder in request["given"]),
        None if request["start"] is None else str(request["start"]),
        tuple(str(entry) for entry in request["search_path"]),
    )


def xacro_text(path: str, args: Mapping[str, str], packages: PackageFolders, output: int) -> str:
    """The expansion itself (in the Xacro process): every file xacro opens checked first.

    Raises:
        RobotImportError: A file xacro opens is no regular file or is over the size cap,
            ``$(find NAME)`` names a package found nowhere, xacro fails, or its URDF is over
            ``output`` bytes.

    """
    import xacro

    xacro.open = _checked_open  # xacro's parse and load_yaml: the module's name before builtins
    name = Path(path).name
    missing: list[str] = []
    try:
        with _xacro_finds(packages, missing):
            text = str(xacro.process_file(path, mappings=dict(args)).toxml())
    except Exception as err:  # xacro raises XacroException, NameError, KeyError, ...
        if missing:  # xacro wraps what find raised in its own exception: say it plainly
            raise RobotImportError(
                f"{name} uses $(find {missing[0]}): {missing_packages_note(missing, path)}"
            ) from None
        if isinstance(err, RobotImportError):
            raise
        cause = _root_cause(err)
        if isinstance(cause, MemoryError):
            raise MemoryError from None
        if isinstance(cause, RecursionError):
            raise RobotImportError(
                f"xacro on {name} nests macros or includes deeper than Python's recursion limit"
            ) from None
        if isinstance(cause, RobotImportError):
            raise cause from None
        raise RobotImportError(f"xacro failed on {name}: {one_line(err)}") from None
    if len(text.encode("utf-8")) > output:
        raise RobotImportError(f"xacro on {name} writes more than {size_text(output)} of URDF")
    return text


def xacro_warnings(printed: str) -> list[str]:
    """The warnings xacro printed, each once, at most :data:`MAX_XACRO_WARNINGS`.

    xacro prints a warning and then where it was (``when processing file: ...``) as
    lines of their own; the location lines are dropped, and so are redefinitions of its
    global symbols (``pi``): a file's own property is what its author meant.
    """
    found: dict[str, None] = {}
    for line in printed.splitlines():
        text = line.strip()
        if text.startswith("warning:") and REDEFINED not in text:
            found.setdefault(" ".join(text[len("warning:") :].split()), None)
    return [message for message in found if message][:MAX_XACRO_WARNINGS]


def past_memory(path: str, memory: int) -> str:
    """The refusal of a Xacro expansion that needed more than ``memory`` bytes."""
    return (
        f"xacro on {Path(path).name} needed more than the {size_text(memory)} of memory its "
        "expansion may hold (XACRO_MEMORY_BYTES): a runaway property or macro?"
    )


def _past_time(path: Path) -> str:
    return (
        f"xacro on {path.name} ran past the {XACRO_SECONDS:g} s its expansion may take "
        "(XACRO_SECONDS): a runaway expression or macro?"
    )


def _root_cause(err: BaseException) -> BaseException:
    """The exception under xacro's wrappers (its ``XacroException.exc``, or the chain's)."""
    seen: set[int] = set()
    while id(err) not in seen:
        seen.add(id(err))
        inner = getattr(err, "exc", None) or err.__cause__ or err.__context__
        if not isinstance(inner, BaseException):
            break
        err = inner
    return err


def _ending(status: int) -> str:
    """How a process ended, in words: ``signal SIGSEGV``, ``exit status 1``."""
    if status < 0:
        try:
            return f"signal {signal.Signals(-status).name}"
        except ValueError:
            return f"signal {-status}"
    return f"exit status {status}"


def _checked_open(file: str, *args: object, **kwargs: object) -> object:
    """``open`` for xacro: a regular file within :data:`MAX_ROBOT_FILE_BYTES` only."""
    check_input_file(file, MAX_ROBOT_FILE_BYTES, str(file), RobotImportError)
    return open(file, *args, **kwargs)  # type: ignore[call-overload]


def xacro_cpu_seconds(seconds: float) -> int:
    """The CPU-time limit [s] of the Xacro process: the clock's limit, rounded up, plus 1."""
    return math.ceil(seconds) + 1


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


def warning_lines(messages: Iterable[str]) -> str:
    """The Xacro process's lines for ``messages`` (xacro's warnings), marked for its parent."""
    return "".join(f"{WARNING_MARK}{' '.join(message.split())}\n" for message in messages)
