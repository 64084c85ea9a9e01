"""``hexaleg simulate``: the planned gait walked in MuJoCo, and the tripod standing check."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from hexaleg._typing import Controller, choices
from hexaleg.cli.gait import add_gait_options, gait_from_args
from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.loads import add_payload_options, payload_from_args
from hexaleg.cli.options import UsageError, add_design_options, bounded_int, note
from hexaleg.cli.output import (
    check_outputs,
    lengths_title,
    print_json,
    print_table,
    report_files,
    summary_stream,
)
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.model import HexapodModel
from hexaleg.sim.result import SimulationResult
from hexaleg.sim.simulate import CYCLES_RANGE, DEFAULT_CYCLES, simulate_gait
from hexaleg.sim.video import VIDEO_SUFFIXES, check_video_path
from hexaleg.statics.ratings import rating_use

DESCRIPTION = (
    "Walk the design's planned gait in MuJoCo (pip install 'hexaleg[sim]'): hexaleg's URDF "
    "on a free body, foot spheres on a floor with friction, joint servos fed the gait's "
    "joint trajectory with its inverse-dynamics torques as feed-forward, from rest at the "
    "period's first pose. Measured over the periods after the first (SI units, radians): "
    "distance against the planned v·T per period, body tilt and lowest height, whether it "
    "fell, RMS joint tracking error, standing-foot slip, peak servo torques beside the "
    "plan's, each servo over its rated torque flagged (as in gait and loads). Then the "
    "robot stands 2 s on the first tripod (lf, rm, lr) with the other feet lifted 2 cm: "
    "each standing foot's vertical force beside the statics' (`loads --stance tripod`). "
    "A stride beyond the design's max stride is refused before simulating. With --urdf, "
    "your robot: its file's links, masses, inertias and joints in MuJoCo (its meshes left "
    "out: only the feet touch the floor, each a 5 mm sphere), walking the gait `gait --urdf` "
    "plans. --controller torque: a torque-controlled robot (the plan's torques, a low-gain "
    "PD, started at the plan's velocities) instead of stiff position servos; either "
    "reports the internal force the standing feet push on each other with. A simulation "
    "that diverges (MuJoCo's accelerations NaN or huge, a body through the ground) stops "
    "and says so in one line."
)

CONTROLLERS = {
    "servo": "servo: stiff position servos (the plan's torques fed forward), from rest",
    "torque": "torque: the plan's torques and a low-gain PD, from the plan's velocities",
}
"""What each controller is, in the table."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_gait_options(parser)
    add_payload_options(parser)
    low, high = CYCLES_RANGE
    parser.add_argument(
        "--cycles",
        type=bounded_int(low, high),
        default=DEFAULT_CYCLES,
        metavar="N",
        help=f"gait periods to walk, {low}..{high}; the first is not measured "
        f"(default {DEFAULT_CYCLES})",
    )
    parser.add_argument(
        "--controller",
        choices=choices(Controller),
        default="servo",
        help="how the joints follow the plan: stiff position 'servo's (default, from rest), "
        "or 'torque' control (the plan's torques and a low-gain PD)",
    )
    parser.add_argument(
        "--json", action="store_true", help="print one JSON object (SI units, radians)"
    )
    parser.add_argument(
        "--html",
        metavar="FILE",
        help="write the simulated motion as a 3-D animation (meshcat, static HTML)",
    )
    parser.add_argument(
        "--video",
        metavar="FILE",
        help=f"write the simulated motion as an animated image ({', '.join(VIDEO_SUFFIXES)}), "
        "rendered offscreen by MuJoCo (EGL or OSMesa; skipped with a note where neither works)",
    )


