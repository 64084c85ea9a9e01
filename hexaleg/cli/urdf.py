"""``hexaleg urdf``: the hexapod's URDF for a design."""

from __future__ import annotations

import argparse

from hexaleg._io import write_text
from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import add_design_options, note
from hexaleg.cli.output import check_outputs, refuse_inputs_as_outputs, report_files

DESCRIPTION = (
    "Render the hexapod URDF from the Xacro templates for the given design. Joint "
    "values of the URDF are the paper's θ1, θ2, θ3 [rad]; lengths are in metres. With "
    "--urdf, your robot's own URDF (its joints, zeros, signs, masses and meshes) with a link "
    "<leg>_foot at each foot point hexaleg found; --l1 --l2 --l3 (every leg) or the design "
    "file's [robot.segments] (per leg) lengthen or shorten its segments along their own lines, "
    "drawn then as cylinders in place of their meshes."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    parser.add_argument(
        "-o",
        "--output",
        metavar="FILE",
        help="write here instead of stdout (a file is replaced atomically, keeping its mode; "
        "- is stdout)",
    )


def run(args: argparse.Namespace) -> int:
    """Write the URDF to stdout or to the file given (see :func:`hexaleg._io.write_bytes`)."""
    robot = inputs_from_args(args, size=True).robot  # sized tubes: their links
    target = "-" if args.output is None else args.output
    check_outputs({"--output": target})
    named = f"--urdf {args.urdf}" if args.urdf else "the --design file's [robot] urdf"
    refuse_inputs_as_outputs(  # the robot file's path: None for hexaleg's template
        {"-o": target},
        {
            "robot file": (named, robot.source.path),
            "design file": (f"--design {args.design}", args.design),
        },
    )
    text = robot.urdf()
    for line in robot.notes:
        note(line)
    report_files([write_text(target, text)])
    return 0
