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
    if nproc is not None:
        if shutil.which("prlimit") is None:
            pytest.skip("prlimit (util-linux) is not installed")
        prefix += ["prlimit", f"--nproc={nproc}"]
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
    if _runs_as_plain_user([sys.executable]):
        return (sys.executable, "-c", run_module)
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    for folder in ("/usr/bin", "/usr/local/bin"):
        candidate = [str(Path(folder, version))]
        if Path(candidate[0]).exists() and _runs_as_plain_user(candidate):
            packages = sysconfig.get_paths()["purelib"]
            code = f"import site, sys; site.addsitedir({packages!r}); sys.argv[0] = 'hexaleg'; "
            return (candidate[0], "-c", code + run_module)
    pytest.skip(f"no {version} that a plain user may run ({sys.executable} is private)")


def _runs_as_plain_user(interpreter: list[str]) -> bool:
    check = [*_privileges_dropped(), *interpreter, "-c", "import sys; sys.exit(0)"]
    try:
        return subprocess.run(check, capture_output=True, timeout=60).returncode == 0
    except OSError:
        return False
