"""``hexaleg explore``: a live design explorer, served on loopback until Ctrl-C."""

from __future__ import annotations

import argparse
import signal
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from hexaleg.cli.options import (
    add_design_options,
    bounded_int,
    inputs_from_args,
    note,
    walked_by,
)
from hexaleg.cli.robot_options import add_robot_options, robot_model, robot_table
from hexaleg.exceptions import HexalegError
from hexaleg.leg_geometry import SEGMENT_NAMES
from hexaleg.output.viewer.server import browser_url, is_loopback

if TYPE_CHECKING:
    from hexaleg.design import HexapodDesign
    from hexaleg.explore.robot import ExploredRobot

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

ROBOT_OPTIONS = True
"""It runs on an imported robot (``--urdf``)."""

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
        f".toml, else {DEFAULT_SAVE})",
    )
    add_robot_options(parser)


def run(args: argparse.Namespace) -> int:
    """Serve the explorer until Ctrl-C or SIGTERM."""
    from hexaleg.explore.server import ExplorerServer
    from hexaleg.explore.session import Session

    design, requirements = inputs_from_args(args)
    save_to = _save_target(args)
    robot = _explored_robot(args, design)
    if robot is not None:
        design = robot.model.design
        requirements = walked_by(args, requirements, robot.model)  # its own default gait
    if not is_loopback(args.host):
        note(
            f"--host {args.host} serves the explorer beyond this machine, to anyone who can "
            "reach it, without authentication: they can measure designs and save the design file"
        )
    session = Session.start(design, requirements, save_to, robot)
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


def _explored_robot(args: argparse.Namespace, design: HexapodDesign) -> ExploredRobot | None:
    """The imported robot of ``--urdf`` (or the ``--design`` file's ``[robot]``), or ``None``."""
    from hexaleg.explore.robot import ExploredRobot
    from hexaleg.robot.imported_model import robot_mass

    model = robot_model(args, design)
    if model is None:
        return None
    robot_mass(model)  # its payloads and torques need the file's masses: refused before serving
    lengths = dict(zip(SEGMENT_NAMES, model.robot.legs[0].reading.geometry.lengths, strict=True))
    for change in model.robot.changes:  # back to the file's: what the saved file's l* say
        if change.leg == model.robot.legs[0].name:
            lengths[change.segment] = change.file_length
    l1, l2, l3 = (lengths[name] for name in SEGMENT_NAMES)
    return ExploredRobot(model, robot_table(args, None, model.robot), (l1, l2, l3))


def _save_target(args: argparse.Namespace) -> Path:
    """Where 'save design' writes: --save, else a .toml --design file, else design.toml."""
    if args.save is not None:
        return Path(args.save)
    if args.design is not None and Path(args.design).suffix.lower() == ".toml":
        return Path(args.design)
    return Path(DEFAULT_SAVE)
