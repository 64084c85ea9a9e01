"""Report part: the motors and the battery of the design, walking the report's gait.

Presentation only: the numbers come from one gait period of the report's design
(:func:`~hexaleg.gait.analysis.analyze_gait` at the report's gait,
:attr:`~.options.ReportOptions.gait`) through its actuators
(:mod:`hexaleg.electrical`): each joint type's actuator, its every margin to its ratings
(peak torque, continuous torque against the RMS, supply voltage, speed), where the power
goes (mechanical against copper loss), the energy per kilometre and the battery's range.
The sizing is the plan's torques, what a torque-controlled robot needs; the part says so,
and with ``--simulate`` sets both simulated controllers' peaks beside the plan's.
A design without ``[actuators]`` gets one sentence saying how to give them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.actuators import Actuators
from hexaleg.electrical.period import ElectricalResult
from hexaleg.electrical.ratings import RATED
from hexaleg.evaluation.metrics import significant
from hexaleg.gait.analysis import GaitAnalysis
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.figures.canvas import save
from hexaleg.output.figures.motors import envelope_figure, power_split_figure
from hexaleg.output.report.document import Figure, Section, table
from hexaleg.output.report.part import Part, ReportData, where_legs_are_the_designs
from hexaleg.output.report.simulation import SimulationRecord
from hexaleg.output.report.yours import YoursRecord
from hexaleg.sim.measure import WalkMetrics

POWER, ENVELOPE = "gait_power", "gait_envelope"
"""The figures' file names, without extension."""


@dataclass(frozen=True)
class MotorsRecord:
    """The design's gait period through its motors (None: the design has no actuators).

    Attributes:
        walked: The period, with its electrical figures and max speed.

    """

    walked: GaitAnalysis | None


def compute(data: ReportData) -> MotorsRecord:
    """The report's gait walked by your design (its one evaluation's), if it has actuators."""
    if data.design.actuators is None:
        return MotorsRecord(None)
    return MotorsRecord(data[YoursRecord].evaluation.gait)


def summary(record: MotorsRecord) -> str:
    """One sentence on the period's electrical cost (empty without actuators)."""
    if record.walked is None or record.walked.electrical is None:
        return ""
    electrical = record.walked.electrical
    share = electrical.copper_loss_per_period / max(electrical.energy_per_period, 1e-300)
    return (
        f"Through its motors your design draws {significant(electrical.average_power)} W "
        f"walking this gait, {significant(electrical.energy_per_km)} Wh/km (electrical cost "
        f"of transport {significant(electrical.cost_of_transport)}; the copper loss is "
        f"{100 * share:.0f} % of the energy drawn)."
    )


def section(data: ReportData) -> Section:
    """The actuators, their margins, the power split, Wh/km and range, and the figures."""
    walked = data[MotorsRecord].walked
    title = "Motors and battery"
    actuators = data.design.actuators
    if walked is None or walked.electrical is None or actuators is None:
        return Section(title, (
            "The design names no actuators, so its joints are held against its rated torques "
            "and speeds only. Give `[actuators.root]`, `[actuators.hip]` and "
            "`[actuators.knee]` tables in the design file (`catalog = \"NAME\"` takes a real "
            "actuator from `hexaleg actuators`) and a `[battery]` for the currents, voltages, "
            "copper loss, energy per kilometre and range.",
        ))  # fmt: skip
    electrical = walked.electrical
    return Section(
        title,
        (
            f"Walking {walked.gait.named} ({walked.gait.pattern} at {walked.gait.speed:.2g} m/s), "
            f"the robot weighs {significant(walked.mass)} kg with its motors "
            f"({significant(actuators.total_mass)} kg){_battery_mass(data)}. Every motor is "
            f"fed from one {electrical.supply:g} V bus, its windings at "
            f"{electrical.winding_temperature:g} °C (R below at that temperature). Each joint "
            "type's actuator (V: the supply its datasheet quotes):",
            _actuator_table(actuators),
            *_controller_blocks(data, walked),
            "Every margin to the ratings, worst leg of each joint type (ratio above 1: over "
            "the rating):",
            _margin_table(electrical),
            _energy(walked, electrical),
            Figure(POWER, "Each joint type's six motors' power over the period: the shafts' "
                   "mechanical power τ_m·ω_m, the copper loss i²R, and their sum P_e"),
            Figure(ENVELOPE, "Every sample's joint speed and torque over its motor's envelope: "
                   "peak and continuous torque, speed rating and the bus's voltage line"),
        ),
    )  # fmt: skip


def _controller_blocks(data: ReportData, walked: GaitAnalysis) -> tuple[str, ...]:
    """Which controller the sizing holds for, and (``--simulate``) both controllers' peaks."""
    said = (
        "The margins below are the plan's joint torques: what a torque-controlled robot needs "
        "(walked in MuJoCo on the plan's torques with a low-gain PD, it needs them within "
        "10 %). Position servos as stiff as hobby servos need more, the roots most: they push "
        "the standing feet against each other and drag a lifting foot"
    )
    if not data.options.simulate:
        return (said + " (`report --simulate` measures both).",)
    walks = data[SimulationRecord].walks
    rows = [
        [joint, f"{walked.metrics.peak_torque[joint]:.3g}"]
        + [_peak(walk.metrics, joint) for walk in walks.values()]
        for joint in LEG_JOINTS
    ]
    return (
        said + ". Peak joint torque [N·m], worst leg, planned and simulated:",
        table(["joint", "plan (the sizing)", "servos", "torque control"], rows),
    )


