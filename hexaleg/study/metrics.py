"""The four metrics the ranking rule combines, for any one design.

Improved workspace area (eq 16) [m²], average manipulability on the improved
domain (eq 27) [m³], axis-locked body flexibility FB (eq 29) [-] and the payload
capacity at the nominal stance [kg] (:func:`~hexaleg.statics.capacity.payload_capacity`,
the payload at the centre of the body's top face): the same kernels as the grid sweeps,
so a single design is measured as the grid's designs are.
"""

from __future__ import annotations

from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.axis_locked import axis_locked_flexibility
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.statics.capacity import payload_capacity
from hexaleg.statics.forces import Statics
from hexaleg.study.ranking import RANKED_METRICS, Metrics
from hexaleg.swing.manipulability import average_manipulability, rectangular_and_improved
from hexaleg.swing.workspace import improved_area_closed_form


def design_metrics(
    design: HexapodDesign,
    model: HexapodModel,
    template: StanceGeometry | None = None,
    collisions: bool = False,
) -> Metrics:
    """Improved area [m²], w_A [m³], axis-locked FB [-] and payload capacity [kg] of ``design``.

    Args:
        design: The design.
        model: Its Pinocchio model (one derived from a model of the same body is exact).
        template: A stance geometry of the same body and mounts (the fast path of sweeps);
            read from the model if omitted.
        collisions: The robot's own parts touching also stop the body (FB).

    """
    _, improved = rectangular_and_improved(design.manipulability_limits)
    locked = axis_locked_flexibility(design, "all", model, geometry=template, collisions=collisions)
    statics = Statics(model, locked.legs)
    return {
        "improved_area": improved_area_closed_form(design.l2, design.l3),
        "average_manipulability": float(average_manipulability(design.lengths, improved)),
        "flexibility": locked.fb,
        "payload_capacity": payload_capacity(statics, model.nominal_configuration()).mass,
    }


def ratio_metrics(
    base: HexapodDesign,
    l1_ratio: float,
    l3_ratio: float,
    model: HexapodModel,
    template: StanceGeometry,
    collisions: bool = False,
) -> Metrics:
    """:func:`design_metrics` of ``base`` with segments at these ratios of its leg length.

    ``model`` is ``base``'s (the design's is derived from it). A design that cannot exist
    or stand scores NaN in every metric.
    """
    try:
        design = base.with_ratios(l1_ratio, l3_ratio)
        return design_metrics(design, model.with_design(design), template, collisions)
    except HexalegError:
        return dict.fromkeys(RANKED_METRICS, float("nan"))
