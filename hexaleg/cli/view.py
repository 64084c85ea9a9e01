"""``hexaleg view``: a meshcat scene of the nominal stance and the 12 body extremes."""

from __future__ import annotations

import argparse
import ipaddress
import sys

from hexaleg.cli.options import (
    add_design_options,
    add_stance_option,
    bounded_int,
    design_from_args,
    note,
)
from hexaleg.cli.output import report_files
from hexaleg.exceptions import ParameterError
from hexaleg.output.viewer import (
    LoopbackServer,
    build_scene,
    client,
    serve_until_stopped,
    write_static_html,
)
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.axis_locked import axis_locked_flexibility
from hexaleg.statics.loads import loads_at_extremes

DESCRIPTION = (
    "Serve a meshcat scene of the hexapod: ground, footholds, the nominal stance and the "
    "12 axis-locked extreme poses (scene tree: hexaleg/extremes/x+ ... yaw-, limiting "
    "link in red), with an animation of each from nominal to the extreme and back. "
    "Binds 127.0.0.1 unless --host says otherwise; Ctrl-C stops it. --html writes a "
    "self-contained snapshot instead of serving."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_stance_option(parser)
    parser.add_argument("--host", default="127.0.0.1", help="interface to bind (default 127.0.0.1)")
    parser.add_argument(
        "--port", type=bounded_int(1, 65535), help="web port (default: the first free from 7000)"
    )
    parser.add_argument("--html", metavar="FILE", help="write a static HTML snapshot and exit")
    parser.add_argument("--workspace", metavar="LEG", help="also draw this leg's workspace cloud")


def run(args: argparse.Namespace) -> int:
    """Write the static page, or serve the scene until Ctrl-C or SIGTERM."""
    design = design_from_args(args)
    model = HexapodModel(design)
    if args.workspace is not None and args.workspace not in model.leg_names:
        raise ParameterError(
            "--workspace", args.workspace, f"legs are {', '.join(model.leg_names)}"
        )
    result = axis_locked_flexibility(design, args.stance, model)
    loads = loads_at_extremes(model, result)
    if args.html is not None:
        report_files([write_static_html(model, result, args.html, args.workspace, loads)])
        return 0
    if not is_loopback(args.host):
        note(
            f"--host {args.host} serves the scene beyond this machine, to anyone who can "
            "reach it, without authentication"
        )
    server = LoopbackServer(args.host, args.port)
    try:
        build_scene(client(server), model, result, args.workspace, loads=loads)
    except BaseException:
        server.stop()
        raise
    print(f"hexaleg viewer: open {server.web_url}", flush=True)
    print("serving until Ctrl-C", file=sys.stderr, flush=True)
    serve_until_stopped(server)
    print("hexaleg viewer: stopped", file=sys.stderr)
    return 0


def is_loopback(host: str) -> bool:
    """Whether ``host`` names this machine only (127.0.0.0/8, ::1 or localhost)."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False
