"""Memory bounded by design: a long run needs about what a short one does.

Each command runs in a child process whose peak resident memory (its own and its
children's, as the kernel counts it) is read back; the long case must stay within a
margin of the short one. Before the fix, the simulation held every step (about 2 kB per
millisecond simulated), the renderer every frame (1.5 MB each) and the gait's stride scan
eight copies of every sample's margins: each long case here then needed at least 1.6
times its short one.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

MARGIN = 1.3
"""How much more a long case may need than its short one [-]."""

_MEASURE = """
import resource, subprocess, sys
done = subprocess.run(sys.argv[1:], capture_output=True, text=True)
sys.stderr.write(done.stderr)
print(done.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
"""


def _peak(tmp: Path, *args: str) -> tuple[int, str]:
    """Peak resident memory [kB] of ``hexaleg ARGS`` run in ``tmp``, and its stderr."""
    result = subprocess.run(
        [sys.executable, "-c", _MEASURE, sys.executable, "-m", "hexaleg", *args],
        cwd=tmp,
        capture_output=True,
        text=True,
        check=False,
        timeout=1200,
    )
    status, peak = result.stdout.split()
    assert status == "0", result.stderr[-2000:]
    return int(peak), result.stderr


def _within(short: int, long: int) -> None:
    assert long <= MARGIN * short, f"long case {long / 1e3:.0f} MB, short {short / 1e3:.0f} MB"


@pytest.mark.slow
def test_a_long_simulation_needs_about_what_a_short_one_does(tmp_path):
    pytest.importorskip("mujoco")
    # 36 s and 360 s simulated: 36 000 and 360 000 steps
    short, _ = _peak(tmp_path, "simulate", "--cycles", "2", "--period", "18")
    long, _ = _peak(tmp_path, "simulate", "--cycles", "20", "--period", "18")
    _within(short, long)


@pytest.mark.slow
def test_a_long_video_needs_about_what_a_short_one_does(tmp_path):
    pytest.importorskip("mujoco")
    # 100 and 400 frames of 640 × 480
    short, err = _peak(tmp_path, "simulate", "--cycles", "2", "--video", "short.gif")
    if "--video skipped" in err:
        if os.environ.get("CI"):
            pytest.fail(f"no offscreen OpenGL in CI: {err}")
        pytest.skip(f"no offscreen OpenGL here: {err}")
    long, _ = _peak(tmp_path, "simulate", "--cycles", "8", "--video", "long.gif")
    from PIL import Image

    with Image.open(tmp_path / "long.gif") as image:
        assert image.n_frames == 400
    _within(short, long)


@pytest.mark.slow
def test_many_gait_samples_and_their_animation_need_about_what_few_do(tmp_path):
    # 2000 and 20 000 samples: what the analysis holds grows by about 60 MB
    short, _ = _peak(tmp_path, "gait", "--samples", "2000", "--html", "short.html")
    long, _ = _peak(tmp_path, "gait", "--samples", "20000", "--html", "long.html")
    _within(short, long)
