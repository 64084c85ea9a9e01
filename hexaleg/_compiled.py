"""Numba compilation with an on-disk cache that works for any user, and stays fresh.

:func:`compiled` is ``numba.njit`` with caching in a directory hexaleg chooses, so that:

- a user whose home and site-packages are not writable (a container, a CI runner,
  ``runuser -u nobody``) still runs hexaleg: the cache falls back to a private folder
  in the temporary directory, or is switched off when nothing is writable (every
  process then compiles anew, a few seconds). Matplotlib's cache goes beside it
  (``MPLCONFIGDIR``, unless the user set it) when Matplotlib's own folders are not
  writable (:func:`use_private_matplotlib_cache`, called by the command line before
  any command runs), so that figures come without warnings about them;
- an edit to any module holding compiled code makes a fresh cache. Numba checks only
  the source file of the function it loads, so a kernel inlined into a caller in another
  module would otherwise be loaded stale; the folder's name carries a hash of every
  module listed in :data:`COMPILED_MODULES`, and :func:`compiled` refuses functions of
  modules not listed.
"""

from __future__ import annotations

import hashlib
import os
import stat
import sys
import tempfile
from collections.abc import Callable
from functools import cache, update_wrapper
from pathlib import Path
from typing import Any, TypeVar, cast

F = TypeVar("F", bound=Callable[..., Any])

PACKAGE = Path(__file__).resolve().parent
COMPILED_MODULES = (
    "gait/friction.py",
    "gait/newton_euler.py",
    "numerics/lp.py",
    "stance/margin_kernel.py",
    "stance/margin_jacobian.py",
    "stance/leg_kernel.py",
    "stance/climb.py",
    "stance/paths.py",
    "structure/tube_kernel.py",
)
"""The modules (relative to the package) that define compiled functions."""


def compiled(function: F) -> F:
    """``numba.njit(cache=True)`` with the cache in :func:`cache_directory` (off if None).

    Deferred (:class:`Kernel`): Numba is imported and the function handed to it when a
    kernel first runs, so importing a module that holds kernels costs nothing (a command's
    parser, ``hexaleg --help``, imports the analyses it names without running them).
    """
    source = Path(function.__code__.co_filename).resolve()
    listed = source.is_relative_to(PACKAGE) and (
        source.relative_to(PACKAGE).as_posix() in COMPILED_MODULES
    )
    if not listed:
        raise RuntimeError(f"{source} defines compiled code but is not in COMPILED_MODULES")
    return cast(F, Kernel(function))


class Kernel:
    """A function compiled by Numba on its first call (from Python or from another kernel).

    Called from Python, it calls its dispatcher; named in another kernel, Numba types it
    as that dispatcher (:func:`_register_kernel_type`), so kernels call each other as
    compiled functions do.
    """

    def __init__(self, function: Callable[..., Any]) -> None:
        update_wrapper(self, function)
        self.function = function
        self._dispatcher: Any = None

    @property
    def dispatcher(self) -> Any:
        """Numba's dispatcher of the function, made on first use."""
        if self._dispatcher is None:
            self._dispatcher = _njit(self.function)
        return self._dispatcher

    def __call__(self, *args: Any) -> Any:
        return self.dispatcher(*args)


def _njit(function: Callable[..., Any]) -> Any:
    """``numba.njit`` of ``function``, cached in :func:`cache_directory` when there is one."""
    import numba

    _register_kernel_type()
    directory = cache_directory()
    if directory is None:
        return numba.njit(cache=False)(function)
    config: Any = numba.config
    previous = config.CACHE_DIR
    config.CACHE_DIR = str(directory)  # numba fixes a function's cache path here
    try:
        return numba.njit(cache=True)(function)
    finally:
        config.CACHE_DIR = previous


@cache
def _register_kernel_type() -> None:
    """Teach Numba that a :class:`Kernel` named in compiled code is its dispatcher."""
    from numba.core import types
    from numba.extending import typeof_impl

    @typeof_impl.register(Kernel)
    def _typeof(value: Kernel, _context: Any) -> Any:
        return types.Dispatcher(value.dispatcher)


@cache
def cache_directory() -> Path | None:
    """The first usable cache folder of :func:`cache_candidates`, or None if none is."""
    name = f"numba-{source_fingerprint()}"
    for base in cache_candidates():
        if _private_and_writable(base) and _private_and_writable(base / name):
            return base / name
    return None


def use_private_matplotlib_cache() -> None:
    """Point Matplotlib at ``matplotlib`` beside the compiled code's cache, if need be.

    Sets ``MPLCONFIGDIR`` when Matplotlib's own folders are not writable (else it warns on
    every import and caches nothing), only before Matplotlib is imported (it reads the
    variable then), and never over a value the user set.
    """
    if os.environ.get("MPLCONFIGDIR") or "matplotlib" in sys.modules:
        return
    try:
        home: Path | None = Path.home()
    except (RuntimeError, KeyError):  # no home at all
        home = None
    bases = [
        os.environ.get("XDG_CONFIG_HOME") or (home and home / ".config"),
        os.environ.get("XDG_CACHE_HOME") or (home and home / ".cache"),
    ]
    if all(base and _writable(Path(base) / "matplotlib") for base in bases):
        return
    for base in cache_candidates():
        if _private_and_writable(base) and _private_and_writable(base / "matplotlib"):
            os.environ["MPLCONFIGDIR"] = str(base / "matplotlib")
            return


def _writable(directory: Path) -> bool:
    """Whether ``directory`` is, or could be made, a folder this process writes in."""
    while not directory.exists() and directory != directory.parent:
        directory = directory.parent
    return directory.is_dir() and os.access(directory, os.W_OK | os.X_OK)


def cache_candidates() -> list[Path]:
    """Where the cache may go, in order.

    ``$NUMBA_CACHE_DIR/hexaleg`` if that is set, the user's cache folder, and a
    per-user folder in the temporary directory.
    """
    candidates = []
    if os.environ.get("NUMBA_CACHE_DIR"):
        candidates.append(Path(os.environ["NUMBA_CACHE_DIR"]) / "hexaleg")
    if sys.platform == "win32" and os.environ.get("LOCALAPPDATA"):
        candidates.append(Path(os.environ["LOCALAPPDATA"]) / "hexaleg")
    elif os.environ.get("XDG_CACHE_HOME"):
        candidates.append(Path(os.environ["XDG_CACHE_HOME"]) / "hexaleg")
    else:
        candidates.append(Path.home() / ".cache" / "hexaleg")
    user = os.getuid() if hasattr(os, "getuid") else os.getlogin()
    candidates.append(Path(tempfile.gettempdir()) / f".hexaleg-cache-{user}")
    return candidates


def source_fingerprint() -> str:
    """A short hash of every compiled module's source (and of the Python version)."""
    digest = hashlib.sha256(sys.version.encode())
    for module in COMPILED_MODULES:
        digest.update((PACKAGE / module).read_bytes())
    return digest.hexdigest()[:16]


def _private_and_writable(directory: Path) -> bool:
    """Create ``directory`` (mode 700) if needed; True if it is ours, writable by us alone.

    Numba's cache holds pickles it loads: a folder that another user can write to (a
    shared temporary directory) must not be used.
    """
    try:
        directory.mkdir(mode=0o700, parents=True, exist_ok=True)
        info = directory.stat()
        if hasattr(os, "getuid") and info.st_uid != os.getuid():
            return False
        if info.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
            return False
        with tempfile.TemporaryFile(dir=directory):
            pass
    except OSError:
        return False
    return True
