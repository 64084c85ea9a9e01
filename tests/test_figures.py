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
        ".hexaleg.json",  # the folder is marked as hexaleg's figures
        "manipulability_average_map.png",
        "manipulability_surface.png",
        "manipulability_surfaces_table5.png",
        "workspace_l1_series.png",
        "workspace_monte_carlo.png",
        "workspace_planar.png",
    ]
    for path in tmp_path.glob("*.png"):
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


def _overlap(a, b) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def test_planar_legend_leaves_the_workspace_visible_and_the_ground_is_drawn(default_design):
    from hexaleg.kinematics import planar_foot_position
    from hexaleg.output.figures import planar_workspace_figure
    from hexaleg.swing.workspace import planar_workspace

    rect = planar_workspace(default_design.lengths, default_design.workspace_limits)
    improved = planar_workspace(default_design.lengths, default_design.improved_limits)
    foot = tuple(planar_foot_position(default_design.lengths, 0.0, -np.pi / 2))
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = planar_workspace_figure(rect, improved, foot)
    FigureCanvasAgg(fig).draw()
    (ax,) = fig.axes
    renderer = fig.canvas.get_renderer()
    legend = fig.legends[0].get_window_extent(renderer)
    assert not _overlap(legend, ax.get_window_extent(renderer))
    labels = [text.get_text() for text in fig.legends[0].get_texts()]
    assert "ground at the nominal stance" in labels
    ground = next(
        line for line in ax.get_lines() if line.get_label() == "ground at the nominal stance"
    )
    assert ground.get_ydata()[0] == pytest.approx(-default_design.l3)


def test_monte_carlo_has_a_colour_bar_and_names_its_limits_as_the_paper(default_design):
    from hexaleg.output.figures import monte_carlo_figure
    from hexaleg.swing.workspace import monte_carlo_workspace

    fig = monte_carlo_figure(monte_carlo_workspace(default_design, samples=500))
    title = fig.axes[0].get_title()
    assert "Table 2 limits" in title and "workspace_limits" not in title
    assert len(fig.axes) == 2  # the cloud and its colour bar


def test_the_manipulability_surface_names_its_lengths(default_design, tmp_path):
    from hexaleg.output.figures import manipulability_surface_figure
    from hexaleg.swing.manipulability import manipulability_surface

    surface = manipulability_surface(default_design.lengths, default_design.manipulability_limits)
    fig = manipulability_surface_figure([surface], ["this design, l = (0.2, 0.4, 0.4) m"])
    assert "0.2, 0.4, 0.4" in fig.axes[0].get_title()


@pytest.mark.parametrize("peak", [90.0, 149.0, 160.0])
def test_a_rating_s_label_stays_inside_its_axes(peak):
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    from hexaleg.output.figures.marks import rating_line

    ax = Figure().subplots()
    ax.plot([0, 1], [20.0, peak])
    rating_line(ax, 150.0, "hip")
    ax.figure.canvas.draw()
    label = ax.texts[-1].get_window_extent()
    frame = ax.get_window_extent()
    assert frame.y0 <= label.y0 and label.y1 <= frame.y1  # the label inside the frame
    assert ax.get_ylim()[0] <= 20.0 and ax.get_ylim()[1] >= max(150.0, peak)


def test_the_ranges_figure_marks_both_designs_on_every_curve_and_names_each_once():
    import math

    import pandas as pd

    from hexaleg.output.figures.marks import your_and_recommended
    from hexaleg.output.figures.study import ranges_figure

    ratios = np.linspace(0.2, 0.6, 5)
    axes = ("x", "y", "z", "roll", "pitch", "yaw")
    rng = np.random.default_rng(3)
    table = pd.DataFrame(
        {"l1_ratio": 0.1, "l3_ratio": ratios}
        | {f"range_{a}": rng.uniform(0.1, 0.6, ratios.size) for a in axes}
    )
    yours, theirs = table.iloc[1].to_dict(), table.iloc[3].to_dict()
    figure = ranges_figure(table, 0.1, your_and_recommended(yours, theirs))
    panels = zip(figure.axes, (axes[:3], axes[3:]), (1.0, 180 / math.pi), strict=True)
    for ax, names, scale in panels:
        points = {tuple(np.round(c.get_offsets()[0], 12)) for c in ax.collections}
        expected = {
            (round(row["l3_ratio"], 12), round(row[f"range_{a}"] * scale, 12))
            for row in (yours, theirs)
            for a in names
        }
        assert points == expected  # each design on each of the panel's three curves
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert labels.count("your design") == 1 and sum("recommended" in t for t in labels) == 1