def _peak(metrics: WalkMetrics | None, joint: str) -> str:
    """A simulated walk's peak torque of ``joint`` [N·m] (or that it diverged)."""
    return "diverged" if metrics is None else f"{metrics.peak_torque[joint]:.3g}"


def _battery_mass(data: ReportData) -> str:
    battery = data.design.battery
    return "" if battery is None else f" and its battery ({significant(battery.mass)} kg)"


def _actuator_table(actuators: Actuators) -> str:
    header = ["joint", "actuator", "N", "k_t [N·m/A]", "R [Ω]", "η", "peak / continuous [N·m]",
              "V [V]", "speed [rad/s]", "mass [kg]"]  # fmt: skip
    rows = [
        [joint, a.catalog or "given", f"{a.gear_ratio:g}", significant(a.torque_constant),
         significant(r), significant(a.gearbox_efficiency),
         f"{significant(a.peak_torque)} / {significant(a.continuous_torque)}",
         f"{a.voltage:g}", significant(a.rated_speed), significant(a.mass)]
        for joint, a, r in zip(LEG_JOINTS, actuators.joints, actuators.resistances, strict=True)
    ]  # fmt: skip
    return table(header, rows)


def _margin_table(electrical: ElectricalResult) -> str:
    ratings = electrical.ratings
    worst = ratings.ratios.max(axis=1)  # (4, 3): each quantity's worst leg per joint type
    values = ratings.values.max(axis=1)
    units = {"peak_torque": "N·m", "continuous_torque": "N·m", "voltage": "V", "speed": "rad/s"}
    names = {"continuous_torque": "RMS torque / continuous", "voltage": "voltage needed / bus"}
    rows = [
        [names.get(quantity, quantity.replace("_", " ") + " / rating") + f" [{units[quantity]}]"]
        + [
            f"{significant(values[k, j])} / {significant(ratings.ratings[k, j])} "
            f"({worst[k, j]:.2f}{', OVER' if worst[k, j] > 1 else ''})"
            for j in range(len(LEG_JOINTS))
        ]
        for k, quantity in enumerate(RATED)
    ]
    return table(["quantity", *LEG_JOINTS], rows)


def _energy(walked: GaitAnalysis, electrical: ElectricalResult) -> str:
    mechanical, copper = electrical.mechanical_power, electrical.copper_power
    text = (
        f"Power: {significant(electrical.average_power)} W from the battery on average, of "
        f"which the shafts give {significant(mechanical)} W net and the windings lose "
        f"{significant(copper)} W as heat (copper loss i²R, "
        f"{100 * copper / max(electrical.average_power, 1e-300):.0f} % of what is drawn)"
        f"{_unreturned(electrical)}; {significant(electrical.energy_per_km)} Wh/km, "
        f"an electrical cost of transport of {significant(electrical.cost_of_transport)} "
        f"against a mechanical one of {significant(walked.metrics.cost_of_transport)}."
    )
    battery = electrical.battery
    if battery is not None and math.isfinite(battery.range):
        text += (
            f" The {significant(battery.capacity)} Wh battery lasts "
            f"{significant(battery.runtime)} h: {significant(battery.range)} km."
        )
    limit = walked.max_speed
    if limit is not None:
        text += f" Max speed within every rating: {limit.value:.3g} m/s ({limit.limited_by})."
    return text


def _unreturned(electrical: ElectricalResult) -> str:
    """What the battery gives beyond the net shaft power, copper loss and electronics."""
    rest = electrical.average_power - electrical.mechanical_power - electrical.copper_power
    rest -= electrical.electronics_power
    if rest <= 1e-9 * max(electrical.average_power, 1e-300):
        return ""
    return (
        f"; {significant(rest)} W more is what braking joints give back that the battery does "
        "not take (regeneration below 1)"
    )


def write_files(data: ReportData, out: Path) -> None:
    """The power split and the envelopes (a design with actuators)."""
    walked = data[MotorsRecord].walked
    if walked is None or walked.electrical is None:
        return
    save(power_split_figure(walked), out / f"{POWER}.png", svg=data.options.svg)
    save(envelope_figure(walked), out / f"{ENVELOPE}.png", svg=data.options.svg)


def to_json(record: MotorsRecord) -> dict[str, Any]:
    """``motors``: the period's electrical figures and battery (null without actuators)."""
    walked = record.walked
    if walked is None or walked.electrical is None:
        return {"motors": None}
    over = [o.to_dict() for o in walked.over_rating]
    return {"motors": walked.electrical.to_dict() | {"over_rating": over}}


PART = Part(
    MotorsRecord,
    compute,
    section,
    needs=(YoursRecord,),
    step="motors",
    files=write_files,
    json=to_json,
    level=2,
    holds=where_legs_are_the_designs("", ""),
)
