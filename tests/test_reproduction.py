"""The paper's Tables 5 and 6 recomputed: eq 16 holds, row 1 of Table 6 is flagged."""

from __future__ import annotations

import pytest

from hexaleg import IMPROVED_LIMITS, MANIPULABILITY_LIMITS, WORKSPACE_LIMITS
from hexaleg.paper import TABLE5, TABLE6
from hexaleg.paper.reproduction import (
    digits_transposed,
    table5_reproduction,
    table6_reproduction,
)


def test_table5_improved_areas_equal_eq16():
    rows = table5_reproduction(1.0, IMPROVED_LIMITS, WORKSPACE_LIMITS)
    assert [r["l1_ratio"] for r in rows] == [r.l1_ratio for r in TABLE5]
    for row in rows:
        assert abs(row["relative_difference"]) < 1e-10
        assert row["rectangular_area_m2"] > 0
    areas = [r["improved_area_m2"] for r in rows]
    assert areas == sorted(areas, reverse=True)  # shrinks as the coxa grows


def test_table6_flags_exactly_the_misprinted_row():
    rows = table6_reproduction(MANIPULABILITY_LIMITS)
    assert [r["paper_w_matches_eq25"] for r in rows] == [False, True, True, True]
    for row, printed in zip(rows, TABLE6, strict=True):
        assert row["hexaleg_theta2_deg"] == pytest.approx(printed.theta2_deg, abs=1e-3)
        assert row["hexaleg_theta3_deg"] == pytest.approx(printed.theta3_deg, abs=1e-3)
    first = rows[0]
    assert digits_transposed(first["paper_w_mm3"], first["eq25_at_paper_angles_mm3"])


@pytest.mark.parametrize(
    ("printed", "computed", "expected"),
    [(1.7576e8, 1.7567e8, True), (1.7576e8, 1.7576e8, False), (1.5949e8, 1.2903e8, False)],
)
def test_digits_transposed(printed, computed, expected):
    assert digits_transposed(printed, computed) is expected
