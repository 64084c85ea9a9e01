"""``hexaleg design``: start a design file, and show the design a file and options resolve to."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from hexaleg._io import check_output_file, write_text
from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import UsageError, add_design_options, add_robot_options
from hexaleg.cli.output import print_json, print_table, report_files
from hexaleg.cli.structure_options import structure_rows, tube_rows
from hexaleg.design import HexapodDesign
from hexaleg.design_text import structure_example
from hexaleg.evaluation.requirements import Requirements
from hexaleg.evaluation.requirements_table import example_table
from hexaleg.gait.spec import Gait
from hexaleg.ratings import ratings_text
from hexaleg.robot.robot import Robot

INIT_DESCRIPTION = (
    "Write FILE: every design field with its unit in a comment, at the defaults or at "
    "the values the options give (say --layout hexagon --body-radius 0.35), and an example "
    "[requirements] table for decide and report and a [structure] table of the legs' tubes, "
    "commented out. With --urdf (or a --design file's [robot]), the robot file's design and "
    "its [robot] table, as design import writes."
)

DESCRIPTION = (
    "Keep your robot in a design file: `design init FILE` writes a commented TOML file "
    "(the defaults, or the design the options describe); `design show` prints the design "
    "a --design file and options resolve to, with its derived values."
)

IMPORT_DESCRIPTION = (
    "Read your hexapod's URDF or Xacro FILE (six yaw-pitch-pitch legs) and write a design "
    "file: the segments, mounts, body mass and ratings hexaleg read, and a [robot] table "
    "that names FILE and records each leg (joints, dimensions, offsets, foot, limits), to "
    "edit and version. Every command takes it with --design."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``init``, ``show`` and ``import`` actions and their options."""
    actions = parser.add_subparsers(dest="action", metavar="ACTION", parser_class=type(parser))
    actions.required = True
    init = actions.add_parser(
        "init", help="write a commented TOML design file", description=INIT_DESCRIPTION
    )
    init.add_argument("file", metavar="FILE", help="the .toml file to write")
    init.add_argument("--force", action="store_true", help="overwrite FILE if it exists")
    add_design_options(init)
    show = actions.add_parser(
        "show",
        help="print the resolved design and its derived values",
        description="Print the design (defaults, --design file, then options) with its leg "
        "length, nominal height, mass and leg mounts, and the file's [requirements] if it has "
        "them. With --urdf, what the robot file says: its legs as read, its mass (Pinocchio's "
        "total of its links), its standing height and footholds.",
    )
    add_design_options(show)
    show.add_argument("--json", action="store_true", help="print one JSON object")
    imported = actions.add_parser(
        "import",
        help="read a robot's URDF or Xacro into a design file",
        description=IMPORT_DESCRIPTION,
    )
    add_robot_options(imported, required=True)
    imported.add_argument(
        "-o", "--output", required=True, metavar="FILE", help="the .toml to write"
    )
    imported.add_argument("--force", action="store_true", help="overwrite FILE if it exists")


def run(args: argparse.Namespace) -> int:
    """Write, import or show the design."""
    if args.action == "import":
        path = _target(args.output, "design import -o", args.force)
        report_files([write_text(path, inputs_from_args(args).robot.design_text(path))])
        return 0
    inputs = inputs_from_args(args, size=args.action == "show")
    requirements, sized = inputs.written, inputs.sized
    gait = inputs.gait if inputs.gait_given and inputs.gait != inputs.default_gait else None
    if args.action == "init":
        return _init(args.file, inputs.robot, args.force, gait)
    out = inputs.robot.record()
    if sized is not None:
        out["derived"]["sizing"] = sized.to_dict() | {"check": sized.check.to_dict()}
    if args.json:
        if requirements.given:
            out["requirements"] = requirements.to_dict()
        if gait is not None:
            out["gait"] = gait.to_dict()
        print_json(out)
        return 0
    design = inputs.design
    show(design, out)
    if design.structure is not None:
        rows = (
            tube_rows(design.structure, design.lengths)
            if sized is None
            else structure_rows(sized.check, sized)
        )
        print_table("Structure (the file's [structure] table)", rows)
    if requirements.given:
        show_requirements(requirements)
    if gait is not None:
        print_table("Gait (the file's [gait] table)", gait_rows(gait))
    return 0


def _target(file: str, what: str, force: bool) -> Path:
    """The .toml design file to write, checked: as typed, not there unless ``force``."""
    path = check_output_file(file)  # as typed: an empty path is refused, not read as "."
    if path.suffix.lower() != ".toml":
        raise UsageError(f"{what} {path}: the file must end in .toml")
    if path.exists() and not force:
        raise UsageError(f"{what} {path}: the file exists (pass --force to overwrite it)")
    return path


