"""Compiled code runs for any user: its cache falls back to a private folder, or to none."""

from __future__ import annotations

import os
import shutil
import site
import stat
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import hexaleg
from hexaleg import _compiled

PACKAGE_ROOT = Path(hexaleg.__file__).resolve().parent.parent
BOOT = (
    "import runpy, site, sys; n = len(sys.path); "
    "[site.addsitedir(folder) for folder in sys.argv[1].split(':')]; "  # .pth files too
    "sys.path[:] = sys.path[n:] + sys.path[:n]; "  # before the system's own dist-packages
    "sys.argv = ['hexaleg', *sys.argv[2:]]; "
    "runpy.run_module('hexaleg', run_name='__main__')"
)
"""Run hexaleg with this environment's site-packages (and their .pth files) first.

First: a system Python's dist-packages (Debian's python3-cffi-backend, say) must not
shadow what the environment installed.
"""


def test_the_cache_folder_is_private_and_named_by_the_compiled_sources(tmp_path, monkeypatch):
    monkeypatch.setattr(_compiled, "cache_candidates", lambda: [tmp_path / "a"])
    _compiled.cache_directory.cache_clear()
    try:
        directory = _compiled.cache_directory()
    finally:
        _compiled.cache_directory.cache_clear()
    assert directory == tmp_path / "a" / f"numba-{_compiled.source_fingerprint()}"
    assert stat.S_IMODE(directory.stat().st_mode) & 0o077 == 0


def test_an_unwritable_or_shared_folder_is_passed_over(tmp_path, monkeypatch):
    shared = tmp_path / "shared"
    shared.mkdir(mode=0o777)
    shared.chmod(0o777)  # others may write: numba's pickles there could be anyone's
    candidates = [Path("/proc/hexaleg-cannot-be-made"), shared, tmp_path / "mine"]
    monkeypatch.setattr(_compiled, "cache_candidates", lambda: candidates)
    _compiled.cache_directory.cache_clear()
    try:
        assert _compiled.cache_directory().parent == tmp_path / "mine"
        monkeypatch.setattr(_compiled, "cache_candidates", lambda: candidates[:2])
        _compiled.cache_directory.cache_clear()
        assert _compiled.cache_directory() is None  # then nothing is cached
    finally:
        _compiled.cache_directory.cache_clear()


def test_without_a_cache_folder_functions_still_compile(monkeypatch):
    monkeypatch.setattr(_compiled, "cache_directory", lambda: None)
    source = Path(_compiled.__file__).parent / "numerics" / "lp.py"
    namespace: dict[str, object] = {}
    code = compile("def double(x):\n    return 2 * x\n", str(source), "exec")
    exec(code, namespace)  # a function that claims lp.py as its source
    double = _compiled.compiled(namespace["double"])
    assert double(np.arange(3.0)).tolist() == [0.0, 2.0, 4.0]
    assert not double.dispatcher._cache_hits  # numba's dispatcher: nothing came from a cache


def test_a_function_of_an_unlisted_module_is_refused():
    def stray(x):
        return x

    with pytest.raises(RuntimeError, match="not in COMPILED_MODULES"):
        _compiled.compiled(stray)


def _interpreter_for(runuser: str, path: str) -> str | None:
    """A Python of this version that the user nobody can run and that imports hexaleg.

    A virtual environment's interpreter may live where nobody cannot go (under /root,
    say); the system's of the same version reads the same packages.
    """
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    candidates = [sys.executable, os.path.realpath(sys.executable)]
    candidates += [f"{folder}/{version}" for folder in ("/usr/bin", "/usr/local/bin")]
    for candidate in dict.fromkeys(candidates):
        probe = subprocess.run(
            [runuser, "-u", "nobody", "--", candidate, "-c", BOOT, path, "--help"],
            capture_output=True,
            cwd="/",
            env={"PATH": os.environ.get("PATH", ""), "PYTHONPATH": str(PACKAGE_ROOT)},
            timeout=120,
        )
        if probe.returncode == 0:
            return candidate
    return None


def _as_nobody(argv: list[str], timeout: float) -> subprocess.CompletedProcess[str]:
    """``argv`` run as the user nobody, whose home does not exist."""
    runuser = shutil.which("runuser")
    if runuser is None or not hasattr(os, "geteuid") or os.geteuid() != 0:
        pytest.skip("needs runuser and root to run a command as the user nobody")
    path = os.pathsep.join(site.getsitepackages())
    python = _interpreter_for(runuser, path)
    if python is None:
        pytest.skip(f"no Python {sys.version_info[:2]} that the user nobody can run imports {path}")
    env = {
        "PATH": os.environ.get("PATH", ""),
        "PYTHONPATH": str(PACKAGE_ROOT),
        "HOME": "/nonexistent",
    }
    return subprocess.run(
        [runuser, "-u", "nobody", "--", python, "-c", BOOT, path, *argv],
        capture_output=True,
        text=True,
        cwd="/",
        env=env,
        timeout=timeout,
    )


def test_a_user_without_a_writable_home_gets_a_urdf():
    result = _as_nobody(["urdf"], timeout=300)
    assert result.returncode == 0, result.stderr
    assert "<robot" in result.stdout and "Traceback" not in result.stderr


@pytest.mark.slow
def test_a_user_without_a_writable_home_gets_flexibility():
    """The compiled margins run (and compile, into a private temporary folder)."""
    result = _as_nobody(["flexibility", "--json"], timeout=900)
    assert result.returncode == 0, result.stderr
    assert '"fb"' in result.stdout and "Traceback" not in result.stderr


MATPLOTLIB_IMPORT = (
    "import os, sys; from hexaleg._compiled import use_private_matplotlib_cache; "
    "sys.argv[1] == 'set' and use_private_matplotlib_cache(); "
    "import matplotlib.pyplot; print(os.environ.get('MPLCONFIGDIR'))"
)


@pytest.mark.parametrize("call", ["set", "skip"])
def test_matplotlib_caches_beside_the_compiled_code_when_home_is_not_writable(tmp_path, call):
    home = tmp_path / "home"
    home.write_text("a file, not a folder: nothing can be made under it")
    skipped = ("XDG_", "MPLCONFIGDIR", "NUMBA_CACHE_DIR")  # the user's own folders
    env = {k: v for k, v in os.environ.items() if not k.startswith(skipped)}
    env |= {"HOME": str(home), "TMPDIR": str(tmp_path)}
    done = subprocess.run(
        [sys.executable, "-c", MATPLOTLIB_IMPORT, call],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
        check=True,
    )
    if call == "skip":  # what the command line spares the user
        assert "Matplotlib created a temporary cache directory" in done.stderr
        return
    user = os.getuid()
    assert done.stdout.strip() == str(tmp_path / f".hexaleg-cache-{user}" / "matplotlib")
    assert done.stderr == ""
