"""The recommendation: scores compare across coxa ratios, the coxa can be fixed, peaks refined."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.study.recommendation import BAND, METRICS, combined_score, recommend

R1 = np.array([0.05, 0.10, 0.15, 0.20])
R3 = np.linspace(0.2, 0.6, 9)


def _maps(peak: float = 0.43) -> dict[str, np.ndarray]:
    """Smooth metrics peaking at l3 = peak, all falling as the coxa grows."""
    shape = 1 - (R3[None, :] - peak) ** 2
    fall = 1 - R1[:, None]
    return {name: (k + 1) * shape * fall for k, name in enumerate(METRICS)}


def test_scores_compare_across_coxa_ratios():
    rec = recommend(R1, R3, _maps())
    best = rec.peaks["combined_best_score"].to_numpy()
    np.testing.assert_allclose(best, (1 - R1) / (1 - R1[0]) * best[0], rtol=1e-12)
    assert best[0] == pytest.approx(1.0) and best[-1] < 0.9  # discriminates


def test_default_recommends_at_the_practical_coxa_ratio_and_the_user_can_fix_it():
    assert recommend(R1, R3, _maps()).l1_ratio == pytest.approx(0.10)
    assert recommend(R1, R3, _maps(), candidates=[0.15]).l1_ratio == pytest.approx(0.15)
    assert recommend(R1, R3, _maps(), candidates=[0.05, 0.2]).l1_ratio == pytest.approx(0.05)


def test_refinement_finds_the_peak_between_grid_points():
    peak = 0.4321

    def exact(l1_ratio: float, l3_ratio: float) -> dict[str, float]:
        value = (1 - (l3_ratio - peak) ** 2) * (1 - l1_ratio)
        return {name: (k + 1) * value for k, name in enumerate(METRICS)}

    maps = _maps(peak)
    coarse = recommend(R1, R3, maps)
    refined = recommend(R1, R3, maps, evaluate=exact)
    assert coarse.l3_ratio == pytest.approx(0.45)  # the nearest grid point
    assert refined.l3_ratio == pytest.approx(peak, abs=1e-4)
    assert refined.score >= coarse.score
    assert refined.score == pytest.approx(combined_score(exact(0.1, peak), refined.maxima))
    lo, hi = refined.l3_band
    assert lo <= refined.l3_ratio <= hi
    inside = [
        r for r in R3 if combined_score(exact(0.1, r), refined.maxima) >= BAND * refined.score
    ]
    assert (lo, hi) == (min(inside), max(inside))


def test_candidate_mask_allows_the_practical_or_the_given_coxa_ratios():
    from hexaleg.study.recommendation import candidate_mask

    assert candidate_mask(R1, None).tolist() == [False, True, True, True]  # ≥ 0.10
    assert candidate_mask(R1, [0.15]).tolist() == [False, False, True, False]
    assert candidate_mask([0.05, 0.05, 0.15], [0.05]).tolist() == [True, True, False]
    assert candidate_mask([0.02, 0.05], None).tolist() == [True, True]  # none practical: all


def test_decision_options_say_which_coxa_ratios_compete():
    from hexaleg.study.decision import DecisionOptions

    assert "≥ 0.10" in DecisionOptions().describe_candidates()
    assert "(0.125)" in DecisionOptions(l1_ratios=(0.125,)).describe_candidates()
