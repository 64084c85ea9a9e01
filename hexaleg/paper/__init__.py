"""Numbers and claims printed in the paper, kept verbatim in the paper's units.

Liu, Yang, Wang, Feng, "Design and Dimensional Optimization of Legged
Structures for Construction Robots". The tables are in millimetres and
degrees as printed; hexaleg computes in metres and radians and converts only
to compare.
"""

from __future__ import annotations

from typing import NamedTuple

from hexaleg.design import L3_RATIO_POINTS as L3_RATIO_POINTS  # the study's count, kept there

L1_RATIOS: tuple[float, ...] = (0.05, 0.10, 0.15, 0.20)
"""Coxa ratios l1 / l of Table 5 and Fig 8, 10, 11, 15 [-]."""

CLAIMED_L3_RATIO_PEAK: tuple[float, float] = (0.40, 0.45)
"""The paper's best tibia ratios for the workspace (§4.3, coxa ratio 0.1–0.2) and where FB
peaks (§6.3: "approximately between 0.4 and 0.45") [-]."""

CLAIMED_W_A_PEAK = 0.45
"""Where the paper says w_A peaks (§5.4: "when the ratio of the tibia length l3 is
approximately 0.45") [-]: one value, not the 0.40–0.45 band of §4.3 and §6.3."""


class Table5Row(NamedTuple):
    """One row of Table 5 (segment lengths [mm])."""

    l1_ratio: float
    l1_mm: float
    l2_mm: float
    l3_mm: float


TABLE5: tuple[Table5Row, ...] = (
    Table5Row(0.05, 50, 475, 475),
    Table5Row(0.10, 100, 450, 450),
    Table5Row(0.15, 150, 425, 425),
    Table5Row(0.20, 200, 400, 400),
)


class Table6Row(NamedTuple):
    """One row of Table 6: optimum pose of eq 25–26 (lengths [mm], angles [°], w [mm³])."""

    l1_mm: float
    l2_mm: float
    l3_mm: float
    theta2_deg: float
    theta3_deg: float
    w_mm3: float


TABLE6: tuple[Table6Row, ...] = (
    Table6Row(50, 475, 475, 35.6827, -71.3655, 1.7576e08),
    Table6Row(100, 450, 450, 36.1108, -72.2215, 1.5949e08),
    Table6Row(150, 425, 425, 36.5485, -73.0969, 1.4393e08),
    Table6Row(200, 400, 400, 36.9956, -73.9913, 1.2903e08),
)

TABLE6_PRINTED_DIGITS = 5
"""Table 6 prints w with five significant digits."""
