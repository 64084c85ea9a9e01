"""Report parts of a robot whose legs are its own: what the report tells of a robot file.

The paper's sections (the workspace and manipulability sweeps, the free-coupled
flexibility, the template body's sensitivity, the recommendation on the paper's ratio
grid) hold where every leg is the design's, the paper's leg of l1, l2, l3. A robot whose
legs are its own (a robot file's, each leg its general leg) has these parts instead
(:data:`~hexaleg.output.report.registry.PARTS` holds both; each part says whether it holds):
its metrics as read and the sections left out with why (:data:`ROBOT`), each leg's swing
phase (:data:`SWING`), the axis-locked flexibility with its statics and walking payload
(:data:`STANCE`) and, with requirements, the decision over its segments (:data:`DECISION`).
The design, the study of its segments and the 3-D view are the report's own parts.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.evaluation.evaluate import Evaluation
from hexaleg.evaluation.metrics import METRICS, MetricSpec
from hexaleg.gait.capacity import WalkingCapacity
from hexaleg.gait.defaults import default_gait
from hexaleg.output.figures import extremes_figure, save
from hexaleg.output.report.document import Figure, Section, table, write_csv
from hexaleg.output.report.part import LeftOut, Part, ReportData, where_legs_are_their_own
from hexaleg.output.report.requirements import requirement_blocks
from hexaleg.output.report.yours import YoursRecord
from hexaleg.ratings import NEEDS_RATING
from hexaleg.stance.constraints import TRANSLATIONS
from hexaleg.stance.extremes import FlexibilityResult
from hexaleg.statics.loads import LoadsAnalysis
from hexaleg.study.decide import DecideResult, decide
from hexaleg.study.executors import local_pool
from hexaleg.swing.manipulability import analyze_manipulability
from hexaleg.swing.workspace import analyze_workspace

METRIC_NAMES: tuple[MetricSpec, ...] = (
    METRICS.fb,
    METRICS.payload_capacity,
    METRICS.walking_payload_capacity,
    METRICS.max_speed,
    METRICS.stability_margin,
    METRICS.max_slope,
    METRICS.ground_clearance,
    METRICS.robot_mass,
    METRICS.nominal_height,
    METRICS.leg_length,
)
"""The robot's metrics the first section lists (as read, under the report's gait)."""


# -- the robot as read ----------------------------------------------------------------------


@dataclass(frozen=True)
class RobotRecord:
    """The robot as read, measured once for every metric the report lists.

    Attributes:
        source: What names it (its robot file).
        evaluation: Its metrics under the report's gait (no payload, level ground).
        left_out: The report's sections that do not hold for it, and why.
        gait_named: The walked gait's name ("the default gait" for the robot's own).

    """

    source: str
    evaluation: Evaluation
    left_out: tuple[LeftOut, ...] = ()
    gait_named: str = ""


def compute_robot(data: ReportData) -> RobotRecord:
    """The robot's metrics, as its one evaluation measured them."""
    evaluation = data[YoursRecord].evaluation
    return RobotRecord(data.robot.name, evaluation, data.left_out, _gait_named(data))


def robot_section(data: ReportData) -> Section:
    """The robot, its metrics, and the template's sections left out."""
    record = data[RobotRecord]
    rows = []
    for spec in METRIC_NAMES:
        value, cause = record.evaluation.metrics.value(spec), record.evaluation.causes[spec]
        unit = "" if spec.unit in ("1", "-") else f" {spec.unit}"
        shown = "—" if math.isnan(value) else f"{value:.4g}{unit}"
        rows.append((spec.label, shown, "" if cause is None else str(cause)))
    skipped = [(left.section, left.why) for left in record.left_out]
    return Section(
        f"Your robot: {record.source}",
        (
            "The robot file as read (each leg its own general leg, the file's masses, joint "
            f"limits and feet), walking {record.gait_named} for the walking numbers:",
            table(["metric", "value", "limited by"], rows),
            "Sections of hexaleg's report left out for an imported robot, and why:",
            table(["section", "why it is left out"], skipped),
        ),
    )


