"""``hexaleg urdf``: the hexapod's URDF for a design."""

from __future__ import annotations

import argparse

from hexaleg.cli.options import add_design_options, design_from_args
from hexaleg.cli.output import check_outputs, report_files
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
        help="write here instead of stdout (a file is replaced atomically, keeping its mode; "
        "- is stdout)",
    )


def run(args: argparse.Namespace) -> int:
    """Write the URDF to stdout or to the file given (see :func:`hexaleg._io.write_bytes`)."""
    design = design_from_args(args)
    target = "-" if args.output is None else args.output
    check_outputs({"--output": target})
    report_files([write_urdf(design, target)])
    return 0
