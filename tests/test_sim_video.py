"""The offscreen video: an animated image of the run, or nothing and a reason."""

from __future__ import annotations

import os

import numpy as np
import pinocchio as pin
import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.exceptions import HexalegError
from hexaleg.sim.video import VIDEO_SIZE, check_video_path

if not os.environ.get("CI"):  # CI installs hexaleg[test], which includes the sim extra
    pytest.importorskip("mujoco")

from hexaleg.sim.model import SimModel
from hexaleg.sim.video import write_video


@pytest.mark.parametrize("name", ["walk.mp4", "walk", "walk.png"])
def test_only_animated_image_suffixes_are_accepted(name):
    with pytest.raises(HexalegError, match=r"video = .* is not valid: .*\.gif or \.webp"):
        check_video_path(name)


@pytest.mark.slow
@pytest.mark.parametrize("suffix", [".gif", ".webp"])
def test_video_has_a_frame_per_configuration_and_shows_the_body_moving(tmp_path, suffix):
    from PIL import Image

    model = HexapodModel(HexapodDesign())
    sim = SimModel(model)
    frames = np.array(
        [model.configuration(pin.SE3(np.eye(3), np.array([x, 0.0, 0.4]))) for x in (0.0, 0.15, 0.3)]
    )
    target = tmp_path / f"walk{suffix}"
    outcome = write_video(sim, frames, 10.0, target)
    if outcome.path is None:
        if os.environ.get("CI"):
            pytest.fail(f"no offscreen OpenGL in CI: {outcome.tried}")
        pytest.skip(f"no offscreen OpenGL here: {outcome.tried}")
    assert outcome.path == target and outcome.backend in ("egl", "osmesa")
    with Image.open(target) as image:
        assert image.size == VIDEO_SIZE
        assert image.n_frames == 3
        pictures = []
        for k in range(3):
            image.seek(k)
            pictures.append(np.asarray(image.convert("RGB"), dtype=float))
    assert np.abs(pictures[0] - pictures[2]).mean() > 1.0  # the floor moves under the camera
    assert not list(tmp_path.glob(".*"))  # no temporary file left beside it


@pytest.mark.slow
def test_still_is_one_png_picture(tmp_path):
    from PIL import Image

    from hexaleg.sim.video import write_still

    model = HexapodModel(HexapodDesign())
    outcome = write_still(SimModel(model), model.nominal_configuration(), tmp_path / "still.png")
    if outcome.path is None:
        if os.environ.get("CI"):
            pytest.fail(f"no offscreen OpenGL in CI: {outcome.tried}")
        pytest.skip(f"no offscreen OpenGL here: {outcome.tried}")
    with Image.open(outcome.path) as image:
        assert image.format == "PNG" and image.size == VIDEO_SIZE
        pixels = np.asarray(image.convert("RGB"), dtype=float)
    assert pixels.std() > 10.0  # a picture, not a blank frame


def test_still_must_be_png():
    from hexaleg.sim.video import write_still

    with pytest.raises(HexalegError, match=r"still = 'x\.jpg' is not valid"):
        write_still(None, np.zeros(25), "x.jpg")  # type: ignore[arg-type]
