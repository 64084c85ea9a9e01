"""Figures: every one is written as a real PNG, atomically, through the CLI and the API."""

from __future__ import annotations

import io
import json

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


def _study_rows(l1_ratios, l3_ratios, rng):
    import pandas as pd

    axes = ("x", "y", "z", "roll", "pitch", "yaw")
    rows = [
        {"l1_ratio": r1, "l3_ratio": r3}
        | {f"range_{a}": float(rng.uniform(0.1, 0.6)) for a in axes}
        for r1 in l1_ratios
        for r3 in l3_ratios
    ]
    return pd.DataFrame(rows)


def test_the_ranges_figure_draws_only_the_designs_at_its_own_coxa_ratio():
    from hexaleg.output.figures.marks import your_and_recommended
    from hexaleg.output.figures.study import ranges_figure

    table = _study_rows((0.05, 0.2), np.linspace(0.2, 0.6, 5), np.random.default_rng(5))
    yours = table.iloc[7].to_dict()  # coxa ratio 0.2: not on the 0.05 panel
    theirs = table.iloc[2].to_dict()  # coxa ratio 0.05
    figure = ranges_figure(table, 0.05, your_and_recommended(yours, theirs))
    for ax, names, scale in zip(
        figure.axes, (("x", "y", "z"), ("roll", "pitch", "yaw")), (1.0, 180 / np.pi), strict=True
    ):
        points = {tuple(np.round(c.get_offsets()[0], 12)) for c in ax.collections}
        assert points == {
            (round(theirs["l3_ratio"], 12), round(theirs[f"range_{a}"] * scale, 12)) for a in names
        }
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert "your design" not in labels and sum("recommended" in t for t in labels) == 1
    title = figure.get_suptitle()
    assert "your design 0.20" in title and "not drawn" in title  # said, not silently dropped


def _walking_table(rng):
    """A study's walking columns: CoT spread 10 % (0.088–0.098) as on the default grid."""
    import pandas as pd

    rows = []
    for r1 in (0.1, 0.2):
        for r3 in np.linspace(0.4, 0.7, 12):
            rows.append({
                "l1_ratio": r1, "l3_ratio": r3, "walks": bool(r3 > 0.42),
                "gait_peak_hip_torque": 70 + 80 * (0.7 - r3) / 0.3 + rng.uniform(0, 2),
                "gait_peak_knee_torque": 23 + 4 * (0.7 - r3) / 0.3,
                "mechanical_cost_of_transport": 0.088 + 0.01 * ((r3 - 0.6) / 0.2) ** 2,
                "walking_payload_capacity": 90 * (r3 - 0.42) / 0.28,
            })  # fmt: skip
    return pd.DataFrame(rows)


def test_the_walking_figure_reads_each_magnitude_from_zero_and_states_a_narrow_spread():
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from hexaleg.output.figures.gait import walking_study_figure

    table = _walking_table(np.random.default_rng(2))
    figure = walking_study_figure(table, {"hip": 150.0, "knee": 120.0})
    FigureCanvasAgg(figure).draw()
    columns = ("gait_peak_hip_torque", "gait_peak_knee_torque", "mechanical_cost_of_transport",
               "walking_payload_capacity")  # fmt: skip
    walking = table[table["walks"]]
    for ax, column in zip(figure.axes, columns, strict=True):
        low, high = ax.get_ylim()
        assert low == 0.0 and high >= walking[column].max()  # the whole magnitude, from 0
        assert ax.yaxis.get_offset_text().get_text() == ""  # ticks are values, not offsets
    cot = walking["mechanical_cost_of_transport"]
    note = " ".join(t.get_text() for t in figure.axes[2].texts)
    assert f"{cot.min():.3g} to {cot.max():.3g}" in note  # the 10 % spread, in numbers
    spread = 100 * (cot.max() - cot.min()) / cot.max()
    assert f"all within {spread:.0f} %" in note
    assert not figure.axes[3].texts  # the payload spreads over its whole axis: no note


def _marker_disks(ax, renderer):
    """Every scatter marker of ``ax``: centre (display px) and radius [px]."""
    centres, radii = [], []
    for collection in ax.collections:
        offsets = collection.get_offset_transform().transform(collection.get_offsets())
        sizes = np.resize(collection.get_sizes(), len(offsets))
        centres.append(offsets)
        radii.append(np.sqrt(sizes) / 2 * renderer.points_to_pixels(1.0))
    return np.vstack(centres), np.concatenate(radii)


