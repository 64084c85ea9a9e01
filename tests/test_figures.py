"""Figures: every one is written as a real PNG, atomically, through the CLI and the API."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.cli import main

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _assert_png(path, min_size=20_000):
    data = path.read_bytes()
    assert data.startswith(PNG_MAGIC)
    assert len(data) > min_size  # a blank canvas compresses to a few kB


@pytest.mark.slow
def test_swing_figures_from_the_cli(tmp_path):
    assert main(["workspace", "--samples", "2000", "--plot", str(tmp_path)]) == 0
    assert main(["manipulability", "--plot", str(tmp_path)]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == [
        "manipulability_average_map.png",
        "manipulability_surface.png",
        "manipulability_surfaces_table5.png",
        "workspace_l1_series.png",
        "workspace_monte_carlo.png",
        "workspace_planar.png",
    ]
    for path in tmp_path.iterdir():
        _assert_png(path)


def test_figures_are_not_blank(tmp_path, default_design):
    from PIL import Image

    from hexaleg.output.figures import planar_workspace_figure, save
    from hexaleg.swing.workspace import planar_workspace

    rect = planar_workspace(default_design.lengths, default_design.workspace_limits)
    improved = planar_workspace(default_design.lengths, default_design.improved_limits)
    path = save(planar_workspace_figure(rect, improved), tmp_path / "planar.png")
    pixels = np.asarray(Image.open(path).convert("L"))
    assert (pixels < 250).mean() > 0.05  # a meaningful share is drawn


def test_study_figures(tmp_path):
    from hexaleg.output.figures import write_study_figures
    from hexaleg.study import StudySpec, run_study

    spec = StudySpec((0.05, 0.2), tuple(np.linspace(0.1, 0.7, 8)))
    from concurrent.futures import ThreadPoolExecutor

    table = run_study(spec, tmp_path, executor=ThreadPoolExecutor(2))
    paths = write_study_figures(table, tmp_path)
    assert sorted(p.name for p in paths) == ["flexibility_fb.png", "flexibility_ranges.png"]
    for path in paths:
        _assert_png(path)
