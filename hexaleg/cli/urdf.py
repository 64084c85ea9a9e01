"""``hexaleg urdf``: the hexapod's URDF for a design."""

from __future__ import annotations

import argparse
import sys

from hexaleg.cli.options import add_design_options, design_from_args
from hexaleg.cli.output import report_files
from hexaleg.robot.urdf import render_hexapod, write_urdf

DESCRIPTION = (
    "Render the hexapod URDF from the Xacro templates for the given design. Joint "
    "values of the URDF are the paper's θ1, θ2, θ3 [rad]; lengths are in metres."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    parser.add_argument(
        "-o", "--output", metavar="FILE", help="write here (atomically) instead of stdout"
    )


def run(args: argparse.Namespace) -> int:
    """Write the URDF to stdout or, atomically, to the file given."""
    design = design_from_args(args)
    if args.output is None or args.output == "-":
        sys.stdout.write(render_hexapod(design))
    else:
        report_files([write_urdf(design, args.output)])
    return 0
