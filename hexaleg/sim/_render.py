"""Child process of :mod:`hexaleg.sim.video`: render frames offscreen and encode them.

MuJoCo picks its OpenGL backend from ``MUJOCO_GL`` when first imported, so each
backend is tried in a process of its own: ``python -m hexaleg.sim._render FOLDER``
reads ``model.xml``, ``frames.npy`` (MuJoCo ``qpos`` per frame) and ``job.json``
from FOLDER and writes the animation to the file ``job.json`` names.
"""

from __future__ import annotations

import json
import sys
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
    """Render the job in ``folder`` (see the module docstring)."""
    import mujoco
    from PIL import Image

    job = json.loads((folder / "job.json").read_text())
    model = _scene((folder / "model.xml").read_text(), job["width"], job["height"])
    data = mujoco.MjData(model)
    camera = mujoco.MjvCamera()
    camera.type = mujoco.mjtCamera.mjCAMERA_FREE
    camera.azimuth, camera.elevation, camera.distance = (
        CAMERA_AZIMUTH,
        CAMERA_ELEVATION,
        job["distance"],
    )
    images = []
    with mujoco.Renderer(model, job["height"], job["width"]) as renderer:
        for qpos in np.load(folder / "frames.npy"):
            data.qpos[:] = qpos
            mujoco.mj_forward(model, data)
            camera.lookat[:] = [qpos[0], qpos[1], 0.5 * qpos[2]]
            renderer.update_scene(data, camera)
            images.append(Image.fromarray(renderer.render()))
    if len(images) == 1:
        images[0].save(job["output"])
        return
    images[0].save(
        job["output"],
        save_all=True,
        append_images=images[1:],
        duration=round(1000.0 / job["frame_rate"]),
        loop=0,
    )


if __name__ == "__main__":
    render(Path(sys.argv[1]))
