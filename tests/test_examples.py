"""Every example runs as a user would run it and prints what examples/README.md says."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
EXPECTED = {
    "01_urdf_and_kinematics.py": ["18 revolute joints", "reachable = True", "on the ground"],
    "02_workspace_and_manipulability.py": ["θ2 = 35.6827°", "θ3 = -71.3655°", "1.75665e+08 mm³"],
    "03_body_flexibility.py": ["stance all: FB = 0.2307", "stopped by", "free-coupled"],
    "04_design_study.py": [
        "34 designs",
        "FB peaks at l3 ratio",
        "flexibility_fb.png",
        "removed: pass OUTPUT_DIR to keep",
    ],
    "05_dask_study.py": ["scheduler at tcp://127.0.0.1:", "9 designs"],
    "06_hexagonal_robot.py": [
        "hexagon_robot.toml: hexagon layout",
        "pointing  +30.0°",
        "stopped by",
        "payload capacity",
        "body_radius = 0.45 m: peak FB",
    ],
}

SLOW = {
    "03_body_flexibility.py",
    "04_design_study.py",
    "05_dask_study.py",
    "06_hexagonal_robot.py",
}
"""Examples that take more than a few seconds (a study, a cluster, the free mode, a body sweep)."""


@pytest.mark.skipif(not EXAMPLES.is_dir(), reason="examples/ not shipped in this install")
@pytest.mark.parametrize(
    "script",
    [pytest.param(s, marks=pytest.mark.slow) if s in SLOW else s for s in sorted(EXPECTED)],
)
def test_example_runs_and_prints_what_it_should(script, tmp_path):
    """Each example runs in a temp folder of its own, which it must leave empty (Dask's
    scratch space and the study folders included)."""
    import os

    temp = tmp_path / "temp"
    temp.mkdir()
    env = {**os.environ, "TMPDIR": str(temp)}
    argv = [sys.executable, str(EXAMPLES / script)]
    result = subprocess.run(
        argv, capture_output=True, text=True, timeout=300, cwd=tmp_path, env=env
    )
    assert result.returncode == 0, result.stderr
    for fragment in EXPECTED[script]:
        assert fragment in result.stdout, (fragment, result.stdout)
    assert list(temp.iterdir()) == []  # nothing left behind
    assert sorted(p.name for p in tmp_path.iterdir()) == ["temp"]


def test_every_example_is_listed():
    scripts = sorted(p.name for p in EXAMPLES.glob("*.py"))
    assert scripts == sorted(EXPECTED)
    readme = (EXAMPLES / "README.md").read_text()
    for script in scripts:
        assert script in readme
