"""``hexaleg loads``: foot forces, joint torques, stability, slopes and payload capacity."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import TYPE_CHECKING

from hexaleg._io import check_output_folder
from hexaleg._typing import Distribution, choices
from hexaleg.cli.options import (
    add_design_options,
    add_mode_option,
    add_output_options,
    add_stance_option,
    design_from_args,
)
from hexaleg.cli.output import lengths_title, print_json, print_table, report_files
from hexaleg.limits import LEG_JOINTS
from hexaleg.statics.forces import DEFAULT_FRICTION, Payload

if TYPE_CHECKING:
    from hexaleg.statics.loads import LoadsAnalysis

DESCRIPTION = (
    "Statics of the design (SI units: N, N·m, kg, m, rad): the foot forces balancing "
    "gravity and the joint torques holding the nominal stance and each of the 12 body "
    "extremes, the stability margin, the steepest slope per heading (tip or slide) and "
    "the largest payload the nominal stance holds within the rated torques."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_payload_options(parser)
    add_stance_option(parser)
    add_mode_option(parser)
    add_output_options(parser)


def add_payload_options(parser: argparse.ArgumentParser) -> None:
    """``--payload``, ``--payload-at``, ``--friction`` and ``--distribution`` (loads, gait)."""
    parser.add_argument(
        "--payload", type=float, default=0.0, metavar="KG", help="payload mass [kg] (default 0)"
    )
    parser.add_argument(
        "--payload-at",
        type=float,
        nargs=3,
        metavar=("X", "Y", "Z"),
        help="payload position in the body frame [m] (default: the centre of the top face)",
    )
    parser.add_argument(
        "--friction",
        type=float,
        default=DEFAULT_FRICTION,
        metavar="MU",
        help=f"friction coefficient between feet and ground [-] (default {DEFAULT_FRICTION})",
    )
    parser.add_argument(
        "--distribution",
        choices=choices(Distribution),
        default="min-norm",
        help="how the feet share the load: least forces (default) or least torque/rating",
    )


def payload_from_args(args: argparse.Namespace) -> Payload:
    """The payload ``--payload`` and ``--payload-at`` describe (validated)."""
    return Payload(args.payload, None if args.payload_at is None else tuple(args.payload_at))


def run(args: argparse.Namespace) -> int:
    """Compute the statics; print a table or JSON, and write the figure if asked."""
    from hexaleg.output.figures import loads_figure, save
    from hexaleg.statics.loads import analyze_loads

    design = design_from_args(args)
    if args.plot is not None:
        check_output_folder(args.plot)  # before computing
    payload = payload_from_args(args)
    analysis = analyze_loads(
        design, payload, args.friction, args.stance, args.distribution, args.mode
    )
    if args.plot is not None:
        report_files([save(loads_figure(analysis), Path(args.plot) / "loads.png")])
    if args.json:
        print_json(analysis.to_dict())
        return 0
    print_table(lengths_title("Statics", design.lengths), _rows(analysis))
    return 0


def _rows(analysis: LoadsAnalysis) -> list[tuple[str, str]]:
    rated = dict(zip(LEG_JOINTS, analysis.design.rated_torques, strict=True))
    nominal = analysis.nominal.peak_torques()
    rows = [
        ("total mass", f"{analysis.nominal.mass:.3f} kg (payload {analysis.payload.mass:g} kg)"),
        ("stability margin, nominal", f"{analysis.nominal.stability_margin:.4f} m"),
    ]
    for joint in LEG_JOINTS:
        rows.append(
            (
                f"peak |τ| {joint}: nominal / extremes",
                f"{nominal[joint]:.2f} / {analysis.peak_torques[joint]:.2f} N·m "
                f"(rated {rated[joint]:g} N·m)"
                + (", OVER RATING" if analysis.peak_torques[joint] > rated[joint] else ""),
            )
        )
    for slope in analysis.slopes:
        rows.append(
            (
                f"max slope, uphill at {math.degrees(slope.heading):+.0f}°",
                f"{slope.max_slope:.4f} rad ({math.degrees(slope.max_slope):.1f}°), "
                f"limited by {slope.limited_by}",
            )
        )
    capacity = analysis.capacity
    rows.append(("payload capacity", f"{capacity.mass:.2f} kg, limited by {capacity.limited_by}"))
    rows += [("OVER RATING", str(over)) for over in analysis.over_rating]
    return rows
