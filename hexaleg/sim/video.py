"""A simulated run as an animated image or a still, rendered by MuJoCo offscreen (EGL or OSMesa).

MuJoCo renders without a display through EGL (``libegl1``, with Mesa's software
driver where there is no GPU) or OSMesa (``libosmesa6``), chosen by ``MUJOCO_GL`` when
it is first imported. Each backend is therefore tried in a child process
(:mod:`hexaleg.sim._render`): the user's own ``MUJOCO_GL`` first, then EGL, then
OSMesa. Where none works, :func:`write_video` writes nothing and says which it tried.
Frames are encoded by Pillow as an animated GIF or WebP, chosen by the file's suffix,
each as soon as it is rendered (at most :data:`MAX_VIDEO_FRAMES`); a still is a PNG.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hexaleg._io import write_bytes
from hexaleg._typing import ArrayF
from hexaleg.exceptions import ParameterError
from hexaleg.sim.model import SimModel

VIDEO_SUFFIXES = (".gif", ".webp")
"""The animated image formats ``--video`` writes."""
BACKENDS = ("egl", "osmesa")
"""MuJoCo's offscreen OpenGL backends, in the order tried."""
VIDEO_SIZE = (640, 480)
"""Frame width and height [px]."""
RENDER_TIMEOUT = 900.0
"""Longest a backend may take to render [s]."""
MAX_VIDEO_FRAMES = 2500
"""Most frames a video holds: software OpenGL renders a frame in about a tenth of a second,
so these fit in :data:`RENDER_TIMEOUT`. A longer run is shown at a lower frame rate,
still in real time (every second frame from 100 s of simulation at 25 frames a second)."""


@dataclass(frozen=True)
class RenderOutcome:
    """What :func:`write_video` or :func:`write_still` did.

    Attributes:
        path: The file written, or None where no backend could render.
        backend: The backend that rendered, or None.
        tried: Each backend tried, with the last line of its error where it failed.

    """

    path: Path | None
    backend: str | None
    tried: tuple[str, ...]


def check_video_path(path: str | os.PathLike[str]) -> Path:
    """``path`` if it ends in a suffix of :data:`VIDEO_SUFFIXES`; else a one-line error."""
    target = Path(path)
    if target.suffix.lower() not in VIDEO_SUFFIXES:
        raise ParameterError(
            "video",
            str(path),
            f"the file must end in {' or '.join(VIDEO_SUFFIXES)} (animated image)",
        )
    return target


def write_video(
    sim: SimModel, frames: ArrayF, frame_rate: float, path: str | os.PathLike[str]
) -> RenderOutcome:
    """Render Pinocchio configurations ``frames`` (F, nq) of ``sim`` into ``path``.

    Frames are encoded as they are rendered, so memory does not grow with their number;
    past :data:`MAX_VIDEO_FRAMES`, every k-th frame is kept, shown k times as long.

    Args:
        sim: The simulated model (its scene is rendered).
        frames: The robot's configuration in each frame (Pinocchio's layout).
        frame_rate: Frames per second [1/s].
        path: The file to write, ``.gif`` or ``.webp``; written atomically, or not at all.

    """
    target = check_video_path(path)
    every = math.ceil(len(frames) / MAX_VIDEO_FRAMES)
    return _render_files(sim, frames[::every], frame_rate / every, target)


def write_still(sim: SimModel, q: ArrayF, path: str | os.PathLike[str]) -> RenderOutcome:
    """Render one Pinocchio configuration ``q`` of ``sim`` as a PNG picture at ``path``."""
    target = Path(path)
    if target.suffix.lower() != ".png":
        raise ParameterError("still", str(path), "the file must end in .png")
    return _render_files(sim, np.asarray(q, dtype=float)[None, :], 1.0, target)


def _render_files(sim: SimModel, frames: ArrayF, frame_rate: float, target: Path) -> RenderOutcome:
    """Render ``frames`` into ``target`` with the first backend that works."""
    reach = float(np.abs(sim.hexapod.design.nominal_footholds[:, :2]).max())
    tried: list[str] = []
    with tempfile.TemporaryDirectory(prefix="hexaleg-video-") as tmp:
        folder = Path(tmp)
        output = folder / f"render{target.suffix.lower()}"
        (folder / "model.xml").write_text(sim.spec.to_xml())
        np.save(folder / "frames.npy", np.array([sim.qpos_of(q) for q in frames]))
        job: dict[str, float | str] = {"width": VIDEO_SIZE[0], "height": VIDEO_SIZE[1]}
        job |= {"frame_rate": frame_rate, "distance": 3.2 * reach, "output": str(output)}
        (folder / "job.json").write_text(json.dumps(job))
        for backend in _backends():
            error = _render(folder, backend)
            if error is None and output.is_file():
                written = write_bytes(target, output.read_bytes())
                return RenderOutcome(written, backend, (*tried, backend))
            tried.append(f"{backend} ({error or 'wrote nothing'})")
    return RenderOutcome(None, None, tuple(tried))


def _backends() -> tuple[str, ...]:
    own = os.environ.get("MUJOCO_GL", "").strip().lower()
    return tuple(dict.fromkeys((own, *BACKENDS) if own in BACKENDS else BACKENDS))


def _render(folder: Path, backend: str) -> str | None:
    """Run the renderer with ``backend``; None on success, else its last error line."""
    env = dict(os.environ, MUJOCO_GL=backend, PYOPENGL_PLATFORM=backend)
    try:
        result = subprocess.run(
            [sys.executable, "-m", "hexaleg.sim._render", str(folder)],
            env=env,
            capture_output=True,
            text=True,
            timeout=RENDER_TIMEOUT,
            check=False,
        )
    except subprocess.TimeoutExpired:
        return f"no frames within {RENDER_TIMEOUT:g} s"
    if result.returncode == 0:
        return None
    lines = [line for line in result.stderr.strip().splitlines() if line.strip()]
    return lines[-1].strip() if lines else f"exit status {result.returncode}"
