"""``hexaleg view``: a meshcat scene of the nominal stance and the 12 body extremes."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from typing import Any

from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import add_design_options, add_stance_option, bounded_int, note
from hexaleg.cli.output import check_outputs, report_files
from hexaleg.evaluation.sizing import sized_for
from hexaleg.exceptions import ParameterError
from hexaleg.gait.analysis import analyze_gait
from hexaleg.gait.spec import Gait
from hexaleg.gait.walkable import require_walkable
from hexaleg.output.viewer.gait import build_gait_scene, write_gait_html
from hexaleg.output.viewer.legend import GAIT_LEGEND, STATICS_LEGEND, Legend
from hexaleg.output.viewer.scene import build_scene, write_static_html
from hexaleg.output.viewer.server import (
    LoopbackServer,
    client,
    is_loopback,
    serve_until_stopped,
)
from hexaleg.robot.imported_model import has_masses
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.axis_locked import axis_locked_flexibility
from hexaleg.statics.loads import loads_at_extremes

DESCRIPTION = (
    "Serve a meshcat scene of the hexapod: ground, footholds, the nominal stance and the "
    "12 axis-locked extreme poses (scene tree: hexaleg/extremes/x+ ... yaw-, limiting "
    "link in red), with an animation of each from nominal to the extreme and back. "
    "The web page binds 127.0.0.1 unless --host says otherwise (the socket that changes "
    "the scene stays on 127.0.0.1); Ctrl-C stops it. --html writes a self-contained "
    "snapshot instead of serving."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_stance_option(parser)
    parser.add_argument(
        "--host",
        default="127.0.0.1",
        help="interface the web page binds (default 127.0.0.1; 0.0.0.0 or :: for every one)",
    )
    parser.add_argument(
        "--port", type=bounded_int(1, 65535), help="web port (default: the first free from 7000)"
    )
    parser.add_argument("--html", metavar="FILE", help="write a static HTML snapshot and exit")
    parser.add_argument("--workspace", metavar="LEG", help="also draw this leg's workspace cloud")
    parser.add_argument(
        "--gait",
        action="store_true",
        help="animate one period of the --design file's [gait] (else the default tripod gait) "
        "instead (hexaleg gait --html for other gaits), legs coloured by |τ|/rated",
    )


def run(args: argparse.Namespace) -> int:
    """Write the static page, or serve the scene until Ctrl-C or SIGTERM."""
    inputs = inputs_from_args(args, sizing=sized_for)  # sized tubes are drawn
    check_outputs({"--html": args.html})
    model = inputs.robot.model
    missing = model.missing_meshes_note("not drawn")
    if missing is not None:
        note(missing)
    if args.workspace is not None and args.workspace not in model.leg_names:
        raise ParameterError(
            "--workspace", args.workspace, f"legs are {', '.join(model.leg_names)}"
        )
    if args.gait:
        return _view_gait(model, inputs.gait, args)
    result = axis_locked_flexibility(model.design, args.stance, model)
    loads = loads_at_extremes(model, result) if has_masses(model) else None  # else uncoloured
    if args.html is not None:
        report_files([write_static_html(model, result, args.html, args.workspace, loads)])
        return 0
    return _serve(
        args,
        lambda viewer: build_scene(viewer, model, result, args.workspace, loads=loads),
        STATICS_LEGEND,
    )


def _view_gait(model: HexapodModel, gait: Gait, args: argparse.Namespace) -> int:
    """``--gait``: the design file's gait's animation (else the default's), written or served."""
    analysis = analyze_gait(model.design, gait, model=model, limits=False)
    require_walkable(analysis, model)  # what ``hexaleg gait`` refuses: one line, nothing written
    if args.html is not None:
        report_files([write_gait_html(model, analysis, args.html)])
        return 0
    return _serve(args, lambda viewer: build_gait_scene(viewer, model, analysis), GAIT_LEGEND)


def _serve(args: argparse.Namespace, build: Callable[[Any], None], legend: Legend) -> int:
    """Serve the scene ``build`` draws, its legend beside it, until Ctrl-C or SIGTERM."""
    if not is_loopback(args.host):
        port = "chosen below" if args.port is None else args.port
        note(
            f"--host {args.host} serves the scene's web page (port {port}) beyond this "
            "machine, to anyone who can reach it, without authentication: they can watch "
            "the robot and its extremes, not change them (the command socket stays on "
            "127.0.0.1)"
        )
    server = LoopbackServer(args.host, args.port, legend)
    try:
        build(client(server))
    except BaseException:
        server.stop()
        raise
    print(f"hexaleg viewer: open {server.web_url}", flush=True)
    print("serving until Ctrl-C", file=sys.stderr, flush=True)
    serve_until_stopped(server)
    print("hexaleg viewer: stopped", file=sys.stderr)
    return 0
