"""``hexaleg gait``: one gait period of the design: torques, speeds, power, energy, limits."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from hexaleg._io import write_text
from hexaleg.cli.best_posture import add_best_posture_option, posing
from hexaleg.cli.gait_options import (
    add_gait_options,
    add_ground_options,
    gait_from_args,
    ground_from_args,
)
from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import (
    add_design_options,
    add_output_options,
)
from hexaleg.cli.output import (
    check_outputs,
    lengths_title,
    print_json,
    print_table,
    report_files,
    summary_stream,
    write_plots,
)
from hexaleg.cli.payload_options import (
    add_payload_options,
    add_safety_factor_option,
    payload_from_args,
    rated_text,
    safety_factor_from_args,
)
from hexaleg.cli.structure_rows import structure_rows
from hexaleg.evaluation.sizing import sized_for
from hexaleg.gait.analysis import GaitAnalysis, analyze_gait
from hexaleg.gait.walkable import require_walkable
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.figures.gait import write_gait_figures
from hexaleg.output.figures.motors import write_motor_figures
from hexaleg.output.viewer.gait import write_gait_html
from hexaleg.ratings import NEEDS_RATING
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.robot import Robot

DESCRIPTION = (
    "One gait period of the design (SI units: s, m, kg, N·m, rad/s, W, J): the body walks "
    "at constant velocity, level, at its nominal height; standing feet stay put, swinging "
    "feet follow a smooth lift-and-place path. Joint motion from the closed-form IK, "
    "torques from Pinocchio's inverse dynamics on the free-flyer model with the standing "
    "feet's forces split as in `loads`. Prints the peak and RMS torques, peak joint speeds "
    "and power, the positive work and cost of transport per period, the ZMP margin, "
    "whether the period is feasible, the max stride and the max speed within the ratings; "
    "flags every joint over its rating. A design with [actuators] also gets each motor's "
    "current, voltage and copper loss, the electrical energy, cost of transport and Wh/km, "
    "the battery's runtime and range, and checks continuous torque and voltage against the "
    "bus. --slope-deg walks a plane inclined that much (uphill, downhill or across): gravity "
    "tilts in the body frame, which stays parallel to it, and each standing foot's force is "
    "held within the friction cone. With --urdf, "
    "your robot: each leg its own general leg and nominal posture, the file's masses, "
    "joint limits (standing and swinging) and ratings; angles and torques on hexaleg's θ, "
    "and in the file's joints (urdf_* in the JSON and CSV). With a [structure] table, each "
    "leg tube's worst stress ratio over the period, the links' inertial forces included (a "
    "tube over its strength makes the period infeasible)."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_gait_options(parser)
    add_ground_options(parser)
    add_payload_options(parser)
    add_safety_factor_option(parser)
    add_best_posture_option(parser)
    add_output_options(parser)
    parser.add_argument("--csv", metavar="FILE", help="write the time series (one row per sample)")
    parser.add_argument(
        "--html", metavar="FILE", help="write a 3-D animation of the period (meshcat, static HTML)"
    )


def run(args: argparse.Namespace) -> int:
    """Walk one period; print a table or JSON; write the CSV, figures and animation if asked."""
    inputs = inputs_from_args(args, posing=posing(args), sizing=sized_for)
    robot, sized = inputs.robot, inputs.sized
    model = robot.model
    gait = gait_from_args(args, inputs.gait)
    payload, ground = payload_from_args(args), ground_from_args(args)
    check_outputs({"--csv": args.csv, "--html": args.html}, {"--plot": args.plot})  # before
    analysis = analyze_gait(
        model.design,
        gait,
        payload,
        distribution=args.distribution,
        ground=ground,
        model=model,
        safety_factor=safety_factor_from_args(args, inputs.written),
    )
    require_walkable(analysis, model)  # an unwalkable period: one line, nothing written
    written = []
    if args.csv is not None:
        written.append(_write_csv(analysis, Path(args.csv), robot))
    if args.plot is not None:
        write_plots(args.plot, lambda out: _write_figures(analysis, model, out))
    if args.html is not None:
        written.append(write_gait_html(model, analysis, args.html))
    report_files(written)
    summary = summary_stream(args.csv, args.html)
    if args.json:
        out = analysis.to_dict()
        if sized is not None:
            out["structure"]["sizing"] = sized.to_dict()
        print_json(robot.posture() | out, summary)
        return 0
    title = lengths_title(robot.titled("Walking"), model.design.lengths)
    table = rows(analysis) + structure_rows(analysis.structure, sized)
    print_table(title, table, summary)
    return 0


def _write_csv(analysis: GaitAnalysis, path: Path, robot: Robot) -> Path:
    """The time series, a robot file's joints also in the file's own (``_urdf_*`` columns)."""
    import pandas as pd

    in_file = robot.file_columns(analysis.legs, analysis.joint_angles, analysis.joint_torques)
    columns = analysis.time_series() | in_file
    return write_text(path, pd.DataFrame(columns).to_csv(index=False))


def _write_figures(analysis: GaitAnalysis, model: HexapodModel, out: Path) -> list[Path]:
    written = write_gait_figures(analysis, out, analysis.reach_clouds(model))
    if analysis.electrical is not None:
        written += write_motor_figures(analysis, out)
    return written


def _friction_needed(analysis: GaitAnalysis) -> str:
    needed, friction = analysis.friction_needed, analysis.ground.friction
    if math.isinf(needed):
        return f"∞: a standing foot would pull on the ground (μ = {friction:g})"
    return f"{needed:.3g} (largest tangential / normal force of a standing foot; μ = {friction:g})"


def _feasible(analysis: GaitAnalysis) -> str:
    """``yes``, ``no: why``, and which ratings it could not check (the design gives none)."""
    why, unchecked = analysis.infeasible_because, analysis.unchecked_ratings
    said = "yes" if why is None else f"no: {why}"
    if not unchecked:
        return said
    options = ", ".join(f"--rated-{kind}s" for kind in unchecked)
    kinds = " and ".join(f"{kind}s" for kind in unchecked)
    return f"{said}; the rated {kinds} NOT checked: the design gives none ({options})"


def electrical_rows(analysis: GaitAnalysis) -> list[tuple[str, str]]:
    """The motors' rows: the bus, energy, power, cost, each joint type's loads, the battery."""
    electrical, actuators = analysis.electrical, analysis.design.actuators
    if electrical is None or actuators is None:
        return []
    share = electrical.copper_loss_per_period / max(electrical.energy_per_period, 1e-300)
    rows = [
        (
            "motors",
            f"bus {electrical.supply:g} V, windings at {electrical.winding_temperature:g} °C",
        ),
        (
            "electrical energy per period",
            f"{electrical.energy_per_period:.4g} J (copper loss "
            f"{electrical.copper_loss_per_period:.4g} J, {100 * share:.0f} %)",
        ),
        ("average electrical power", f"{electrical.average_power:.4g} W"),
        ("electrical cost of transport", f"{electrical.cost_of_transport:.4f}"),
        ("energy per km", f"{electrical.energy_per_km:.4g} Wh/km"),
    ]
    for joint, actuator in zip(LEG_JOINTS, actuators.joints, strict=True):
        figures = electrical.per_joint[joint]
        rows.append(
            (
                f"{joint}: RMS torque, current, voltage",
                f"{figures.rms_torque:.2f} N·m (continuous {actuator.continuous_torque:g}), "
                f"peak {figures.peak_current:.3g} A, {figures.peak_voltage:.3g} V "
                f"(bus {electrical.supply:g})",
            )
        )
    if electrical.battery is not None:
        use = electrical.battery
        rows.append(
            (
                "battery",
                f"{use.capacity:.4g} Wh, {use.mass:.3g} kg, {100 * use.reserve:.0f} % kept in "
                f"reserve: runtime {use.runtime:.3g} h, range {use.range:.3g} km",
            )
        )
    return rows


def _rating(ratings: tuple[float, ...] | None, joint: int) -> float:
    """A joint type's rating; +inf (nothing is over it) where the design gives none."""
    return math.inf if ratings is None else ratings[joint]