def _init(file: str, robot: Robot, force: bool, gait: Gait | None) -> int:
    """Write the robot's design file, its gait if given, and the commented examples.

    The ``[structure]`` example where the robot's links are its design's and it has none.
    """
    path = _target(file, "design init", force)
    walked = "" if gait is None else "\n" + gait.to_toml()
    tubes = robot.design_links and robot.design.structure is None
    structure = "\n" + structure_example() if tubes else ""
    text = robot.design_text(path) + walked + structure + "\n" + example_table()
    report_files([write_text(path, text)])
    return 0


def show(design: HexapodDesign, record: dict[str, Any]) -> None:
    """The robot's record (``design show --json``) as text: design, derived values, legs."""
    derived = record["derived"]
    total, body = derived["total_mass"], derived["body_mass"]
    mass = (
        f"{total:.4g} kg (body {body:.4g} kg{_drive(design)})"
        if total > 0
        else "none: the file gives no masses (kinematics only)"
    )
    print_table(
        f"Design ({derived['body']})",
        [
            ("segments l1, l2, l3", f"{design.l1:.4g}, {design.l2:.4g}, {design.l3:.4g} m"),
            ("leg length", f"{derived['leg_length']:.4g} m"),
            ("nominal height", f"{derived['nominal_height']:.4g} m"),
            ("nominal angles", ", ".join(f"{a:.4g}" for a in design.nominal_angles) + " rad"),
            ("mass", mass),
            ("rated torques", ratings_text(design.rated_torques, "N·m")),
            ("rated speeds", ratings_text(design.rated_speeds, "rad/s")),
        ],
    )
    print("  mounts (body frame)       x [m]    y [m]    z [m]   yaw [rad]  foothold x, y, z [m]")
    for name, mount in derived["mounts"].items():
        print(
            f"    {name:<20} {mount['x']:8.4f} {mount['y']:8.4f} {mount['z']:8.4f} "
            f"{mount['yaw']:8.4f} ({math.degrees(mount['yaw']):6.1f}°)  "
            + ", ".join(f"{v:.4f}" for v in mount["foothold"])
        )
    if "robot" in record:
        _show_legs(record)


def _show_legs(record: dict[str, Any]) -> None:
    """A robot file's legs as read: where from, the segments changed, each leg's numbers."""
    print("  legs read from " + str(record["robot"]["source"]))
    box = record["robot"].get("body_box")
    if box is not None:  # what the extremes stop at
        size = " × ".join(f"{v:.3g}" for v in box["size"])
        print(f"  body box {size} m, where the extremes stop: {box['from']}")
    for change in record["robot"]["changed_segments"]:
        print(
            f"    {change['leg']} {change['segment']} changed from the file's "
            f"{change['file_length']:.4g} m to {change['length']:.4g} m (mass × "
            f"{change['mass_ratio']:.4g})"
        )
    for leg in record["design"]["legs"]:
        print(
            f"    {leg['name']}: joints {', '.join(leg['joints'])}; coxa {leg['coxa']:.4g}, "
            f"femur {leg['femur']:.4g}, tibia {leg['tibia']:.4g}, hip height "
            f"{leg['hip_height']:.4g}, lateral {leg['foot_lateral']:.4g} m; foot by "
            f"{leg['foot']['rule']} ({leg['foot']['source']})"
        )
        moved = leg["nominal"]["moved_into_limits"]
        if moved:
            print(f"      nominal {', '.join(moved)} angle moved inside the file's limits")


def gait_rows(gait: Gait) -> list[tuple[str, str]]:
    """The gait's keys, one a row (SI units)."""
    units = {"period": "s", "stride": "m", "step_height": "m", "heading": "rad", "speed": "m/s"}
    return [
        (key, f"{value:.6g} {units[key]}" if key in units else str(value))
        for key, value in gait.to_dict().items()
        if key != "duty_factor"
    ]


def show_requirements(requirements: Requirements) -> None:
    """The file's requirements, one a row, with their conditions."""
    rows = [(name, requirements.describe(name)) for name in requirements.given]
    if requirements.payload_at is not None:
        position = ", ".join(f"{v:g}" for v in requirements.payload_at)
        rows.append(("payload_at", f"({position}) m, body frame"))
    print_table("Requirements (the file's [requirements] table)", rows)


def _drive(design: HexapodDesign) -> str:
    """``, actuators … kg, battery … kg`` for those the design has."""
    text = "" if design.actuators is None else f", actuators {design.actuators.total_mass:.4g} kg"
    return text + ("" if design.battery is None else f", battery {design.battery.mass:.4g} kg")
