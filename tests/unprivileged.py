"""Run ``hexaleg`` as a user without privileges, for the cases root would pass by.

Root writes into read-only folders and ignores ``ulimit -u``; these cases need a plain
user. As root, the command runs under ``setpriv`` as an unused numeric uid (no account
needed, and no other process counts against its limits); as a plain user, as that user.
The interpreter must be one the plain user can run: this one, or — when this one lives
in a private folder (a pyenv under /root) — the same Python version from the system,
given this environment's packages.
"""

from __future__ import annotations

import functools
import os
import shutil
import subprocess
import sys
import sysconfig
import tempfile
from pathlib import Path

import pytest

SYSTEM_BIN = ("/usr/bin", "/usr/local/bin")
"""Where a Python of the same version may be found for the plain user."""
UID = 54_321
"""The plain user's uid and gid (no account needed; unlikely to own any process)."""


def plain_folder() -> Path:
    """A new folder in the temp folder that the plain user owns (removed by the caller)."""
    folder = Path(tempfile.mkdtemp(prefix="hexaleg-unprivileged-"))
    if os.geteuid() == 0:
        os.chown(folder, UID, UID)
    return folder


def run_plain(
    argv: list[str], cwd: Path, nproc: int | None = None, timeout: float = 300
) -> subprocess.CompletedProcess[str]:
    """``hexaleg argv`` in ``cwd`` as the plain user (at most ``nproc`` processes)."""
    prefix = _privileges_dropped()
    if nproc is not None:  # set first: the limit is inherited across the change of user
        if shutil.which("prlimit") is None:
            pytest.skip("prlimit (util-linux) is not installed")
        prefix = ["prlimit", f"--nproc={nproc}", *prefix]
    env = {
        "PATH": os.environ.get("PATH", "/usr/bin:/bin"),
        "HOME": str(cwd),
        "NUMBA_CACHE_DIR": str(cwd / ".numba"),  # a writable cache: not the case tested here
        "OPENBLAS_NUM_THREADS": "1",
        "LANG": "C.UTF-8",
    }
    return subprocess.run(
        [*prefix, *_interpreter(), *argv],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


def _privileges_dropped() -> list[str]:
    if os.geteuid() != 0:
        return []
    if shutil.which("setpriv") is None:
        pytest.skip("setpriv (util-linux) is not installed: cannot drop root's privileges")
    return ["setpriv", f"--reuid={UID}", f"--regid={UID}", "--clear-groups", "--"]


@functools.lru_cache(maxsize=1)
def _interpreter() -> tuple[str, ...]:
    """A command that runs ``python -m hexaleg`` and that the plain user can execute."""
    run_module = "import runpy; runpy.run_module('hexaleg', run_name='__main__', alter_sys=True)"
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    packages = sysconfig.get_paths()["purelib"]
    # the venv's packages (and its .pth files) first: a system Python's own dist-packages
    # (Debian's python3-cffi-backend, say) must not shadow what the venv installed
    given_packages = (
        f"import site, sys; n = len(sys.path); site.addsitedir({packages!r}); "
        "sys.path[:] = sys.path[n:] + sys.path[:n]; "
    )
    candidates = [(sys.executable, "")]
    candidates += [(str(Path(folder, version)), given_packages) for folder in SYSTEM_BIN]
    for interpreter, setup in candidates:
        if Path(interpreter).exists() and _runs_as_plain_user(interpreter, setup):
            return (interpreter, "-c", setup + run_module)
    pytest.skip(f"no {version} that a plain user may run ({sys.executable} is private)")


def _runs_as_plain_user(interpreter: str, setup: str) -> bool:
    """Whether the plain user can run ``interpreter`` and import what hexaleg needs.

    A trivial script is not enough: the modules Python starts with are frozen into it,
    so it starts even where the plain user cannot read its library.
    """
    code = setup + "import json, numpy, hexaleg"
    check = [*_privileges_dropped(), interpreter, "-c", code]
    try:
        return subprocess.run(check, capture_output=True, timeout=120).returncode == 0
    except OSError:
        return False