def robot_json(record: RobotRecord) -> dict[str, Any]:
    """``robot``: the file and its metrics; ``skipped``: the sections left out and why."""
    evaluation = record.evaluation
    return {
        "robot": {
            "urdf": record.source,
            "metrics": evaluation.metrics.to_dict(),
            "limited_by": {k: str(v) for k, v in evaluation.causes.to_dict().items()},
        },
        "skipped": [{"section": left.section, "why": left.why} for left in record.left_out],
    }


def robot_headline(data: ReportData) -> tuple[str, ...]:
    """The robot and its FB."""
    record = data[RobotRecord]
    return (f"{record.source}: FB = {record.evaluation.metrics.value(METRICS.fb):.4f}",)


ROBOT = Part(RobotRecord, compute_robot, robot_section, needs=(YoursRecord,), step="your robot",
             json=robot_json, holds=where_legs_are_their_own,
             headline=robot_headline)  # fmt: skip


# -- the swing phase of each leg -----------------------------------------------------------


@dataclass(frozen=True)
class RobotSwingRecord:
    """Each leg's workspace and manipulability, by its own general leg.

    Attributes:
        legs: Per leg (hexaleg's name), ``workspace`` and ``manipulability`` as
            ``workspace --urdf`` and ``manipulability --urdf`` give them (SI units).

    """

    legs: dict[str, dict[str, Any]]


def compute_swing(data: ReportData) -> RobotSwingRecord:
    """Monte Carlo and planar workspace, optimum pose and w_A of every leg."""
    design, samples = data.design, data.options.monte_carlo_samples
    legs = {}
    own = data.robot.own_legs
    assert own is not None  # the part holds where the legs are their own
    for name, geometry in own.items():
        legs[name] = {
            "workspace": analyze_workspace(design, samples, leg=geometry).to_dict(design=False),
            "manipulability": analyze_manipulability(design, general=geometry).to_dict(
                design=False
            ),
        }
    return RobotSwingRecord(legs)


def swing_section(data: ReportData) -> Section:
    """One row a leg: planar areas, Monte Carlo reach, optimum w and average w_A."""
    rows = []
    for name, leg in data[RobotSwingRecord].legs.items():
        area, cloud = leg["workspace"]["area"], leg["workspace"]["monte_carlo"]
        optimum, average = leg["manipulability"]["optimum"], leg["manipulability"]["average"]
        reach = cloud["upper_bound"][0]  # along the leg-root frame's x, toward the hip
        cells = (area["rectangular"], area["improved"], reach, optimum["w"], average["improved"])
        rows.append((name, *(f"{value:.4g}" for value in cells)))
    return Section(
        "Swing phase: each leg's workspace and manipulability",
        (
            "Each leg by its own general leg (offsets and bends as the file draws them), in "
            "the paper's joint-limit sets: planar workspace areas (Tables 3 and 4) in m², the "
            f"farthest Monte Carlo foot point ({data.options.monte_carlo_samples} samples) "
            "along the leg root's x in m, the optimum w = |det J| and the average w_A on the "
            "improved domain in m³ (eq 25–27), as `workspace --urdf` and `manipulability "
            "--urdf` give them:",
            table(
                ["leg", "rectangular area", "improved area", "reach x", "optimum w", "w_A"], rows
            ),
        ),
    )


def swing_json(record: RobotSwingRecord) -> dict[str, Any]:
    """``legs``: each leg's ``workspace`` and ``manipulability``."""
    return {"legs": record.legs}


SWING = Part(RobotSwingRecord, compute_swing, swing_section, step="swing phase",
             json=swing_json, level=2, holds=where_legs_are_their_own)  # fmt: skip


