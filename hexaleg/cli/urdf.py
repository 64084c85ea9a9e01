"""``hexaleg urdf``: the hexapod's URDF for a design."""

from __future__ import annotations

import argparse

from hexaleg._io import STDOUT, check_output_file
from hexaleg.cli.options import add_design_options, design_from_args
from hexaleg.cli.output import report_files
from hexaleg.robot.urdf import write_urdf

DESCRIPTION = (
    "Render the hexapod URDF from the Xacro templates for the given design. Joint "
    "values of the URDF are the paper's θ1, θ2, θ3 [rad]; lengths are in metres."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    parser.add_argument(
        "-o",
        "--output",
        metavar="FILE",
        help="write here instead of stdout (a file is replaced atomically, keeping its mode)",
    )


def run(args: argparse.Namespace) -> int:
    """Write the URDF to stdout or to the file given (see :func:`hexaleg._io.write_bytes`)."""
    design = design_from_args(args)
    target = check_output_file(STDOUT if args.output in (None, "-") else args.output)
    written = write_urdf(design, target)
    if args.output not in (None, "-"):
        report_files([written])
    return 0