def _crowded_front():
    """A Pareto front whose largest walker has other designs all along its left, as on the
    default grid (coxa 0.20's 94 kg beside coxa 0.10's and 0.15's)."""
    import pandas as pd

    rows = []
    for r1, reach, slope in ((0.1, 73.0, 0.0014), (0.15, 89.0, 0.0011), (0.2, 94.0, 0.0009)):
        for x in np.linspace(0.0, reach, 22):
            rows.append({"l1_ratio": r1, "l3_ratio": 0.4 + x / 200, "l1": r1, "l2": 0.3,
                         "l3": 0.4, "walking_payload_capacity": x, "fb": 0.242 - slope * x,
                         "walks": True})  # fmt: skip
    table = pd.DataFrame(rows)
    return table, table.sort_values("fb", ascending=False)


def test_the_pareto_front_names_its_largest_design_where_the_name_hides_no_point():
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text

    from hexaleg.output.figures.study import pareto_figure

    table, front = _crowded_front()
    figure = pareto_figure(table, front)
    FigureCanvasAgg(figure).draw()
    renderer = figure.canvas.get_renderer()
    (ax,) = figure.axes
    (label,) = [t for t in ax.texts if t.get_text().startswith("94 kg")]
    box = Text.get_window_extent(label, renderer)  # the words, not the leader line
    centres, radii = _marker_disks(ax, renderer)
    nearest_x = np.clip(centres[:, 0], box.x0, box.x1)  # the box's point nearest each centre
    nearest_y = np.clip(centres[:, 1], box.y0, box.y1)
    gaps = np.hypot(centres[:, 0] - nearest_x, centres[:, 1] - nearest_y) - radii
    assert gaps.min() > 0, f"the label covers {int((gaps <= 0).sum())} markers"
    frame = ax.get_window_extent(renderer)
    assert frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 <= box.y1 <= frame.y1
    spot = label.xyann
    figure.savefig(io.BytesIO(), format="svg")  # 72 dpi: the same spot as the 150 dpi PNG
    assert label.xyann == spot


def _motor_design():
    from hexaleg import HexapodDesign
    from hexaleg.actuators import Actuator, Actuators

    keys = dict(torque_constant=0.12, resistance=0.3, gearbox_efficiency=0.85, voltage=48.0)
    return HexapodDesign(actuators=Actuators(
        Actuator(60.0, peak_torque=80.0, continuous_torque=50.0, mass=0.8, **keys),
        Actuator(100.0, peak_torque=250.0, continuous_torque=150.0, mass=2.0, **keys),
        Actuator(80.0, peak_torque=150.0, continuous_torque=90.0, mass=1.2, **keys),
    ))  # fmt: skip


def test_the_motor_envelope_fits_its_samples_and_its_legend_names_only_what_is_drawn(tmp_path):
    from matplotlib.colors import to_rgb
    from PIL import Image

    from hexaleg.gait import analyze_gait
    from hexaleg.gait.analysis import STUDY_GAIT
    from hexaleg.output.figures.canvas import DPI, TEXTS_KEY, save
    from hexaleg.output.figures.gait import LEG_COLORS
    from hexaleg.output.figures.motors import envelope_figure

    walked = analyze_gait(_motor_design(), STUDY_GAIT, limits=False)
    figure = envelope_figure(walked)
    path = save(figure, tmp_path / "envelope.png")
    panels = figure.axes[:3]
    for j, ax in enumerate(panels):  # the samples fill the axes: at least 60 % each way
        speeds = np.abs(walked.joint_velocities[:, :, j]).max()
        torques = np.abs(walked.joint_torques[:, :, j]).max()
        assert speeds >= 0.6 * ax.get_xlim()[1] and torques >= 0.6 * ax.get_ylim()[1]
    with Image.open(path) as image:
        pixels = np.asarray(image.convert("RGB")).astype(int)
        texts = " ".join(json.loads(image.text[TEXTS_KEY]))
    height = pixels.shape[0]
    inside = np.zeros(pixels.shape[:2], dtype=bool)  # the panels' pixels, not the legend's
    for ax in panels:
        x0, y0, x1, y1 = (np.array(ax.get_window_extent().extents) * DPI / figure.dpi).round()
        inside[height - int(y1) : height - int(y0), int(x0) : int(x1)] = True
    legend = [t.get_text() for t in figure.legends[0].get_texts()]
    for leg, color in zip(walked.legs, LEG_COLORS, strict=False):
        rgb = np.round(np.array(to_rgb(color)) * 255).astype(int)
        seen = int(((pixels == rgb).all(axis=2) & inside).sum())
        if leg in legend:
            assert seen > 0, f"{leg} is in the legend but not one of its pixels is drawn"
        else:
            assert seen == 0 and any(leg in t and "under" in t for t in legend)
    assert sum(leg in legend for leg in walked.legs) < len(walked.legs)  # some legs overlap
    for joint, actuator in zip(("root", "hip", "knee"), walked.design.actuators.joints,
                               strict=True):  # fmt: skip
        ax = panels[("root", "hip", "knee").index(joint)]
        if actuator.rated_speed > ax.get_xlim()[1]:  # off the axes: named with its value
            assert f"speed rating {actuator.rated_speed:.3g} rad/s" in texts
