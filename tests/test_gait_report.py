"""Walking across a study, the report's Walking section, the study figure and the animation."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.evaluation.metrics import METRICS
from hexaleg.gait import Gait, analyze_gait
from hexaleg.gait.analysis import STUDY_GAIT
from hexaleg.output.figures.canvas import save
from hexaleg.output.figures.gait import walking_study_figure
from hexaleg.output.report.study_record import StudyRecord
from hexaleg.output.report.walking import WalkingRecord, section
from hexaleg.study.rows import StudyRow, design_walking_row
from hexaleg.study.sweep import StudySpec, sweep_in_process
from hexaleg.study.walking import WalkingComparison, walking_comparison, walking_or_none


@pytest.fixture(scope="module")
def small_study():
    spec = StudySpec((0.1, 0.2), (0.3, 0.45, 0.6, 0.76))
    return spec, sweep_in_process(spec)


def test_the_comparison_picks_the_least_and_measures_the_paper_leg(small_study):
    spec, table = small_study
    comparison = walking_comparison(table, spec)
    walking = table[table["walks"]]  # unloaded, within every rating: as the ranking counts
    assert comparison.walking == len(walking) < comparison.designs == 8  # 0.2 + 0.76 cannot
    least_torque, least_energy = comparison.least_torque.metrics, comparison.least_energy.metrics
    assert least_torque.gait_peak_torque == walking["gait_peak_torque"].min()
    assert least_energy.mechanical_cost_of_transport == (
        walking["mechanical_cost_of_transport"].min()
    )
    paper = HexapodDesign()  # the 0.2/0.4/0.4 leg on the default body
    single = analyze_gait(paper, STUDY_GAIT, model=HexapodModel(paper))
    assert comparison.reference.metrics.gait_peak_torque == pytest.approx(
        max(single.metrics.peak_torque.values()), rel=1e-12
    )
    assert comparison.reference.key == (0.2, 0.4)
    expected = 1 - least_torque.value(METRICS.gait_peak_torque) / max(
        single.metrics.peak_torque.values()
    )
    assert comparison.torque_saving == pytest.approx(expected, rel=1e-12)
    assert comparison.to_dict()["peak_torque_saving"] == comparison.torque_saving


def test_a_study_without_walking_columns_or_walkers_has_no_comparison(small_study):
    spec, table = small_study
    assert walking_or_none(table.drop(columns=["gait_peak_torque"]), spec) is None
    assert walking_or_none(table.assign(gait_feasible=False), spec) is None


def _comparison(torque: float, energy: float) -> WalkingComparison:
    base = {
        "l1_ratio": 0.2, "l3_ratio": 0.4, "gait_peak_torque": 100.0,
        "mechanical_cost_of_transport": 0.1, "max_speed": 0.4,
        "gait_peak_root_torque": 5.0, "gait_peak_hip_torque": 100.0,
        "gait_peak_knee_torque": 20.0, "max_speed_limited_by": "lm hip torque at its rating",
    }  # fmt: skip
    best = base | {
        "l3_ratio": 0.6,
        "gait_peak_torque": torque,
        "mechanical_cost_of_transport": energy,
        "max_speed": 0.3,
        "max_speed_limited_by": "lf knee speed at its rating",
    }
    rows = _row(base), _row(best)
    return WalkingComparison(rows[0], rows[1], rows[1], 5, 8, STUDY_GAIT.to_dict())


def _row(values: dict) -> StudyRow:
    return StudyRow.from_dict({"l1_ratio": 0.2, "l3_ratio": 0.4} | values)


@pytest.mark.parametrize(
    ("torque", "energy", "verdict"),
    [
        (70.0, 0.075, "both savings exceed the sequel's 20 %"),
        (70.0, 0.095, "the torque saving exceeds the sequel's 20 %, the energy saving does not"),
        (90.0, 0.075, "the energy saving exceeds the sequel's 20 %, the torque saving does not"),
        (90.0, 0.095, "neither saving reaches the sequel's 20 %"),
        (257.0, 0.095, "neither saving reaches the sequel's 20 %"),  # 157 % more torque
    ],
)
def test_the_section_states_the_claim_whatever_the_grid_shows(torque, energy, verdict):
    text = _section_text(_comparison(torque, energy))
    assert verdict in text
    change = 100 * (1 - torque / 100)  # the saving against the paper's leg's 100 N·m
    words = f"{abs(change):.0f} % {'less' if change >= 0 else 'more'} peak torque"
    assert f"the least-torque leg needs {words} than the paper's leg" in text
    claim = text.split("The sequel")[1].split("\n")[0].split("|")[0]
    assert "-" not in claim.replace("least-", "")  # savings in words, never negative
    assert "its hip" in text and "walks slower" in text and "study_walking" in text
    assert "| least peak torque | 0.2 | 0.6 |" in text
    assert "standing at your posture θ = (0.000, 0.000, -1.571) rad on level ground" in text


def test_the_least_cost_leg_is_chosen_among_the_legs_that_walk_within_their_ratings(
    small_study,
):
    spec, table = small_study
    walking = table[table["walks"]]
    cheapest = walking["mechanical_cost_of_transport"].idxmin()
    # another leg that walks the period but beyond a rating, and costs less than every walker
    over = table.index[table["gait_feasible"] & ~table["walks"]]
    assert len(over), "the small study has a leg over its ratings"
    table = table.copy()
    table.loc[over[0], "mechanical_cost_of_transport"] = (
        0.5 * walking["mechanical_cost_of_transport"].min()
    )
    table.loc[over[0], "gait_peak_torque"] = 0.5 * walking["gait_peak_torque"].min()
    comparison = walking_comparison(table, spec)
    assert comparison.least_energy.key == tuple(table.loc[cheapest, ["l1_ratio", "l3_ratio"]])
    assert comparison.least_energy.columns["walks"] and comparison.least_torque.columns["walks"]
    assert comparison.walking == int(table["walks"].sum())


def _section_text(comparison: WalkingComparison | None) -> str:
    from hexaleg.output.report.motors import MotorsRecord
    from hexaleg.output.report.options import ReportOptions
    from hexaleg.output.report.part import ReportData

    study = StudyRecord(StudySpec((0.2,), (0.4, 0.6)), pd.DataFrame(), _row({}))
    records = {
        WalkingRecord: WalkingRecord(comparison),
        MotorsRecord: MotorsRecord(None),
        StudyRecord: study,
    }
    data = ReportData(HexapodDesign(), ReportOptions(), None, records)  # type: ignore[arg-type]
    found = section(data)
    return found.title + "\n" + "\n".join(str(block) for block in found.blocks)


def test_no_walking_design_is_said_plainly():
    assert "No design of the grid walks" in _section_text(None)


def test_the_study_figure_is_written(small_study, tmp_path):
    _, table = small_study
    assert save(walking_study_figure(table), tmp_path / "walking.png").stat().st_size > 20_000


def test_the_study_columns_turn_off(small_study):
    spec, _ = small_study
    table = sweep_in_process(StudySpec(spec.l1_ratios[:1], spec.l3_ratios[:1], gait=False))
    assert not [c for c in table.columns if c.startswith("gait_")]
    assert StudySpec((0.1,), (0.3,)).fingerprint()["gait"] is True


def test_the_animation_comes_after_every_object_it_colours(hexapod_model):
    from meshcat.servers.tree import walk

    from hexaleg.output.viewer.gait import ANIMATION_PATH, build_gait_scene
    from hexaleg.output.viewer.server import LoopbackServer, client

    walked = analyze_gait(hexapod_model.design, Gait(samples=12), model=hexapod_model,
                          limits=False)  # fmt: skip
    with LoopbackServer() as server:
        viewer = client(server)
        build_gait_scene(viewer, hexapod_model, walked)
        html = viewer.static_html()
        viewer.window.zmq_socket.close(linger=0)
        tree = server._bridge.tree
        nodes = list(walk(tree))
    animated = [k for k, node in enumerate(nodes) if node.animation is not None]
    drawn = [k for k, node in enumerate(nodes) if node.object is not None]
    assert len(animated) == 1 and animated[0] > max(drawn)
    assert nodes[animated[0]] is tree[ANIMATION_PATH.strip("/")]
    assert "MeshCat" in html and len(html) > 100_000


def test_study_columns_match_on_a_free_flyer_built_from_the_urdf():
    design = HexapodDesign.from_ratios(0.1, 0.5)
    row = design_walking_row(design, HexapodModel(design))
    assert row.columns["gait_feasible"]
    assert not math.isnan(row.metrics.value(METRICS.mechanical_cost_of_transport))


def test_the_animation_s_legend_says_what_a_gait_s_colours_mean(hexapod_model):
    """No link is red in a gait: its legend says what the colours mean there, nothing else."""
    from hexaleg.output.viewer.gait import gait_html
    from hexaleg.output.viewer.legend import GAIT_LEGEND, STATICS_LEGEND, torque_legend_html

    walked = analyze_gait(hexapod_model.design, Gait(samples=12), model=hexapod_model,
                          limits=False)  # fmt: skip
    page = gait_html(hexapod_model, walked)
    assert page.count("id='hexaleg-legend'") == 1
    assert torque_legend_html(GAIT_LEGEND) in page
    legend = torque_legend_html(GAIT_LEGEND)
    assert "gait period" in legend and "rated torque" in legend
    assert "red" not in legend and "extreme" not in legend and "swatch" not in legend
    assert "stops an extreme" in torque_legend_html(STATICS_LEGEND)