def _rated(rating: float, safety_factor: float, unit: str) -> str:
    """``rated 150 N·m`` (``/ F = …`` with F ≠ 1), or that the rating is not given."""
    if math.isinf(rating):
        return "rating not given"
    return f"rated {rated_text(rating, safety_factor, unit)}"


def joint_rows(analysis: GaitAnalysis) -> list[tuple[str, str]]:
    """Each joint type's peak and RMS torque, peak speed and power, against rating / F."""
    metrics, design, factor = analysis.metrics, analysis.design, analysis.safety_factor
    rows = []
    for j, joint in enumerate(LEG_JOINTS):
        torque, speed = metrics.peak_torque[joint], metrics.peak_speed[joint]
        rated_torque = _rating(design.rated_torques, j)
        rated_speed = _rating(design.rated_speeds, j)
        rows.append(
            (
                f"{joint}: peak / RMS torque",
                f"{torque:.2f} / {metrics.rms_torque[joint]:.2f} N·m "
                f"({_rated(rated_torque, factor, 'N·m')})"
                + (", OVER RATING" if torque > rated_torque / factor else ""),
            )
        )
        rows.append(
            (
                f"{joint}: peak speed / power",
                f"{speed:.3f} rad/s ({_rated(rated_speed, factor, 'rad/s')}) / "
                f"{metrics.peak_power[joint]:.1f} W"
                + (", OVER RATING" if speed > rated_speed / factor else ""),
            )
        )
    return rows


