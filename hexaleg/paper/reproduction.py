"""The paper's tables recomputed by hexaleg, beside the values as printed.

Table 5 (improved workspace area of four coxa ratios, eq 16) and Table 6
(optimum-manipulability pose, eq 25–26). Each row keeps the paper's units
(mm, °, mm³) where it shows a printed value, and SI units otherwise; column
names say which.
"""

from __future__ import annotations

import math
from typing import Any

from hexaleg.kinematics import manipulability
from hexaleg.limits import JointLimits
from hexaleg.paper import TABLE5, TABLE6, TABLE6_PRINTED_DIGITS, Table6Row
from hexaleg.swing.manipulability import optimum_pose
from hexaleg.swing.workspace import improved_area_closed_form, planar_workspace

PAPER_LEG_MM = 1000.0
"""Total leg length of the paper's Table 5 designs [mm]."""


def table5_reproduction(
    leg_length: float, improved_limits: JointLimits, workspace_limits: JointLimits
) -> list[dict[str, Any]]:
    """Table 5's designs scaled to ``leg_length`` [m]: numerical and eq 16 improved areas [m²].

    Args:
        leg_length: Total leg length to scale the 1000 mm designs to [m].
        improved_limits: The improved (Table 4) joint domain.
        workspace_limits: The rectangular (Table 3) joint domain.

    """
    scale = leg_length / PAPER_LEG_MM
    rows = []
    for row in TABLE5:
        lengths = (row.l1_mm * scale, row.l2_mm * scale, row.l3_mm * scale)
        improved = planar_workspace(lengths, improved_limits).area
        closed = improved_area_closed_form(lengths[1], lengths[2])
        rows.append(
            {
                "l1_ratio": row.l1_ratio,
                "l1_mm": row.l1_mm,
                "l2_mm": row.l2_mm,
                "l3_mm": row.l3_mm,
                "improved_area_m2": improved,
                "eq16_area_m2": closed,
                "relative_difference": improved / closed - 1,
                "rectangular_area_m2": planar_workspace(lengths, workspace_limits).area,
            }
        )
    return rows


def table6_reproduction(limits: JointLimits) -> list[dict[str, Any]]:
    """Table 6: hexaleg's optimum pose beside the printed one, and eq 25 at the printed angles.

    ``paper_w_matches_eq25`` is false where the printed w is not what eq 25 gives at the
    paper's own angles, to the printed precision.
    """
    rows = []
    for row in TABLE6:
        lengths = (row.l1_mm / 1000, row.l2_mm / 1000, row.l3_mm / 1000)
        pose = optimum_pose(lengths, limits)
        w_at_paper = 1e9 * float(
            manipulability(lengths, math.radians(row.theta2_deg), math.radians(row.theta3_deg))
        )
        rows.append(
            {
                "l1_mm": row.l1_mm,
                "l2_mm": row.l2_mm,
                "l3_mm": row.l3_mm,
                "paper_theta2_deg": row.theta2_deg,
                "hexaleg_theta2_deg": math.degrees(pose.theta2),
                "paper_theta3_deg": row.theta3_deg,
                "hexaleg_theta3_deg": math.degrees(pose.theta3),
                "paper_w_mm3": row.w_mm3,
                "eq25_at_paper_angles_mm3": w_at_paper,
                "hexaleg_w_mm3": pose.w * 1e9,
                "paper_w_matches_eq25": _agrees_to_printed_digits(row, w_at_paper),
            }
        )
    return rows


def _agrees_to_printed_digits(row: Table6Row, w_mm3: float) -> bool:
    precision = 10 ** (math.floor(math.log10(row.w_mm3)) - TABLE6_PRINTED_DIGITS + 1)
    return abs(w_mm3 - row.w_mm3) <= precision / 2 + 1e-6 * row.w_mm3


def digits_transposed(printed: float, computed: float) -> bool:
    """Whether two values differ only by the order of their digits at Table 6's precision."""
    a = f"{printed:.{TABLE6_PRINTED_DIGITS - 1}e}"
    b = f"{computed:.{TABLE6_PRINTED_DIGITS - 1}e}"
    return a != b and sorted(a) == sorted(b)
