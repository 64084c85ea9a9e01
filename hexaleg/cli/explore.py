"""``hexaleg explore``: a live design explorer, served on loopback until Ctrl-C."""

from __future__ import annotations

import argparse
import signal
import sys
from pathlib import Path

from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import add_design_options, bounded_int, note
from hexaleg.exceptions import HexalegError
from hexaleg.output.viewer.server import browser_url, is_loopback

DESCRIPTION = (
    "Serve a page where every slider (segment lengths, posture, body size, payload, gait "
    "speed and step height) re-measures the design: FB, workspace, w_A, standing and "
    "walking payload, torques against the ratings, max speed and what binds each, the "
    "design file's requirements passed or failed, the design placed on the study's cloud, "
    "the nominal stance drawn. 'save design' writes the design file. The page binds "
    "127.0.0.1 unless --host says otherwise; Ctrl-C stops it. With --urdf (or a design "
    "file's [robot]), your robot: its segments slide along their own lines, its body and "
    "ratings stay the file's."
)

DEFAULT_SAVE = "design.toml"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    parser.add_argument(
        "--host",
        default="127.0.0.1",
        help="interface the page binds (default 127.0.0.1; another one serves the design "
        "to anyone who can reach it, and is warned about)",
    )
    parser.add_argument(
        "--port",
        type=bounded_int(0, 65535),
        default=0,
        help="port (default 0: the system picks a free one)",
    )
    parser.add_argument(
        "--save",
        metavar="FILE",
        help=f"the .toml file 'save design' writes (default: the --design file if it is "
        f".toml, else {DEFAULT_SAVE}, which is replaced only if this explorer wrote it)",
    )
    parser.add_argument(
        "--force",
        action="store_true",
        help=f"let 'save design' replace a {DEFAULT_SAVE} it did not write (without --save "
        "or a .toml --design)",
    )


def run(args: argparse.Namespace) -> int:
    """Serve the explorer until Ctrl-C or SIGTERM."""
    from hexaleg.explore.server import ExplorerServer
    from hexaleg.explore.session import Session

    inputs = inputs_from_args(args)
    save_to, named = _save_target(args)
    if not is_loopback(args.host):
        note(
            f"--host {args.host} serves the explorer beyond this machine, to anyone who can "
            "reach it, without authentication: they can measure designs and save the design file"
        )
    session = Session.start(inputs.robot, inputs.requirements, save_to, replace=named or args.force)
    try:
        server = ExplorerServer(session, args.host, args.port)
    except OSError as err:
        raise HexalegError(f"cannot serve on {args.host}:{args.port}: {err.strerror}") from None
    for signum in (signal.SIGINT, signal.SIGTERM):  # Ctrl-C or kill: stop cleanly
        signal.signal(signum, signal.default_int_handler)
    try:  # from the URL on: a signal even before serving begins stops it cleanly
        print(f"hexaleg explore: open {browser_url(args.host, server.port, '/')}", flush=True)
        print("serving until Ctrl-C", file=sys.stderr, flush=True)
        server.serve_forever(poll_interval=0.2)
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
        session.jobs.stop()
    print("hexaleg explore: stopped", file=sys.stderr)
    return 0


def _save_target(args: argparse.Namespace) -> tuple[Path, bool]:
    """Where 'save design' writes, and whether the user named that file.

    --save, else a .toml --design file (both named), else design.toml (not named).
    """
    if args.save is not None:
        return Path(args.save), True
    if args.design is not None and Path(args.design).suffix.lower() == ".toml":
        return Path(args.design), True
    return Path(DEFAULT_SAVE), False
