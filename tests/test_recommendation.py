"""The recommendation: one rule on the grid, the cliff kept at a distance, the band beside it."""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from hexaleg.evaluation.metrics import METRICS, Metrics
from hexaleg.study.ranking import RANKED_METRICS, WalkingConstraint
from hexaleg.study.recommendation import (
    BAND,
    CLIFF_MARGIN,
    PROFILE_STEP,
    band_and_cliffs,
    band_of,
    candidate_mask,
    grid_ranking,
    settled,
)
from hexaleg.swing.workspace import improved_area_closed_form

R1 = np.array([0.05, 0.10, 0.15, 0.20])
R3 = np.linspace(0.2, 0.6, 9)
YOURS = Metrics(improved_area=0.3, average_manipulability=0.08, fb=0.2)
WALKING = METRICS.walking_payload_capacity.name


def _w_a(l1_ratio, l3_ratio):
    return 0.1 * (1 - (l3_ratio - 0.43) ** 2) * (1 - l1_ratio)


def _fb(l1_ratio, l3_ratio):
    return 0.3 * (1 - (l3_ratio - 0.5) ** 2) * (1 - l1_ratio)


def _capacity(l1_ratio, l3_ratio):
    return 100.0 * (1 - l3_ratio)  # a longer tibia carries less


def _study() -> pd.DataFrame:
    rows = [
        {"l1_ratio": a, "l3_ratio": b, "fb": _fb(a, b), WALKING: _capacity(a, b), "walks": True}
        for a in R1
        for b in R3
    ]
    return pd.DataFrame(rows)


def _by_hand(l1_ratio, l3_ratio, total=1.0):
    """The rule, written out: the cube root of the product of the ratios to yours."""
    area = 2 * math.pi * (1 - l1_ratio - l3_ratio) * l3_ratio * total**2 / 3  # eq 16
    return (area / 0.3 * _w_a(l1_ratio, l3_ratio) / 0.08 * _fb(l1_ratio, l3_ratio) / 0.2) ** (1 / 3)


def test_the_grid_is_scored_by_the_rule_among_the_legs_that_meet_the_constraint():
    average_map = SimpleNamespace(l1_ratios=R1, l3_ratios=R3, improved=_w_a(R1[:, None], R3[None]))
    assert improved_area_closed_form(0.5, 0.4) == pytest.approx(2 * math.pi * 0.2 / 3)
    peaks, table = grid_ranking(average_map, _study(), YOURS, WalkingConstraint(55.0), 1.0)
    meets = 100.0 * (1 - table["l3_ratio"]) >= 55.0  # the tibia ratio ≤ 0.45 carries 55 kg
    assert table["meets"].tolist() == meets.tolist()
    expected = [_by_hand(a, b) for a, b in zip(table["l1_ratio"], table["l3_ratio"], strict=True)]
    np.testing.assert_allclose(table.loc[meets, "score"], np.array(expected)[meets], rtol=1e-12)
    assert table.loc[~meets, "score"].isna().all()  # missing the constraint: no score
    for row in peaks.to_dict(orient="records"):  # brute force over the legs that meet it
        candidates = [(b, _by_hand(row["l1_ratio"], b)) for b in R3 if 100 * (1 - b) >= 55]
        best = max(candidates, key=lambda pair: pair[1])
        assert row["score_peak_l3_ratio"] == pytest.approx(best[0])
        assert row["best_score"] == pytest.approx(best[1], rel=1e-12)


# -- the cliff: a synthetic profile ---------------------------------------------------------

CLIFF = 0.725
"""The synthetic legs carry 72.7 kg up to tibia ratio 0.725 and nothing beyond (the review's
coxa 0.1: 72.7 kg at tibia 0.717, 0 kg at 0.725)."""


def _synthetic_score(l3_ratio: float) -> float:
    return 1.0 + l3_ratio  # rising toward the cliff: the best sits on its edge


@dataclass(frozen=True)
class _Design:
    l3_ratio: float
    nominal_angles: tuple[float, float, float] = (0.0, 0.1, -1.0)


@dataclass(frozen=True)
class _Leg:
    l3_ratio: float
    l1_ratio: float = 0.1

    @property
    def meets(self) -> bool:
        return self.l3_ratio < CLIFF

    @property
    def score(self) -> float:
        return _synthetic_score(self.l3_ratio) if self.meets else math.nan

    @property
    def ranked(self) -> bool:
        return self.meets

    @property
    def capacity(self) -> float:
        return 72.7 if self.meets else 0.0

    @property
    def limited_by(self) -> str:
        return "knee torque over its rating"

    @property
    def design(self) -> _Design:
        return _Design(round(self.l3_ratio, 12))