def limit_rows(analysis: GaitAnalysis) -> list[tuple[str, str]]:
    """The max stride and max speed, when computed."""
    rows = []
    if analysis.max_stride is not None:
        stride = analysis.max_stride
        rows.append(("max stride", f"{stride.value:.4f} m, limited by {stride.limited_by}"))
    if analysis.max_stride is not None and not analysis.design.rated:
        rows.append(("max speed", NEEDS_RATING))
    if analysis.max_speed is not None:
        limit = analysis.max_speed
        at = (
            ""
            if math.isinf(limit.period)
            else f" (T = {limit.period:.4g} s, S = {limit.stride:.4g} m)"
        )
        rows.append(("max speed", f"{limit.value:.4f} m/s{at}, limited by {limit.limited_by}"))
    return rows


def rows(analysis: GaitAnalysis) -> list[tuple[str, str]]:
    """The text table's rows."""
    gait, metrics = analysis.gait, analysis.metrics
    rows = [
        (
            "gait",
            f"{gait.pattern} (β = {gait.duty_factor:.3g}), T = {gait.period:.4g} s, "
            f"S = {gait.stride:.4g} m, H = {gait.step_height:.4g} m, "
            f"ψ = {gait.heading:.4g} rad, {gait.samples} samples",
        ),
        ("ground", analysis.ground.describe(gait.heading)),
        ("body speed", f"{gait.speed:.4g} m/s"),
        ("total mass", f"{analysis.mass:.3f} kg (payload {analysis.payload.mass:g} kg)"),
    ]
    if analysis.safety_factor != 1:
        factor = analysis.safety_factor
        rows.append(
            ("motor safety factor", f"{factor:g}: peak torques and speeds within rating / F")
        )
    rows += joint_rows(analysis)
    rows += [
        ("positive work per period", f"{metrics.positive_work:.2f} J"),
        ("mechanical cost of transport", f"{metrics.cost_of_transport:.4f}"),
        *electrical_rows(analysis),
        ("min ZMP margin", f"{analysis.min_zmp_margin:.4f} m (on the ground's plane)"),
        ("friction needed", _friction_needed(analysis)),
        ("feasible", _feasible(analysis)),
        *limit_rows(analysis),
    ]
    rows += [("SLIDES", str(slip)) for slip in analysis.slips]
    rows += [("OVER RATING", str(over)) for over in analysis.over_rating]
    return rows
