"""``hexaleg loads``: foot forces, joint torques, stability, slopes and payload capacity."""

from __future__ import annotations

import argparse
import math

from hexaleg.cli.best_posture import add_best_posture_option, posing
from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import (
    add_design_options,
    add_mode_option,
    add_output_options,
    add_stance_option,
)
from hexaleg.cli.output import check_outputs, lengths_title, print_json, print_table, write_plots
from hexaleg.cli.payload_options import (
    add_payload_options,
    add_safety_factor_option,
    payload_from_args,
    rated_text,
    safety_factor_from_args,
)
from hexaleg.cli.structure_rows import structure_rows
from hexaleg.evaluation.metrics import METRICS
from hexaleg.evaluation.requirement_specs import SLOPE
from hexaleg.evaluation.sizing import sized_for
from hexaleg.gait.capacity import WalkingCapacity, walking_payload_capacity
from hexaleg.gait.spec import Gait
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.figures import loads_figure, save
from hexaleg.ratings import NEEDS_RATING
from hexaleg.statics.loads import LoadsAnalysis, analyze_loads

DESCRIPTION = (
    "Statics of the design (SI units: N, N·m, kg, m, rad): the foot forces balancing "
    "gravity and the joint torques holding the nominal stance and each of the 12 body "
    "extremes, the stability margin, the steepest slope per heading (tip or slide) and "
    "the largest payload the nominal stance holds within the rated torques. With --urdf, "
    "your robot: the file's masses, feet, ratings and each leg's nominal posture (the "
    "extremes within the file's limits, axis-locked or free-coupled, the walking capacity as "
    "`gait --urdf` walks it). With a [structure] table, each leg tube's axial force, "
    "bending and torsion at its proximal joint, its von Mises stress against the material's "
    "strength over the safety factor, and each foot's deflection, in every case and on the "
    "[requirements] slope (size = true: the lightest tubes that hold, chosen first)."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_payload_options(parser)
    add_safety_factor_option(parser)
    add_best_posture_option(parser)
    add_stance_option(parser)
    add_mode_option(parser)
    add_output_options(parser)


def run(args: argparse.Namespace) -> int:
    """Compute the statics; print a table or JSON, and write the figure if asked."""
    inputs = inputs_from_args(args, posing=posing(args), sizing=sized_for)
    robot, requirements, sized = inputs.robot, inputs.written, inputs.sized
    check_outputs({}, {"--plot": args.plot})  # before computing
    payload, factor = payload_from_args(args), safety_factor_from_args(args, requirements)
    model = robot.model
    analysis = analyze_loads(
        model.design,
        payload,
        args.friction,
        args.stance,
        args.distribution,
        args.mode,
        model=model,
        slope=requirements.required(SLOPE) or 0.0,
        safety_factor=factor,
    )
    gait = inputs.gait
    walking = walking_payload_capacity(model, gait, payload.position, safety_factor=factor)
    if args.plot is not None:
        write_plots(args.plot, lambda out: [save(loads_figure(analysis), out / "loads.png")])
    if args.json:
        walked = None if walking is None else walking.to_dict()  # None: it needs a rating
        out = analysis.to_dict() | {METRICS.walking_payload_capacity.name: walked}
        if sized is not None:
            out["structure"]["sizing"] = sized.to_dict()
        print_json(robot.posture() | out)
        return 0
    rows = _rows(analysis) + structure_rows(analysis.structure, sized)
    at = rows.index(("payload capacity", _capacity(analysis))) + 1
    own = gait == inputs.default_gait  # no [gait]: the robot's own default gait
    rows.insert(at, ("walking payload capacity", _walking(walking, gait, own)))
    print_table(lengths_title(robot.titled("Statics"), model.design.lengths), rows)
    return 0


TIPS_OVER = "TIPS OVER on level ground"
"""What the table says of a robot whose nominal stability margin is not positive."""


def _rows(analysis: LoadsAnalysis) -> list[tuple[str, str]]:
    given = analysis.design.rated_torques
    rated = dict(zip(LEG_JOINTS, given or (math.inf,) * 3, strict=True))
    nominal = analysis.nominal.peak_torques()
    margin = f"{analysis.nominal.stability_margin:.4f} m"
    if analysis.tips_over:
        margin += (
            f": {TIPS_OVER} (centre of mass outside the support polygon; "
            "the torques below would need the feet fastened to the ground)"
        )
    rows = [
        ("total mass", f"{analysis.nominal.mass:.3f} kg (payload {analysis.payload.mass:g} kg)"),
        ("stability margin, nominal", margin),
    ]
    if analysis.safety_factor != 1:
        rows.append(
            ("motor safety factor", f"{analysis.safety_factor:g}: torques within rating / F")
        )
    for joint in LEG_JOINTS:
        held = rated[joint] / analysis.safety_factor
        rows.append(
            (
                f"peak |τ| {joint}: nominal / extremes",
                f"{nominal[joint]:.2f} / {analysis.peak_torques[joint]:.2f} N·m "
                + (
                    f"(rated {rated_text(rated[joint], analysis.safety_factor, 'N·m')})"
                    if given
                    else "(rating not given)"
                )
                + (", OVER RATING" if analysis.peak_torques[joint] > held else ""),
            )
        )
    for slope in analysis.slopes:
        limit = (
            "TIPS OVER on level ground" if analysis.tips_over else f"limited by {slope.limited_by}"
        )
        rows.append(
            (
                f"max slope, uphill at {math.degrees(slope.heading):+.0f}°",
                f"{slope.max_slope:.4f} rad ({math.degrees(slope.max_slope):.1f}°), {limit}",
            )
        )
    rows.append(("payload capacity", _capacity(analysis)))
    rows += [("OVER RATING", str(over)) for over in analysis.over_rating]
    return rows


def _walking(walking: WalkingCapacity | None, gait: Gait, default: bool) -> str:
    if walking is None:
        return NEEDS_RATING
    which = "default" if default else "design's"
    how = f"walking the {which} {gait.pattern} gait at {gait.speed:g} m/s"
    if not walking.walks:
        return f"none: cannot walk the {which} {gait.pattern} gait ({walking.limited_by})"
    return f"{walking.mass:.2f} kg {how}, limited by {walking.limited_by}"


def _capacity(analysis: LoadsAnalysis) -> str:
    capacity = analysis.capacity
    if capacity is None:
        return NEEDS_RATING
    text = f"{capacity.mass:.2f} kg, limited by {capacity.limited_by}"
    if analysis.tips_over:
        text += f"; the {analysis.payload.mass:g} kg payload tips the robot over"
    return text
