"""``hexaleg urdf``: the hexapod's URDF for a design."""

from __future__ import annotations

import argparse

from hexaleg.cli.options import add_design_options, inputs_from_args
from hexaleg.cli.output import check_outputs, report_files
from hexaleg.cli.robot_options import add_robot_options, refuse_unsupported, robot_from_args
from hexaleg.cli.structure_options import size_if_asked
from hexaleg.robot.urdf import write_urdf

DESCRIPTION = (
    "Render the hexapod URDF from the Xacro templates for the given design. Joint "
    "values of the URDF are the paper's θ1, θ2, θ3 [rad]; lengths are in metres. With "
    "--urdf, your robot's own URDF (its joints, zeros, signs, masses and meshes) with a link "
    "<leg>_foot at each foot point hexaleg found; --l1 --l2 --l3 (every leg) or the design "
    "file's [robot.segments] (per leg) lengthen or shorten its segments along their own lines, "
    "drawn then as cylinders in place of their meshes."
)

ROBOT_OPTIONS = True


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
    add_robot_options(parser)


def run(args: argparse.Namespace) -> int:
    """Write the URDF to stdout or to the file given (see :func:`hexaleg._io.write_bytes`)."""
    design, requirements = inputs_from_args(args)
    target = "-" if args.output is None else args.output
    check_outputs({"--output": target})
    robot = robot_from_args(args)
    design = size_if_asked(design, requirements, robot is not None)[0]  # refused on a robot
    if robot is None:
        written = write_urdf(design, target)
    else:
        from hexaleg._io import write_text
        from hexaleg.robot.imported import urdf_with_feet

        refuse_unsupported(args)
        text = urdf_with_feet(robot)
        if robot.changes:
            from hexaleg.cli.options import note
            from hexaleg.robot.resize import changes_note

            note(changes_note(robot.changes))
        written = write_text(target, text)
    report_files([written])
    return 0
