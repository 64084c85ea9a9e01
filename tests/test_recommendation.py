"""The recommendation: one rule, scores that stay put, the coxa can be fixed, peaks refined."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.evaluation.metrics import METRICS, Metrics
from hexaleg.study.ranking import RANKED_METRICS
from hexaleg.study.recommendation import BAND, recommend

R1 = np.array([0.05, 0.10, 0.15, 0.20])
R3 = np.linspace(0.2, 0.6, 9)
YOURS = Metrics(
    improved_area=0.3, average_manipulability=0.08, fb=0.2, walking_payload_capacity=150.0
)


def _ranked(values) -> Metrics:
    return Metrics(**{spec.name: float(v) for spec, v in zip(RANKED_METRICS, values, strict=True)})


def _metric(k: int, l1_ratio, l3_ratio, peak: float):
    """Smooth metrics peaking at l3 = peak; the kinematic ones fall as the coxa grows,
    the payload rises with it."""
    shape = 1 - (l3_ratio - peak) ** 2
    if RANKED_METRICS[k] is METRICS.walking_payload_capacity:
        return 100.0 * shape * (1 + l1_ratio)
    return (k + 1) * shape * (1 - l1_ratio)


def _maps(peak: float = 0.43, r1=R1) -> dict:
    return {
        spec: _metric(k, r1[:, None], R3[None, :], peak) for k, spec in enumerate(RANKED_METRICS)
    }


def _by_hand(l1_ratio, l3_ratio, peak=0.43):
    """The rule, written out: the fourth root of the product of the ratios to yours."""
    product = 1.0
    for k, spec in enumerate(RANKED_METRICS):
        product *= _metric(k, l1_ratio, l3_ratio, peak) / YOURS.value(spec)
    return product**0.25


def test_the_score_is_the_rule_and_compares_across_coxa_ratios():
    rec = recommend(R1, R3, _maps(), YOURS)
    table = rec.scores
    expected = [_by_hand(a, b) for a, b in zip(table["l1_ratio"], table["l3_ratio"], strict=True)]
    np.testing.assert_allclose(table["score"], expected, rtol=1e-12)
    best = rec.peaks["best_score"].to_numpy()
    np.testing.assert_allclose(best, [_by_hand(a, 0.45) for a in R1], rtol=1e-12)


def test_adding_unrelated_grid_rows_changes_no_score():
    """The old rule divided by the grid's best: one more coxa ratio changed every score."""
    narrow = recommend(R1[1:], R3, _maps(r1=R1[1:]), YOURS)
    wide = recommend(R1, R3, _maps(), YOURS)
    np.testing.assert_array_equal(
        wide.scores["score"].to_numpy()[len(R3) :], narrow.scores["score"].to_numpy()
    )
    np.testing.assert_array_equal(
        wide.peaks["best_score"].to_numpy()[1:], narrow.peaks["best_score"].to_numpy()
    )
    assert (wide.l1_ratio, wide.l3_ratio, wide.score) == (narrow.l1_ratio, narrow.l3_ratio,
                                                          narrow.score)  # fmt: skip


def test_default_recommends_at_the_practical_coxa_ratio_and_the_user_can_fix_it():
    assert recommend(R1, R3, _maps(), YOURS).l1_ratio == pytest.approx(0.10)
    assert recommend(R1, R3, _maps(), YOURS, candidates=[0.15]).l1_ratio == pytest.approx(0.15)
    both = recommend(R1, R3, _maps(), YOURS, candidates=[0.05, 0.2])
    assert both.l1_ratio == pytest.approx(0.05)


def test_refinement_finds_the_peak_between_grid_points():
    peak = 0.4321

    def exact(l1_ratio: float, l3_ratio: float) -> Metrics:
        return _ranked(_metric(k, l1_ratio, l3_ratio, peak) for k in range(len(RANKED_METRICS)))

    maps = _maps(peak)
    coarse = recommend(R1, R3, maps, YOURS)
    refined = recommend(R1, R3, maps, YOURS, evaluate=exact)
    assert coarse.l3_ratio == pytest.approx(0.45)  # the nearest grid point
    assert refined.l3_ratio == pytest.approx(peak, abs=1e-4)
    assert refined.score >= coarse.score
    assert refined.score == pytest.approx(_by_hand(0.1, refined.l3_ratio, peak), rel=1e-12)
    found, expected = refined.metrics.to_dict(), exact(0.1, refined.l3_ratio).to_dict()
    assert found == pytest.approx(expected, rel=1e-12)
    lo, hi = refined.l3_band
    assert lo <= refined.l3_ratio <= hi
    inside = [r for r in R3 if _by_hand(0.1, r, peak) >= BAND * refined.score]
    assert (lo, hi) == (min(inside), max(inside))