def run(args: argparse.Namespace) -> int:
    """Simulate; write the animation and video if asked; print a table or JSON."""
    inputs = inputs_from_args(args, size=True)  # sized tubes: their masses and shapes
    robot = inputs.robot
    model = robot.model
    gait = gait_from_args(args, inputs.gait)
    payload = payload_from_args(args)
    check_outputs({"--html": args.html, "--video": args.video})  # before simulating
    if args.video is not None:
        if not model.simulation_draws_links:
            raise UsageError(
                "--video with --urdf is not supported yet: the simulated file has no shapes "
                "but its feet (use --html, drawn with the file's visuals)"
            )
        check_video_path(args.video)
    result = simulate_gait(
        model.design,
        gait,
        payload,
        cycles=args.cycles,
        friction=args.friction,
        distribution=args.distribution,
        model=model,
        controller=args.controller,
    )
    written: list[Path] = []
    if args.html is not None:
        written.append(_animation(result, model, args.html))
    if args.video is not None:
        written += _video(result, args.video)
    report_files(written)
    summary = summary_stream(args.html, args.video)
    if args.json:
        print_json(robot.posture() | result.to_dict(), summary)
        return 0
    title = lengths_title(robot.titled("Simulated walk (MuJoCo)"), model.design.lengths)
    if result.diverged:  # nothing it measured holds: one line, where and why
        print(f"{title}: DIVERGED {result.diverged}; nothing it measured holds", file=summary)
        return 0
    print_table(title, rows(result, model.nominal_height), summary)
    return 0


def _animation(result: SimulationResult, model: HexapodModel, path: str) -> Path:
    """The simulated motion as a meshcat page, links coloured by measured |τ|/rated."""
    from hexaleg.output.viewer.gait import write_motion_html

    ratios = rating_use(result.frame_torques, result.design.rated_torques)
    return write_motion_html(model, result.frames, result.frame_rate, ratios, path)


def _video(result: SimulationResult, path: str) -> list[Path]:
    from hexaleg.sim.video import write_video

    outcome = write_video(result.sim_model(), result.frames, result.frame_rate, path)
    if outcome.path is None:
        note(
            f"--video skipped: no offscreen OpenGL works here (tried {'; '.join(outcome.tried)}); "
            "install EGL (libegl1, Mesa) or OSMesa (libosmesa6)"
        )
        return []
    return [outcome.path]


def rows(result: SimulationResult, nominal_height: float) -> list[tuple[str, str]]:
    """The text table's rows (``nominal_height``: the body's over the ground [m])."""
    metrics, gait, design, standing = result.metrics, result.gait, result.design, result.standing
    assert metrics is not None and standing is not None  # it did not diverge
    rows = [
        (
            "gait",
            f"{gait.pattern}, T = {gait.period:.4g} s, S = {gait.stride:.4g} m, "
            f"H = {gait.step_height:.4g} m, v = {gait.speed:.4g} m/s; {result.cycles} periods",
        ),
        ("controller", CONTROLLERS[result.controller]),
        ("payload", f"{result.payload.mass:g} kg; friction μ = {result.friction:g}"),
        (
            "distance, periods 2..",
            f"{metrics.distance:.4f} m of {metrics.planned_distance:.4f} m planned "
            f"({100 * metrics.distance_ratio:.1f} %)",
        ),
        (
            "max |roll|, |pitch|",
            f"{math.degrees(metrics.max_roll):.2f}°, {math.degrees(metrics.max_pitch):.2f}°",
        ),
        (
            "lowest body height",
            f"{metrics.min_height:.4f} m (nominal {nominal_height:.4f} m)",
        ),
        ("fell", "YES" if metrics.fell else "no"),
        ("RMS joint tracking error", f"{metrics.tracking_rms:.5f} rad"),
        ("standing-foot slip", f"{metrics.slip:.4f} m"),
        ("internal force, standing feet", f"{metrics.internal_force:.1f} N (planned 0)"),
    ]
    given = design.rated_torques
    for joint, rated in zip(LEG_JOINTS, given or (math.inf,) * 3, strict=True):
        rows.append(
            (
                f"{joint}: peak |τ| simulated / planned",
                f"{metrics.peak_torque[joint]:.2f} / {result.planned_peak_torque[joint]:.2f} "
                + (f"N·m (rated {rated:g})" if given else "N·m (rating not given)")
                + (", OVER RATING" if metrics.peak_torque[joint] > rated else ""),
            )
        )
    rows += [("OVER RATING", str(over)) for over in metrics.over_rating]
    for leg in standing.legs:
        simulated, statics = standing.foot_forces_z[leg], standing.statics_foot_forces_z[leg]
        rows.append(
            (
                f"standing on {', '.join(standing.legs)}: {leg} f_z",
                f"{simulated:.2f} N, statics {statics:.2f} N "
                f"({100 * (simulated - statics) / statics:+.2f} %)",
            )
        )
    return rows