# -- axis-locked flexibility and the statics --------------------------------------------


@dataclass(frozen=True)
class RobotStanceRecord:
    """The robot's axis-locked flexibility and its statics there.

    Attributes:
        flexibility: The twelve axis-locked extremes, all six feet down.
        loads: The statics at the nominal stance and at each extreme (no payload).
        walking: The largest payload carried walking the report's gait.

    """

    flexibility: FlexibilityResult
    loads: LoadsAnalysis
    walking: WalkingCapacity | None


def compute_stance(data: ReportData) -> RobotStanceRecord:
    """Axis-locked flexibility, its statics and the walking capacity: the one evaluation's."""
    found = data[YoursRecord].evaluation
    assert found.flexibility is not None and found.loads is not None  # kept
    spec = METRICS.walking_payload_capacity
    cause, walks = found.causes[spec], found.walks
    walking = (
        None
        if cause is None or walks is None
        else WalkingCapacity(found.metrics.value(spec), cause, walks)
    )
    return RobotStanceRecord(found.flexibility, found.loads, walking)


def _displacement(value: float, axis: str) -> str:
    if axis in TRANSLATIONS:
        return f"{value:+.4f} m"
    return f"{value:+.4f} rad ({math.degrees(value):+.2f}°)"


ROUND_OFF = 1e-9
"""A torque below this share of its joint's rating is round-off of a zero [-]."""


def _torque(value: float, rated: float) -> str:
    """A peak |τ| [N·m] in three digits; round-off of a zero (2e-18 N·m) as 0."""
    return "0" if abs(value) < ROUND_OFF * rated else f"{value:.3g}"


def stance_section(data: ReportData) -> Section:
    """The twelve extremes, FB, the torques there and the payload capacities."""
    record = data[RobotStanceRecord]
    locked, loads = record.flexibility, record.loads
    nominal = loads.nominal.peak_torques()
    given = data.design.rated_torques
    rated = dict(zip(nominal, given or (1.0,) * 3, strict=True))  # 1 N·m: round-off's scale
    peaks = loads.peak_torques
    torques = [
        (
            j,
            f"{rated[j]:g}" if given else "not given",
            _torque(nominal[j], rated[j]),
            _torque(peaks[j], rated[j]),
        )
        for j in nominal
    ]
    standing, walks = _capacities(record)
    return Section(
        "Body flexibility and statics (axis-locked, the file's joint limits)",
        (
            f"All six feet on their nominal footholds, one body coordinate moving at a time: "
            f"**FB = {locked.fb:.4f}**. Each extreme stops at the first constraint that breaks:",
            table(
                ["direction", "extreme", "stopped by"],
                [(e.name, _displacement(e.value, e.axis), e.description) for e in locked.extremes],
            ),
            Figure("flexibility_extremes", "How far the body moves along and about each axis"),
            f"The robot weighs {loads.nominal.mass:.3f} kg; stability margin at the nominal "
            f"stance {loads.nominal.stability_margin:.4f} m. Payload capacity standing: "
            f"{standing}; walking {data[RobotRecord].gait_named}: {walks}. Peak |τ| in N·m:",
            table(["joint", "rated", "nominal stance", "over the extremes"], torques),
        ),
    )


def _gait_named(data: ReportData) -> str:
    """The walked gait's name: "the default gait" for the robot's own (sized to it).

    The robot's own is :attr:`~.options.ReportOptions.default_gait` when the caller found
    it already (the command line has), else found here.
    """
    gait, default = data.options.gait, data.options.default_gait
    default = default_gait(data.model) if default is None else default
    return "the default gait" if gait == default else gait.named