class _Legs:
    """Measures a synthetic leg at a tibia ratio, counting how many."""

    def __init__(self) -> None:
        self.measured = 0

    def at(self, l1_ratio, l3_ratio, angles):
        self.measured += 1
        return _Leg(l3_ratio, l1_ratio)


def test_a_leg_at_the_edge_of_a_cliff_is_not_recommended_and_the_band_keeps_away():
    legs = _Legs()
    edge = _Leg(0.717)  # the search's best: 0.8 % of the leg from the cliff
    chosen, profile = settled(legs, edge, (0.2, 0.8))  # type: ignore[arg-type]
    (cliff,) = profile.cliffs
    assert abs(cliff.l3_ratio - CLIFF) <= PROFILE_STEP / 2**6  # located by bisection
    assert cliff.held < CLIFF <= cliff.broken and cliff.capacity == 72.7
    assert "knee torque" in cliff.describe() and "0.725" in cliff.describe()
    # brute force: the profile's lattice from 0.717 in steps of 0.01, clear of the cliff
    lattice = [0.717 - k * PROFILE_STEP for k in range(60) if 0.717 - k * PROFILE_STEP >= 0.2]
    clear = [r for r in lattice if CLIFF - r >= CLIFF_MARGIN]
    best = max(clear, key=_synthetic_score)
    assert chosen.l3_ratio == pytest.approx(best) and best == pytest.approx(0.697)
    low, high = band_of(chosen, profile)  # type: ignore[arg-type]
    kept = [r for r in clear if _synthetic_score(r) >= BAND * _synthetic_score(best)]
    assert (low, high) == pytest.approx((min(kept), max(kept)))
    assert CLIFF - high >= CLIFF_MARGIN - 1e-12


def test_a_leg_clear_of_every_cliff_stays_and_its_band_stops_short_of_the_cliff():
    ratios = [0.60, 0.62, 0.64, 0.66, 0.68, 0.70, 0.72, 0.74]
    scores = [_synthetic_score(r) if r < CLIFF else math.nan for r in ratios]
    meets = [r < CLIFF for r in ratios]
    band = band_and_cliffs(ratios, scores, meets, chosen=2, cliffs=[CLIFF])
    # by hand: 0.72 meets the constraint but lies within 0.02 of the cliff at 0.725
    assert band == pytest.approx((0.60, 0.70))
    assert band_and_cliffs(ratios, scores, meets, chosen=6, cliffs=[CLIFF]) is None
    assert band_and_cliffs(ratios, scores, meets, chosen=2, cliffs=[]) == pytest.approx(
        (0.60, 0.72)
    )


def test_candidate_mask_allows_the_practical_or_the_given_coxa_ratios():
    assert candidate_mask(R1, None).tolist() == [False, True, True, True]  # ≥ 0.10
    assert candidate_mask(R1, [0.15]).tolist() == [False, False, True, False]
    assert candidate_mask([0.05, 0.05, 0.15], [0.05]).tolist() == [True, True, False]
    assert candidate_mask([0.02, 0.05], None).tolist() == [True, True]  # none practical: all


def test_decision_options_say_which_coxa_ratios_compete_and_what_every_leg_carries():
    from hexaleg.study.recommendation import DecisionOptions

    assert "≥ 0.10" in DecisionOptions().describe_candidates()
    assert "(0.125)" in DecisionOptions(l1_ratios=(0.125,)).describe_candidates()
    assert DecisionOptions(payload=30.0).constraint == WalkingConstraint(30.0)


def test_the_report_table_gives_a_reason_where_a_coxa_ratio_has_no_leg_that_walks():
    """A coxa ratio whose legs all miss the constraint has no peaks: the table says so."""
    from hexaleg.output.report.recommendation import NO_WALKER, _peak_row

    study = _study()
    study.loc[np.isclose(study["l1_ratio"], 0.05), "walks"] = False
    average_map = SimpleNamespace(l1_ratios=R1, l3_ratios=R3, improved=_w_a(R1[:, None], R3[None]))
    peaks, _ = grid_ranking(average_map, study, YOURS, WalkingConstraint(), 1.0)
    rows = [_peak_row(r) for r in peaks.to_dict(orient="records")]
    assert rows[0][:2] == ["0.05", NO_WALKER]
    text = " ".join(" ".join(row) for row in rows).lower()
    assert "nan" not in text and "inf" not in text
    for row, l1_ratio in zip(rows[1:], R1[1:], strict=True):  # the others as the rule has them
        assert row[-1] == f"{max(_by_hand(l1_ratio, b) for b in R3):.4f}"
    assert len(RANKED_METRICS) + 3 == len(rows[1])


