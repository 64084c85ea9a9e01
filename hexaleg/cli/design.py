"""``hexaleg design``: start a design file, and show the design a file and options resolve to."""

from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING, Any

from hexaleg.cli.options import UsageError, add_design_options, inputs_from_args
from hexaleg.cli.output import print_json, print_table, report_files
from hexaleg.cli.robot_options import (
    add_refused_robot_option,
    add_robot_options,
    refuse_unsupported,
    robot_from_args,
    robot_table,
)
from hexaleg.cli.structure_options import size_if_asked, structure_rows, tube_rows
from hexaleg.design import HexapodDesign
from hexaleg.evaluation.requirements import Requirements
from hexaleg.evaluation.requirements_table import example_table
from hexaleg.gait.spec import Gait
from hexaleg.ratings import ratings_text

if TYPE_CHECKING:
    from hexaleg.robot.imported import ImportedRobot

INIT_DESCRIPTION = (
    "Write FILE: every design field with its unit in a comment, at the defaults or at "
    "the values the options give (say --layout hexagon --body-radius 0.35), and an example "
    "[requirements] table for decide and report and a [structure] table of the legs' tubes, "
    "commented out."
)

DESCRIPTION = (
    "Keep your robot in a design file: `design init FILE` writes a commented TOML file "
    "(the defaults, or the design the options describe); `design show` prints the design "
    "a --design file and options resolve to, with its derived values."
)


ROBOT_OPTIONS = True