def test_the_band_holds_the_refined_peak_beside_its_grid_point():
    """Peak 0.4321 between grid points 0.40 and 0.45: only 0.45 keeps 97 % of the refined score,
    so the band is the refined ratio up to 0.45, not 0.45 alone."""
    peak = 0.4321

    def gaussian(l1_ratio, l3_ratio):
        shape = np.exp(-(((l3_ratio - peak) / 0.12) ** 2))
        return [(k + 1) * shape * (1 - l1_ratio) for k in range(len(RANKED_METRICS))]

    maps = dict(zip(RANKED_METRICS, gaussian(R1[:, None], R3[None, :]), strict=True))
    refined = recommend(R1, R3, maps, YOURS, evaluate=lambda a, b: _ranked(gaussian(a, b)))
    assert refined.l3_ratio == pytest.approx(peak, abs=1e-4)
    grid = refined.scores[np.isclose(refined.scores["l1_ratio"], refined.l1_ratio)]
    kept = grid.loc[grid["score"] >= BAND * refined.score, "l3_ratio"].tolist()
    assert kept == pytest.approx([0.45])  # the grid alone would leave the recommendation out
    assert refined.l3_band == pytest.approx((refined.l3_ratio, 0.45))


def test_nothing_to_recommend_when_no_allowed_design_stands():
    from hexaleg.exceptions import HexalegError

    maps = _maps()
    maps[METRICS.fb] = np.full_like(maps[METRICS.fb], np.nan)
    with pytest.raises(HexalegError, match="nothing to recommend"):
        recommend(R1, R3, maps, YOURS)


def test_candidate_mask_allows_the_practical_or_the_given_coxa_ratios():
    from hexaleg.study.recommendation import candidate_mask

    assert candidate_mask(R1, None).tolist() == [False, True, True, True]  # ≥ 0.10
    assert candidate_mask(R1, [0.15]).tolist() == [False, False, True, False]
    assert candidate_mask([0.05, 0.05, 0.15], [0.05]).tolist() == [True, True, False]
    assert candidate_mask([0.02, 0.05], None).tolist() == [True, True]  # none practical: all


def test_decision_options_say_which_coxa_ratios_compete():
    from hexaleg.study.recommendation import DecisionOptions

    assert "≥ 0.10" in DecisionOptions().describe_candidates()
    assert "(0.125)" in DecisionOptions(l1_ratios=(0.125,)).describe_candidates()


def test_the_report_table_gives_a_reason_where_a_coxa_ratio_has_no_leg_that_walks():
    """A coxa ratio whose legs all fail to walk has no peaks: the table says so, not nan."""
    from hexaleg import HexapodDesign
    from hexaleg.output.report.options import ReportOptions
    from hexaleg.output.report.part import ReportData
    from hexaleg.output.report.recommendation import NO_WALKER, RecommendationRecord, section
    from hexaleg.study.rows import StudyRow

    maps = _maps()
    for values in maps.values():
        values[0, :] = np.nan  # coxa ratio 0.05: no leg walks (the ranking's NaN)
    rec = recommend(R1, R3, maps, YOURS)
    record = RecommendationRecord(rec, 1.0, StudyRow(rec.l1_ratio, rec.l3_ratio))
    data = ReportData(HexapodDesign(), ReportOptions(), None, {RecommendationRecord: record})  # type: ignore[arg-type]
    (peaks,) = [block for block in section(data).blocks if "| l1 ratio |" in block]
    rows = [line.split(" | ") for line in peaks.splitlines()[2:]]
    assert len(rows) == len(R1)
    assert "nan" not in peaks.lower() and "inf" not in peaks.lower()
    assert rows[0][0] == "| 0.05" and rows[0][1] == NO_WALKER
    for row, l1_ratio in zip(rows[1:], R1[1:], strict=True):  # the others as the rule has them
        assert row[-1].rstrip(" |") == f"{_by_hand(l1_ratio, 0.45):.4f}"