def test_a_payload_no_leg_walks_with_ranks_the_legs_walking_unloaded_and_says_so(monkeypatch):
    from hexaleg.evaluation.requirements import Requirements
    from hexaleg.output.report import recommendation as part
    from hexaleg.output.report.options import ReportOptions
    from hexaleg.study.recommendation import NothingToRecommend, Recommendation

    asked: list[WalkingConstraint] = []
    leg = SimpleNamespace(
        l1_ratio=0.1,
        l3_ratio=0.45,
        design=SimpleNamespace(lengths=(0.1, 0.45, 0.45)),
        evaluation=SimpleNamespace(metrics=YOURS),
    )

    def searched(data, constraint):
        asked.append(constraint)
        if constraint.payload > 0:
            raise NothingToRecommend("no allowed leg walks the gait carrying 500 kg")
        return Recommendation(leg, leg, leg, (0.45, 0.45), (), (), constraint,  # type: ignore[arg-type]
                              pd.DataFrame(), pd.DataFrame(), 0)  # fmt: skip

    monkeypatch.setattr(part, "_recommended", searched)
    options = ReportOptions(requirements=Requirements(payload=500.0))
    data = SimpleNamespace(options=options, design=SimpleNamespace(leg_length=1.0))
    rec = part.compute(data).recommendation  # type: ignore[arg-type]
    assert asked == [WalkingConstraint(500.0), WalkingConstraint()]
    assert rec.relaxed == WalkingConstraint(500.0) and rec.constraint == WalkingConstraint()
    said = part.relaxed_text(rec)
    assert "carrying 500 kg" in said and "unloaded" in said
    asked.clear()
    unloaded = SimpleNamespace(options=ReportOptions(), design=data.design)
    monkeypatch.setattr(part, "_recommended", lambda d, c: (_ for _ in ()).throw(
        NothingToRecommend("none")))  # fmt: skip
    with pytest.raises(NothingToRecommend):  # nothing to relax: the report says why it stops
        part.compute(unloaded)  # type: ignore[arg-type]


def test_a_required_walking_slope_is_what_every_leg_of_the_report_walks_and_ranks_by():
    """The report's one set of conditions: its study, your design and every searched leg."""
    from hexaleg import HexapodDesign, HexapodModel
    from hexaleg.evaluation.requirements import Requirements
    from hexaleg.evaluation.walks import walking_grounds
    from hexaleg.exceptions import HexalegError
    from hexaleg.output.report.options import ReportOptions
    from hexaleg.output.report.part import ReportData
    from hexaleg.output.report.yours import report_study, standing_text
    from hexaleg.study.sweep import StudySpec

    slope = math.radians(10)
    required = Requirements(payload=20.0, walking_slope=slope, motor_safety_factor=1.5)
    options = ReportOptions(l3_points=10, requirements=required)
    design = HexapodDesign()
    spec = report_study(ReportData(design, options, HexapodModel(design)))
    conditions = spec.conditions
    assert conditions.grounds == walking_grounds(slope, options.gait)  # up, down, across
    assert len(conditions.grounds) == 3 and conditions.safety_factor == 1.5
    assert conditions.payload.mass == 0.0  # the payload is the constraint, not a condition
    constraint = options.decision.constraint
    assert constraint == WalkingConstraint(20.0, slope)
    assert "carrying 20 kg up, down and across a 10° slope" in constraint.describe()
    assert "10° slope" in standing_text(spec)
    plain = report_study(ReportData(design, ReportOptions(l3_points=10), HexapodModel(design)))
    assert len(plain.conditions.grounds) == 1 and plain.fingerprint().keys() == (
        StudySpec(plain.l1_ratios, plain.l3_ratios).fingerprint().keys()
    )  # a level study's journal reads as before
    with pytest.raises(HexalegError, match="walking_slope"):
        StudySpec((0.1,), (0.4,), walking_slope=-0.1)
