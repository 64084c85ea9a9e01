"""The explorer's answer about one design: every number the page shows, JSON-ready.

One :func:`~hexaleg.evaluation.evaluate.evaluate` measures the metrics of
:data:`EXPLORED` under the query's conditions; the answer names them as the command
line's ``--json`` does (``fb``, ``payload_capacity``, ``peak_torque`` per joint type,
``max_speed`` ...) with what limits each, the nominal stance's points for the drawing,
and, when the design file has ``[requirements]``, each one checked under the
requirements' own conditions (the same evaluation when they are the sliders' too).
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from hexaleg.actuator_catalog import shipped_catalog
from hexaleg.actuators import Actuator
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.evaluate import Conditions, Evaluation, evaluate
from hexaleg.evaluation.goal import Goal
from hexaleg.evaluation.metrics import METRICS, MetricSpec
from hexaleg.evaluation.requirements import Requirements, limited_by_dict
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.model_cache import model_of
from hexaleg.stance.configurations import extreme_configurations
from hexaleg.statics.forces import Payload
from hexaleg.swing.workspace import standing_reach

__all__ = ["EXPLORED", "answer"]

SCALARS: tuple[MetricSpec, ...] = (
    METRICS.fb,
    METRICS.improved_area,
    METRICS.average_manipulability,
    METRICS.payload_capacity,
    METRICS.walking_payload_capacity,
    METRICS.max_speed,
    METRICS.mechanical_energy_per_km,
    METRICS.mechanical_cost_of_transport,
    *(spec for spec in METRICS if spec.analysis == "motors"),
    METRICS.ground_clearance,
    METRICS.robot_mass,
)
"""Metrics answered under their own names (those through the motors ``None`` without
``[actuators]``, with the reason in ``unmeasured``)."""

EXPLORED: tuple[MetricSpec, ...] = (
    *SCALARS,
    *(spec for spec in METRICS if spec.torque is not None),
)
"""Every metric the explorer measures for a design: those above, and each joint type's
peak and RMS torque over the gait period (answered as ``peak_torque`` and ``rms_torque``)."""


def answer(
    design: HexapodDesign,
    conditions: Conditions,
    requirements: Requirements,
    model: HexapodModel | None = None,
) -> dict[str, Any]:
    """The page's numbers for ``design`` under ``conditions``, checked against ``requirements``.

    Args:
        design: The design.
        conditions: What it is measured under (the sliders' payload and gait).
        requirements: The design file's requirements (none given: nothing checked).
        model: Its model (an imported robot's at these segments); derived from hexaleg's
            template (:func:`~hexaleg.robot.model_cache.model_of`) if omitted.

    """
    start = time.perf_counter()
    model = model_of(design) if model is None else model
    goal = Goal(requirements.resolved(design)) if requirements.given else None
    shared = goal is not None and _placed(goal.conditions, design) == _placed(conditions, design)
    metrics = {*EXPLORED, *(goal.metrics if shared and goal else ())}
    found = evaluate(design, metrics, replace(conditions, keep=True), model=model)
    out = _numbers(found) | {"stance": _stance(model, found), "extremes": _extremes(model, found)}
    if goal is not None:
        checked = found if shared else goal.evaluate(design, model=model)
        out["requirements"] = _checks(goal, checked)
    out["evaluate_ms"] = 1000 * (time.perf_counter() - start)
    return out


def _numbers(found: Evaluation) -> dict[str, Any]:
    """The metrics as the command line names them, with what limits each."""
    metrics = found.metrics
    out: dict[str, Any] = {"error": found.error}
    out |= {spec.name: _finite(metrics.value(spec)) for spec in SCALARS}
    for torque in ("peak", "rms"):
        joints = metrics.joint_torques(torque)
        out[f"{torque}_torque"] = {
            joint: _finite(math.nan if value is None else value) for joint, value in joints.items()
        }
    causes = found.causes.items()
    out["limited_by"] = {s.name: limited_by_dict(c) for s, c in causes if c is not None}
    out["unmeasured"] = {s.name: why for s, why in found.unmeasured.items() if why is not None}
    out["walks"] = found.walks
    out["units"] = {spec.name: spec.unit for spec in SCALARS} | {"torque": "N·m"}
    return out


def _stance(model: HexapodModel, found: Evaluation) -> dict[str, Any]:
    """The nominal stance's points, world frame [m], and each leg's use of its ratings.

    ``chains``: each leg's three joints and its foot; ``utilisation``: each leg's largest
    peak |τ| over a gait period against its joint's rating [-] (``None`` where the period
    breaks a constraint: a joint limit, a foot out of reach — it is not walked; and every
    leg's when the design gives no ratings, as ``rated_torques``).
    """
    design = model.design
    chains = model.leg_chains(model.nominal_configuration())
    utilisation: list[float | None] = [None] * len(model.leg_names)
    rated = design.rated_torques
    if found.gait is not None and found.gait.walkable and rated is not None:
        peaks = np.abs(found.gait.joint_torques).max(axis=0)  # (legs, joints) [N·m]
        used = dict(zip(found.gait.legs, peaks / np.asarray(rated), strict=True))
        utilisation = [  # None where the period has no torque (a foot out of reach: NaN)
            _finite(float(used[leg].max())) if leg in used else None for leg in model.leg_names
        ]
    return {
        "legs": list(model.leg_names),
        "chains": chains.round(6).tolist(),
        "utilisation": utilisation,
        "rated_torques": None if rated is None else dict(zip(LEG_JOINTS, rated, strict=True)),
    }


REACH_SAMPLES = 10_000
"""Joint-angle samples of each foot's reach (the gait figure's Monte Carlo cloud)."""
REACH_SLICE = 0.02
"""Half thickness of the ground's slice of the reach [m]."""
REACH_POINTS = 400
"""Most points of each leg's reach sent to the page."""


def feet_reach(design: HexapodDesign, model: HexapodModel | None = None) -> list[list[list[float]]]:
    """Each leg's foot reach on the ground (x, y), world frame [m], at the nominal body pose.

    Each leg's Monte Carlo cloud within the limits that hold it standing (as ``gait
    --plot`` draws it, :func:`~hexaleg.swing.workspace.standing_reach`), placed at each
    leg's root, kept within :data:`REACH_SLICE` of that leg's nominal foot height, thinned
    to at most :data:`REACH_POINTS` points. Asked for apart from :func:`answer` (the page
    shows it on demand): a slider's redraw does not pay it.
    """
    model = model_of(design) if model is None else model
    ground = model.leg_chains(model.nominal_configuration())[:, -1, 2]
    base = model.nominal_base_pose()
    roots = model.root_placements()
    clouds = standing_reach(model, REACH_SAMPLES)
    out = []
    for leg, height in zip(model.leg_names, ground, strict=True):
        cloud = clouds[leg]
        placed = base * roots[leg]
        world = cloud.points @ placed.rotation.T + placed.translation
        near = world[np.abs(world[:, 2] - height) < REACH_SLICE]
        step = max(1, math.ceil(len(near) / REACH_POINTS))
        out.append(near[::step, :2].round(4).tolist())
    return out


def _extremes(model: HexapodModel, found: Evaluation) -> list[dict[str, Any]]:
    """FB's 12 extremes: direction, value [m or rad], what stops the body there.

    ``chains``: the robot's points there, as the stance's (world frame [m]).
    """
    if found.flexibility is None:
        return []
    extremes = found.flexibility.extremes
    posed = extreme_configurations(model, extremes)
    return [
        {
            "name": x.name,
            "value": x.value,
            "limited_by": x.description,
            "chains": model.leg_chains(q).round(6).tolist(),
        }
        for x, q in zip(extremes, posed, strict=True)
    ]


def _checks(goal: Goal, found: Evaluation) -> list[dict[str, Any]]:
    """Each requirement checked: required, value, margin, met, what limits it, in words."""
    if found.error:
        return [
            {
                "name": name,
                "met": False,
                "text": goal.requirements.describe(name),
                "error": found.error,
            }
            for name in goal.requirements.given
        ]
    checks = []
    for check in goal.checks(found):
        out = check.to_dict(binding=False) | {"name": check.name}
        out |= {key: _finite(out[key]) for key in ("required", "value", "margin")}
        checks.append(out | {"text": goal.requirements.describe(check.name)})
    return checks


def _placed(conditions: Conditions, design: HexapodDesign) -> Conditions:
    """The conditions with the payload's position spelled out (its default made explicit)."""
    payload = conditions.payload
    x, y, z = payload.position_on(design)
    return replace(conditions, payload=Payload(payload.mass, (x, y, z)))


def _finite(value: float) -> float | None:
    """A metric's value for JSON: ``None`` where it is not a finite number."""
    return value if math.isfinite(value) else None


def loaded_values(design: HexapodDesign, conditions: Conditions) -> Mapping[str, Any]:
    """What the sliders start at: the loaded design's and conditions' values."""
    payload = conditions.payload
    motors = design.actuators
    return {
        **{key: getattr(design, key) for key in ("l1", "l2", "l3", "body_length", "body_width")},
        "actuators": {
            joint: None if motors is None else _catalog_name(getattr(motors, joint))
            for joint in LEG_JOINTS
        },
        "nominal_angles": list(design.nominal_angles),
        "payload": payload.mass,
        "payload_at": payload.position_on(design),
        "speed": conditions.gait.speed,
        "stride": conditions.gait.stride,
        "step_height": conditions.gait.step_height,
    }


def _catalog_name(actuator: Actuator) -> str | None:
    """The catalog entry ``actuator`` is exactly (no key overridden), else ``None``."""
    catalog = shipped_catalog()
    if (
        actuator.catalog not in catalog.names
        or catalog.entry(actuator.catalog).actuator != actuator
    ):
        return None
    return actuator.catalog
