"""Grids of segment ratios, as the paper sweeps them: refused up front when they cannot be built.

A study sweeps coxa ratios l1/L and tibia ratios l3/L at a total leg length L. Every
design on the grid must have each segment within the design's plausible range
(:data:`~hexaleg.design.SEGMENT_RANGE`); a grid that leaves a segment outside it would
only compute a table of failed designs, so it is refused before anything runs, with
the ratio and the total that cause it named.
"""

from __future__ import annotations

from collections.abc import Sequence

from hexaleg._checks import require_distinct
from hexaleg.design import SEGMENT_RANGE
from hexaleg.exceptions import ParameterError

MAX_L1_RATIOS = 20
"""Most coxa ratios in one study's grid."""


def require_ratio_grid(
    l1_ratios: Sequence[float], l3_ratios: Sequence[float], total: float
) -> None:
    """Refuse a grid with a ratio given twice, or a segment outside its range.

    Each ratio must already lie in (0, 1) and ``total`` in its own range.

    Args:
        l1_ratios: Coxa ratios l1/L [-].
        l3_ratios: Tibia ratios l3/L [-].
        total: Total leg length L [m].

    """
    require_distinct("l1_ratios", l1_ratios)
    require_distinct("l3_ratios", l3_ratios)
    lower, upper = SEGMENT_RANGE
    within = f"at total {total:g} m every segment must lie in [{lower:g}, {upper:g}] [m]"
    for name, ratios, segment in (
        ("l1_ratios", l1_ratios, "coxa"),
        ("l3_ratios", l3_ratios, "tibia"),
    ):
        for ratio in (min(ratios), max(ratios)):
            if not lower <= ratio * total <= upper:
                length = ratio * total
                raise ParameterError(
                    name, ratio, f"the {segment} would be {length:.3g} m; {within}"
                )
    crowded = max(l1_ratios)
    femur = total * (1 - crowded - min(l3_ratios))
    if femur < lower:
        raise ParameterError(
            "l1_ratios",
            crowded,
            f"must leave room for femur and tibia: l1 ratio + smallest l3 ratio "
            f"({min(l3_ratios):.3g}) leaves a femur of {femur:.3g} m; {within}",
        )
    widest = total * (1 - min(l1_ratios) - min(l3_ratios))
    if widest > upper:
        raise ParameterError("total", total, f"the femur would be {widest:.3g} m; {within}")


def ratio_text(ratio: float) -> str:
    """A segment ratio as every table, sentence and figure of hexaleg prints it: ``0.666``."""
    return f"{ratio:.3f}"


def proportions_text(l1_ratio: float, l2_ratio: float, l3_ratio: float) -> str:
    """A leg's proportions as hexaleg prints them: ``l1 : l2 : l3 = 0.100 : 0.234 : 0.666``."""
    return "l1 : l2 : l3 = " + " : ".join(map(ratio_text, (l1_ratio, l2_ratio, l3_ratio)))
