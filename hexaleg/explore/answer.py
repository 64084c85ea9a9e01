"""The explorer's answer about one design: every number the page shows, JSON-ready.

One :func:`~hexaleg.evaluation.evaluate.evaluate` measures the design under the sliders'
conditions, and every number of the answer reads it: the metrics of :data:`EXPLORED`,
named as the command line's ``--json`` names them (``fb``, ``payload_capacity``,
``peak_torque`` per joint type, ``max_speed`` ...) with what limits each, the nominal
stance's points and the extremes for the drawing, the legs' tubes where the design has a
``[structure]``, and, when the design file has ``[requirements]``, each one checked on
that same evaluation. The sliders start at the requirements' conditions (payload, slope,
gait); where they have been moved off them, the answer says which condition differs
(``requirements_conditions``), so a check is never read as made under conditions it was
not, and no quantity is shown with two values.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import fields, is_dataclass, replace
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
from hexaleg.statics.ground import Ground
from hexaleg.structure.sizing import SizedStructure
from hexaleg.swing.workspace import standing_reach

__all__ = ["EXPLORED", "ROWS", "answer", "conditions_unlike", "walking_on"]

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


def _row(spec: MetricSpec) -> dict[str, str]:
    """A metric's row of the page's table: its key in the answer, its name, what it is, its unit."""
    key = spec.name if spec.torque is None else f"{spec.torque}_torque.{spec.joint}"
    unit = "" if spec.unit == "1" else spec.unit
    return {"key": key, "label": spec.label, "text": spec.text, "unit": unit}


_GAIT = SCALARS.index(METRICS.max_speed) + 1
ROWS: tuple[dict[str, str], ...] = tuple(
    _row(spec) for spec in (*SCALARS[:_GAIT], *EXPLORED[len(SCALARS) :], *SCALARS[_GAIT:])
)
"""The page's table of numbers: a row per metric of :data:`EXPLORED`, as its declaration
says it (the page declares none of its own), the torques after the max speed."""


def answer(
    design: HexapodDesign,
    conditions: Conditions,
    requirements: Requirements,
    model: HexapodModel | None = None,
    ground: Ground | None = None,
) -> dict[str, Any]:
    """The page's numbers for ``design`` under ``conditions``, checked against ``requirements``.

    Args:
        design: The design.
        conditions: What it is measured under (the sliders' payload and gait).
        requirements: The design file's requirements (none given: nothing checked), checked
            on the same evaluation, under ``conditions``.
        model: Its model (an imported robot's at these segments); derived from hexaleg's
            template (:func:`~hexaleg.robot.model_cache.model_of`) if omitted.
        ground: The ground the gait is walked on (the slope slider's; ``None``: the
            conditions' own), :func:`walking_on`; the answer's ``grounds`` say which.

    """
    start = time.perf_counter()
    conditions = walking_on(conditions, ground)
    model = model_of(design) if model is None else model
    goal = Goal(requirements.resolved(design)) if requirements.given else None
    metrics = {*EXPLORED, *(goal.metrics if goal is not None else ())}
    found = evaluate(design, metrics, replace(conditions, keep=True), model=model)
    out = _numbers(found) | {"stance": _stance(model, found), "extremes": _extremes(model, found)}
    heading = conditions.gait.heading
    out["grounds"] = [
        g.to_dict(heading) | {"text": g.describe(heading)} for g in conditions.grounds
    ]
    out["structure"] = _structure(found)
    if goal is not None:
        out["requirements"] = _checks(goal, found)
        out["requirements_conditions"] = conditions_unlike(goal.conditions, conditions, design)
    out["evaluate_ms"] = 1000 * (time.perf_counter() - start)
    return out


def walking_on(conditions: Conditions, ground: Ground | None) -> Conditions:
    """``conditions`` with the gait walked on ``ground`` (the slope slider's) alone.

    ``None``: the conditions' own grounds (the requirements' walking slope, walked up, down
    and across, or level ground).
    """
    return conditions if ground is None else replace(conditions, grounds=(ground,))


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
    out["rows"] = ROWS
    return out


def _stance(model: HexapodModel, found: Evaluation) -> dict[str, Any]:
    """The nominal stance's points, world frame [m], and each leg's use of its ratings.

    ``chains``: each leg's three joints and its foot; ``utilisation``: each leg's largest
    peak |τ| over a gait period, on every ground walked, against its joint's rating [-]
    (``None`` where a period breaks a constraint: a joint limit, a foot out of reach — it is
    not walked; and every leg's when the design gives no ratings, as ``rated_torques``).
    """
    design = model.design
    chains = model.leg_chains(model.nominal_configuration())
    utilisation: list[float | None] = [None] * len(model.leg_names)
    rated = design.rated_torques
    periods = found.gaits or (() if found.gait is None else (found.gait,))
    if periods and all(period.walkable for period in periods) and rated is not None:
        torques = np.concatenate([period.joint_torques for period in periods])  # (T, legs, 3)
        peaks = np.abs(torques).max(axis=0)  # (legs, joints) [N·m]
        used = dict(zip(periods[0].legs, peaks / np.asarray(rated), strict=True))
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


def conditions_unlike(
    required: Conditions, shown: Conditions, design: HexapodDesign
) -> list[dict[str, Any]]:
    """Where the conditions ``shown`` differ from the ``required`` ones, condition by condition.

    Each entry: ``name`` (``payload.mass``, ``gait.period``, ...), the ``required`` value and
    the value ``shown`` [SI units, radians]; empty when the checks are made under the
    requirements' own conditions. The payload's default position is spelled out first.
    """
    wanted, given = _flat(_placed(required, design)), _flat(_placed(shown, design))
    return [
        {"name": name, "required": value, "shown": given[name]}
        for name, value in wanted.items()
        if given[name] != value
    ]


def _flat(value: Any, prefix: str = "") -> dict[str, Any]:
    """A record's fields, and its records' fields, by dotted name (JSON-ready values).

    A tuple of records (the grounds walked) is one condition: a list of each one's fields.
    """
    if isinstance(value, tuple) and value and all(is_dataclass(item) for item in value):
        return {prefix: [_flat(item) for item in value]}
    if not is_dataclass(value) or isinstance(value, type):
        return {prefix: list(value) if isinstance(value, tuple) else value}
    out: dict[str, Any] = {}
    for spec in fields(value):
        if spec.name != "keep":  # what an evaluation keeps, not what it is measured under
            out |= _flat(getattr(value, spec.name), f"{prefix}.{spec.name}".lstrip("."))
    return out


def _placed(conditions: Conditions, design: HexapodDesign) -> Conditions:
    """The conditions with the payload's position spelled out (its default made explicit)."""
    payload = conditions.payload
    x, y, z = payload.position_on(design)
    return replace(conditions, payload=Payload(payload.mass, (x, y, z)))


def _structure(found: Evaluation) -> dict[str, Any] | None:
    """The legs' tubes as the evaluation checked them; ``None`` without a tube to check.

    ``tubes``: each segment's outer diameter, wall [m] and mass [kg]; ``worst_ratio`` and
    ``worst`` (case, leg, segment): the largest von Mises stress over what is allowed [-],
    over the standing cases (nominal stance and the twelve extremes, with the payload) and
    the gait period, where it is walked; ``deflection`` [m]: the largest standing foot
    deflection, with its ``deflection_limit`` [m]; ``feasible``: every ratio ≤ 1 and the
    deflection within its limit.
    """
    standing = found.structure or (None if found.loads is None else found.loads.structure)
    if standing is None:
        return None
    walking = None if found.gait is None else found.gait.structure
    checks = [standing]  # the period's where it was walked (not broken off: finite ratios)
    checks += [walking] if walking is not None and math.isfinite(walking.worst_ratio) else []
    worst = max(checks, key=lambda check: check.worst_ratio)
    return {
        "material": standing.structure.material.name,
        "tubes": standing.tubes_dict(),
        "worst_ratio": worst.worst_ratio,
        "worst": worst.worst,
        "deflection": standing.deflection,
        "deflection_limit": standing.limit,
        "feasible": all(check.feasible for check in checks),
        "sizing": None if found.sized is None else _sizing(found.sized),
    }


def _sizing(sized: SizedStructure) -> dict[str, Any]:
    """How the tubes were sized: whether the grid held every case, in how many rounds."""
    return {"found": sized.found, "iterations": sized.iterations, "settled": sized.settled}


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
        "slope_deg": math.degrees(conditions.grounds[0].slope),  # uphill: the first walked
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