def _capacities(record: RobotStanceRecord) -> tuple[str, str]:
    """The payload capacities standing and walking, in words (each may need a rating)."""
    capacity, walking = record.loads.capacity, record.walking
    standing = (
        NEEDS_RATING
        if capacity is None
        else f"**{capacity.mass:.2f} kg**, limited by {capacity.limited_by}"
    )
    if walking is None:
        return standing, NEEDS_RATING
    if not walking.walks:
        cannot = "none (it cannot walk it: a design file's `[gait]` table sets one it can)"
        return standing, f"{cannot}, limited by {walking.limited_by}"
    return standing, f"**{walking.mass:.2f} kg**, limited by {walking.limited_by}"


def stance_files(data: ReportData, out: Path) -> None:
    """The extremes figure and ``extremes.csv``."""
    locked = data[RobotStanceRecord].flexibility
    save(extremes_figure(locked), out / "flexibility_extremes.png", svg=data.options.svg)
    write_csv(
        out / "extremes.csv",
        [{"direction": e.name, "value": e.value, "limited_by": e.description}
         for e in locked.extremes],
    )  # fmt: skip


def stance_json(record: RobotStanceRecord) -> dict[str, Any]:
    """``flexibility`` (axis-locked), ``loads`` (axis-locked) and the walking capacity."""
    loads = {k: v for k, v in record.loads.to_dict().items() if k != "design"}
    return {
        "flexibility": {"axis": record.flexibility.to_dict()},
        "loads": {"axis": loads},
        METRICS.walking_payload_capacity.name: None
        if record.walking is None
        else record.walking.to_dict(),
    }


STANCE = Part(
    RobotStanceRecord,
    compute_stance,
    stance_section,
    needs=(YoursRecord,),
    step="flexibility and statics",
    files=stance_files,
    json=stance_json,
    level=2,
    holds=where_legs_are_their_own,
)


# -- the decision over its segments ------------------------------------------------------


@dataclass(frozen=True)
class RobotDecisionRecord:
    """The best segments for the user's requirements (``None``: none given)."""

    answer: DecideResult | None


def compute_decision(data: ReportData) -> RobotDecisionRecord:
    """Decide over the robot's segments when the user gave requirements."""
    return RobotDecisionRecord(requirements_answer(data))


def requirements_answer(data: ReportData) -> DecideResult | None:
    """The decision over the robot for the user's requirements; ``None`` without them."""
    requirements = data.options.requirements
    if requirements is None:
        return None
    with local_pool(data.options.workers) as pool:
        return decide(data.robot, requirements, executor=pool, progress=False)


def decision_section(data: ReportData) -> Section:
    """The answer to the requirements, or how to ask."""
    answer = data[RobotDecisionRecord].answer
    if answer is None:
        return Section(
            "Your requirements",
            ("None given: `report --urdf FILE --payload KG ...` (or a `[requirements]` table) "
             "adds the best segments of your robot that meet them.",),
        )  # fmt: skip
    return Section("Your requirements", requirement_blocks(answer))


def decision_json(record: RobotDecisionRecord) -> dict[str, Any]:
    """``requirements_decision`` when requirements were given."""
    return {} if record.answer is None else {"requirements_decision": record.answer.to_dict()}


def answer_lines(answer: DecideResult | None, digits: str) -> tuple[str, ...]:
    """The lengths that meet the requirements, if some were given (``digits``: the format)."""
    if answer is None:
        return ()
    lengths = ", ".join(f"{length:{digits}}" for length in answer.best.design.lengths)
    verdict = "meets" if answer.feasible else "comes closest to meeting"
    return (f"l = ({lengths}) m {verdict} your requirements",)


def decision_headline(data: ReportData) -> tuple[str, ...]:
    """The lengths that meet the requirements, if some were given."""
    return answer_lines(data[RobotDecisionRecord].answer, ".4g")


DECISION = Part(RobotDecisionRecord, compute_decision, decision_section, step="decision",
                json=decision_json, level=0, holds=where_legs_are_their_own,
                headline=decision_headline)  # fmt: skip


__all__ = ["DECISION", "ROBOT", "STANCE", "SWING", "requirements_answer"]