IMPORT_DESCRIPTION = (
    "Read your hexapod's URDF or Xacro FILE (six yaw-pitch-pitch legs) and write a design "
    "file: the segments, mounts, body mass and ratings hexaleg read, and a [robot] table "
    "that names FILE and records each leg (joints, dimensions, offsets, foot, limits), to "
    "edit and version. Commands that run on an imported robot take it with --design."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``init`` and ``show`` actions and their options."""
    actions = parser.add_subparsers(dest="action", metavar="ACTION", parser_class=type(parser))
    actions.required = True
    init = actions.add_parser(
        "init", help="write a commented TOML design file", description=INIT_DESCRIPTION
    )
    init.add_argument("file", metavar="FILE", help="the .toml file to write")
    init.add_argument("--force", action="store_true", help="overwrite FILE if it exists")
    add_design_options(init)
    add_refused_robot_option(init)
    show = actions.add_parser(
        "show",
        help="print the resolved design and its derived values",
        description="Print the design (defaults, --design file, then options) with its leg "
        "length, nominal height, mass and leg mounts, and the file's [requirements] if it has "
        "them.",
    )
    add_design_options(show)
    add_robot_options(show)
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
        return _import(args)
    design, requirements = inputs_from_args(args)
    if args.action == "init":
        return _init(args.file, design, args.force, requirements.walked)
    robot = robot_from_args(args)
    design, sized = size_if_asked(design, requirements, robot is not None)
    out = (
        {"design": design.as_dict(), "derived": derived(design)}
        if robot is None
        else _show_robot(args, robot, design)
    )
    if sized is not None:
        out["derived"]["sizing"] = sized.to_dict() | {"check": sized.check.to_dict()}
    if args.json:
        if requirements.given:
            out["requirements"] = requirements.to_dict()
        if requirements.walked != Gait():
            out["gait"] = requirements.walked.to_dict()
        print_json(out)
        return 0
    if robot is None:
        show(design)
        if design.structure is not None:
            rows = (
                tube_rows(design.structure, design.lengths)
                if sized is None
                else structure_rows(sized.check, sized)
            )
            print_table("Structure (the file's [structure] table)", rows)
    if requirements.given:
        show_requirements(requirements)
    if requirements.walked != Gait():
        print_table("Gait (the file's [gait] table)", gait_rows(requirements.walked))
    return 0


def _show_robot(args: argparse.Namespace, robot: Any, design: HexapodDesign) -> dict[str, Any]:
    """The imported robot's design and what was read, per leg: JSON-ready, else printed."""
    from hexaleg.robot.robot_design import robot_design, robot_record

    refuse_unsupported(args)
    design = robot_design(robot, design)
    record = robot_record(robot, design.nominal_angles)
    shown = {
        "design": {**design.as_dict(), "legs": record["legs"]},
        "derived": {**derived(design), "total_mass": robot.mass},  # the file's links
        "robot": {k: v for k, v in record.items() if k != "legs"},
    }
    if args.json:
        return shown
    if robot.mass <= 0.0:
        show(design, "none: the file gives no masses (kinematics only)")
    else:
        show(design, f"{robot.mass:.4g} kg, the file's links (body {robot.body_mass.mass:.4g} kg)")
    print("  legs read from " + str(record["source"]))
    if record["body_box"] is not None:  # what the extremes stop at
        box = record["body_box"]
        size = " × ".join(f"{v:.3g}" for v in box["size"])
        print(f"  body box {size} m, where the extremes stop: {box['from']}")
    for change in record["changed_segments"]:
        print(
            f"    {change['leg']} {change['segment']} changed from the file's "
            f"{change['file_length']:.4g} m to {change['length']:.4g} m (mass × "
            f"{change['mass_ratio']:.4g})"
        )
    for leg in record["legs"]:
        print(
            f"    {leg['name']}: joints {', '.join(leg['joints'])}; coxa {leg['coxa']:.4g}, "
            f"femur {leg['femur']:.4g}, tibia {leg['tibia']:.4g}, hip height "
            f"{leg['hip_height']:.4g}, lateral {leg['foot_lateral']:.4g} m; foot by "
            f"{leg['foot']['rule']} ({leg['foot']['source']})"
        )
        moved = leg["nominal"]["moved_into_limits"]
        if moved:
            print(f"      nominal {', '.join(moved)} angle moved inside the file's limits")
    return shown


def _import(args: argparse.Namespace) -> int:
    """Write the design file of the robot file ``args.urdf``."""
    from hexaleg._io import check_output_file, write_text
    from hexaleg.design_text import design_toml
    from hexaleg.robot.robot_design import robot_design

    path = check_output_file(args.output)
    if path.suffix.lower() != ".toml":
        raise UsageError(f"design import -o {path}: the file must end in .toml")
    if path.exists() and not args.force:
        raise UsageError(f"design import -o {path}: the file exists (pass --force to overwrite it)")
    robot = robot_from_args(args)
    if robot is None:  # unreachable: FILE is required
        raise UsageError("design import needs the robot's FILE")
    design = robot_design(robot)
    table = _robot_table(args, path, robot)
    report_files([write_text(path, design_toml(design) + "\n" + table)])
    return 0


def _robot_table(args: argparse.Namespace, output: Any, robot: ImportedRobot) -> str:
    """The ``[robot]`` table (:func:`~hexaleg.cli.robot_options.robot_table`), commented."""
    import tomli_w

    comment = "# [robot]: the robot file this design was read from (hexaleg design import);\n"
    comment += "# [robot.read] records what was read, for reference: editing it changes nothing.\n"
    comment += "# What if: [robot.segments] coxa/femur/tibia = M (every leg) or\n"
    comment += "# [robot.segments.<leg>] change the segments along their own lines [m].\n"
    return comment + tomli_w.dumps({"robot": robot_table(args, output, robot)})


def _init(file: str, design: HexapodDesign, force: bool, gait: Gait) -> int:
    from hexaleg._io import check_output_file, write_text
    from hexaleg.design_text import design_toml, structure_example

    path = check_output_file(file)  # as typed: an empty path is refused, not read as "."
    if path.suffix.lower() != ".toml":
        raise UsageError(f"design init {path}: the file must end in .toml")
    if path.exists() and not force:
        raise UsageError(f"design init {path}: the file exists (pass --force to overwrite it)")
    walked = "" if gait == Gait() else "\n" + gait.to_toml()
    structure = "" if design.structure is not None else "\n" + structure_example()
    text = design_toml(design) + walked + structure + "\n" + example_table()
    report_files([write_text(path, text)])
    return 0


def derived(design: HexapodDesign) -> dict[str, Any]:
    """What follows from the design: leg length, nominal height, mass, mounts, footholds."""
    feet = design.nominal_footholds
    return {
        "layout": design.layout,
        "body": design.body_description,
        "leg_length": design.leg_length,
        "nominal_height": design.nominal_height,
        "total_mass": design.total_mass,
        "mounts": {
            m.name: {"x": m.x, "y": m.y, "z": m.z, "yaw": m.yaw, "foothold": list(foot)}
            for m, foot in zip(design.legs, feet, strict=True)
        },
        "units": {"lengths": "m", "angles": "rad", "mass": "kg"},
    }


def show(design: HexapodDesign, mass: str | None = None) -> None:
    """The design as text: the body, derived values, then one row per leg.

    ``mass``: what the mass row says, when it is not the design's (an imported robot's).
    """
    if mass is None:
        mass = f"{design.total_mass:.4g} kg (body {design.body_mass:g} kg{_drive(design)})"
    print_table(
        f"Design ({design.body_description})",
        [
            ("segments l1, l2, l3", f"{design.l1:.4g}, {design.l2:.4g}, {design.l3:.4g} m"),
            ("leg length", f"{design.leg_length:.4g} m"),
            ("nominal height", f"{design.nominal_height:.4g} m"),
            ("nominal angles", ", ".join(f"{a:.4g}" for a in design.nominal_angles) + " rad"),
            ("mass", mass),
            ("rated torques", ratings_text(design.rated_torques, "N·m")),
            ("rated speeds", ratings_text(design.rated_speeds, "rad/s")),
        ],
    )
    print("  mounts (body frame)       x [m]    y [m]    z [m]   yaw [rad]  foothold x, y, z [m]")
    for mount, foot in zip(design.legs, design.nominal_footholds, strict=True):
        print(
            f"    {mount.name:<20} {mount.x:8.4f} {mount.y:8.4f} {mount.z:8.4f} "
            f"{mount.yaw:8.4f} ({math.degrees(mount.yaw):6.1f}°)  "
            + ", ".join(f"{v:.4f}" for v in foot)
        )


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
