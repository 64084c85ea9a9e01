"""Child process of :mod:`hexaleg.sim.video`: render frames offscreen and encode them.

MuJoCo picks its OpenGL backend from ``MUJOCO_GL`` when first imported, so each
backend is tried in a process of its own: ``python -m hexaleg.sim._render FOLDER``
reads ``model.xml``, ``frames.npy`` (MuJoCo ``qpos`` per frame) and ``job.json``
from FOLDER and writes the animation to the file ``job.json`` names.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

CAMERA_AZIMUTH = 135.0
"""Camera direction around the body, from the world's x axis [deg] (MuJoCo's unit)."""
CAMERA_ELEVATION = -20.0
"""Camera elevation [deg] (MuJoCo's unit)."""


def _scene(xml: str, width: int, height: int) -> Any:
    """The simulated model with a chequered floor, a light, and a framebuffer of the size."""
    import mujoco

    spec = mujoco.MjSpec.from_string(xml)
    spec.add_texture(
        name="grid",
        type=mujoco.mjtTexture.mjTEXTURE_2D,
        builtin=mujoco.mjtBuiltin.mjBUILTIN_CHECKER,
        rgb1=[0.92, 0.92, 0.92],
        rgb2=[0.80, 0.80, 0.80],
        width=512,
        height=512,
    )
    spec.add_texture(
        name="sky",
        type=mujoco.mjtTexture.mjTEXTURE_SKYBOX,
        builtin=mujoco.mjtBuiltin.mjBUILTIN_GRADIENT,
        rgb1=[0.95, 0.96, 0.98],
        rgb2=[0.70, 0.78, 0.86],
        width=256,
        height=1536,
    )
    material = spec.add_material(name="grid", texrepeat=[8.0, 8.0])
    material.textures[mujoco.mjtTextureRole.mjTEXROLE_RGB] = "grid"
    floor = spec.geom("floor")
    floor.material, floor.size = "grid", [20.0, 20.0, 1.0]
    spec.worldbody.add_light(pos=[0.0, 0.0, 4.0], dir=[0.0, 0.0, -1.0], diffuse=[0.5] * 3)
    spec.visual.headlight.ambient, spec.visual.headlight.diffuse = [0.35] * 3, [0.5] * 3
    spec.visual.global_.offwidth, spec.visual.global_.offheight = width, height
    # software OpenGL (Mesa) is slow: a small shadow map and no multisampling keep a frame
    # near a tenth of a second
    spec.visual.quality.shadowsize, spec.visual.quality.offsamples = 1024, 0
    return spec.compile()


def render(folder: Path) -> None:
    """Render the job in ``folder`` (see the module docstring).

    Each frame goes to the encoder as soon as it is rendered: what is held is one frame
    and the encoder's output, never every frame.
    """
    job = json.loads((folder / "job.json").read_text())
    frames = np.load(folder / "frames.npy", mmap_mode="r")
    pictures = _pictures(folder, job, frames)
    output = Path(job["output"])
    if len(frames) == 1:
        next(pictures).save(output)
    elif output.suffix.lower() == ".gif":
        _write_gif(pictures, round(1000.0 / job["frame_rate"]), output)
    else:
        _write_webp(pictures, len(frames), round(1000.0 / job["frame_rate"]), output)


def _pictures(folder: Path, job: dict[str, Any], frames: Any) -> Iterator[Any]:
    """Each frame's picture (a Pillow image), rendered when asked for."""
    import mujoco
    from PIL import Image

    model = _scene((folder / "model.xml").read_text(), job["width"], job["height"])
    data = mujoco.MjData(model)
    camera = mujoco.MjvCamera()
    camera.type = mujoco.mjtCamera.mjCAMERA_FREE
    camera.azimuth, camera.elevation, camera.distance = (
        CAMERA_AZIMUTH,
        CAMERA_ELEVATION,
        job["distance"],
    )
    with mujoco.Renderer(model, job["height"], job["width"]) as renderer:
        for qpos in frames:
            data.qpos[:] = qpos
            mujoco.mj_forward(model, data)
            camera.lookat[:] = [qpos[0], qpos[1], 0.5 * qpos[2]]
            renderer.update_scene(data, camera)
            yield Image.fromarray(renderer.render())


def _write_gif(pictures: Iterator[Any], duration: int, output: Path) -> None:
    """An animated GIF written frame by frame, each with its own palette, looping forever.

    Pillow's ``save_all`` keeps every frame until the end (to merge and crop them), so
    the file is put together here from its header and frame blocks (Pillow's
    ``getheader`` and ``getdata``, the GIF format's own pieces).
    """
    from PIL import GifImagePlugin, Image

    with output.open("wb") as file:
        for k, picture in enumerate(pictures):
            frame = picture.convert("P", palette=Image.Palette.ADAPTIVE)
            if k == 0:
                header, _ = GifImagePlugin.getheader(frame, info={"loop": 0, "duration": duration})
                file.write(b"".join(header))
            for block in GifImagePlugin.getdata(frame, duration=duration, include_color_table=True):
                file.write(block)
        file.write(b";")  # the trailer


def _write_webp(pictures: Iterator[Any], count: int, duration: int, output: Path) -> None:
    """An animated WebP: libwebp's encoder takes the frames one at a time."""
    first = next(pictures)
    first.save(
        output,
        save_all=True,
        append_images=[_Sequence(first, pictures, count - 1)],
        duration=duration,
        loop=0,
    )


class _Sequence:
    """``count`` frames as a multi-frame image that renders each when Pillow seeks it.

    Pillow's WebP writer reads a multi-frame image in ``append_images`` by ``n_frames``
    and ``seek``, one frame at a time, as it reads a file.
    """

    def __init__(self, first: Any, pictures: Iterator[Any], count: int) -> None:
        self.n_frames, self._pictures, self._current = count, pictures, first
        self.mode, self.size = first.mode, first.size
        self.info: dict[str, Any] = {}

    def seek(self, frame: int) -> None:
        self._current = next(self._pictures)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._current, name)


if __name__ == "__main__":
    render(Path(sys.argv[1]))
