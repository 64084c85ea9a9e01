"""A robot file's URDF text: read as is, or expanded from Xacro in a process within limits.

A Xacro file (``.xacro``, or one that declares the ``xacro`` namespace) is expanded by
the ``xacro`` package with the given arguments (``NAME:=VALUE``) and package folders
(``NAME=DIR``), which serve ``$(find NAME)`` in the file and ``package://NAME/`` in its
mesh references (:func:`resolve_resource`). Nothing is looked up in the environment:
without a folder, ``$(find NAME)`` is refused naming the package.

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
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from urllib.parse import unquote, urlparse

from hexaleg._input import check_input_file, read_input_file, size_text
from hexaleg.exceptions import RobotImportError, one_line

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

_XACRO_LOCK = threading.Lock()
"""xacro keeps its arguments and file stack in module globals: one expansion at a time."""

_PACKAGE_ROOT = Path(__file__).resolve().parents[2]
"""The folder that holds this ``hexaleg``: the Xacro process imports the same one."""

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
    return expand_xacro(path, args or {}, packages or {})


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

    Raises:
        RobotImportError: xacro fails, or runs past :data:`XACRO_SECONDS`, past
            :data:`XACRO_MEMORY_BYTES` or past :data:`MAX_ROBOT_FILE_BYTES` of output.

    """
    for name, value in args.items():
        if not isinstance(name, str) or not isinstance(value, str):
            raise RobotImportError(f"xacro argument {name!r} := {value!r}: both must be text")
    request = {
        "path": str(path),
        "args": dict(args),
        "packages": {name: str(folder) for name, folder in packages.items()},
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
    if done.returncode == 0:
        return done.stdout.decode("utf-8")
    said = done.stderr.decode("utf-8", errors="replace").strip().splitlines()
    if done.returncode > 0 and said:
        raise RobotImportError(said[-1])
    if -done.returncode in (signal.SIGXCPU, signal.SIGKILL):
        raise RobotImportError(_past_time(path))
    raise RobotImportError(f"xacro on {path.name} ended by {_ending(done.returncode)}")


def xacro_text(path: str, args: Mapping[str, str], packages: Packages, output: int) -> str:
    """The expansion itself (in the Xacro process): every file xacro opens checked first.

    Raises:
        RobotImportError: A file xacro opens is no regular file or is over the size cap,
            ``$(find NAME)`` of a package not given, xacro fails, or its URDF is over
            ``output`` bytes.

    """
    import xacro

    xacro.open = _checked_open  # xacro's parse and load_yaml: the module's name before builtins
    name = Path(path).name
    try:
        with _xacro_finds(packages):
            text = str(xacro.process_file(path, mappings=dict(args)).toxml())
    except RobotImportError:
        raise
    except Exception as err:  # xacro raises XacroException, NameError, KeyError, ...
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
