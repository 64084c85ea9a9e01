"""The three metrics the recommendation combines, for any one design.

Improved workspace area (eq 16) [m²], average manipulability on the improved
domain (eq 27) [m³], and axis-locked body flexibility FB (eq 29) [-]: the same
kernels as the grid sweeps, so a single design scores on the grid's scale.
"""

from __future__ import annotations

from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.stance.axis_locked import axis_locked_flexibility
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.study.recommendation import METRICS, Metrics
from hexaleg.swing.manipulability import average_manipulability, rectangular_and_improved
from hexaleg.swing.workspace import improved_area_closed_form


def design_metrics(
    design: HexapodDesign, template: StanceGeometry | None = None, collisions: bool = False
) -> Metrics:
    """Improved area [m²], w_A on the improved domain [m³] and axis-locked FB [-] of ``design``.

    Args:
        design: The design.
        template: A stance geometry of the same body and mounts (the fast path of sweeps);
            read from the design's own model if omitted.
        collisions: The robot's own parts touching also stop the body (FB).

    """
    _, improved = rectangular_and_improved(design.manipulability_limits)
    return {
        "improved_area": improved_area_closed_form(design.l2, design.l3),
        "average_manipulability": float(average_manipulability(design.lengths, improved)),
        "flexibility": axis_locked_flexibility(
            design, "all", geometry=template, collisions=collisions
        ).fb,
    }


def ratio_metrics(
    base: HexapodDesign,
    l1_ratio: float,
    l3_ratio: float,
    template: StanceGeometry,
    collisions: bool = False,
) -> Metrics:
    """:func:`design_metrics` of ``base`` with segments at these ratios of its leg length.

    A design that cannot exist or stand scores NaN in every metric.
    """
    try:
        design = base.with_ratios(l1_ratio, l3_ratio)
    except HexalegError:
        return dict.fromkeys(METRICS, float("nan"))
    return design_metrics(design, template, collisions)
