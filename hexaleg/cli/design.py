"""``hexaleg design``: start a design file, and show the design a file and options resolve to."""

from __future__ import annotations

import argparse
import math
from typing import Any

from hexaleg.cli.options import UsageError, add_design_options, inputs_from_args
from hexaleg.cli.output import print_json, print_table, report_files
from hexaleg.design import HexapodDesign
from hexaleg.study.requirements import Requirements
from hexaleg.study.requirements_table import example_table

INIT_DESCRIPTION = (
    "Write FILE: every design field with its unit in a comment, at the defaults or at "
    "the values the options give (say --layout hexagon --body-radius 0.35), and an example "
    "[requirements] table for decide and report, commented out."
)

DESCRIPTION = (
    "Keep your robot in a design file: `design init FILE` writes a commented TOML file "
    "(the defaults, or the design the options describe); `design show` prints the design "
    "a --design file and options resolve to, with its derived values."
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
    show = actions.add_parser(
        "show",
        help="print the resolved design and its derived values",
        description="Print the design (defaults, --design file, then options) with its leg "
        "length, nominal height, mass and leg mounts, and the file's [requirements] if it has "
        "them.",
    )
    add_design_options(show)
    show.add_argument("--json", action="store_true", help="print one JSON object")


def run(args: argparse.Namespace) -> int:
    """Write or show the design."""
    design, requirements = inputs_from_args(args)
    if args.action == "init":
        return _init(args.file, design, args.force)
    if args.json:
        out = {"design": design.as_dict(), "derived": derived(design)}
        if requirements.given:
            out["requirements"] = requirements.to_dict()
        print_json(out)
    else:
        show(design)
        if requirements.given:
            show_requirements(requirements)
    return 0


def _init(file: str, design: HexapodDesign, force: bool) -> int:
    from hexaleg._io import check_output_file, write_text
    from hexaleg.design_text import design_toml

    path = check_output_file(file)  # as typed: an empty path is refused, not read as "."
    if path.suffix.lower() != ".toml":
        raise UsageError(f"design init {path}: the file must end in .toml")
    if path.exists() and not force:
        raise UsageError(f"design init {path}: the file exists (pass --force to overwrite it)")
    report_files([write_text(path, design_toml(design) + "\n" + example_table())])
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


def show(design: HexapodDesign) -> None:
    """The design as text: the body, derived values, then one row per leg."""
    print_table(
        f"Design ({design.body_description})",
        [
            ("segments l1, l2, l3", f"{design.l1:.4g}, {design.l2:.4g}, {design.l3:.4g} m"),
            ("leg length", f"{design.leg_length:.4g} m"),
            ("nominal height", f"{design.nominal_height:.4g} m"),
            ("nominal angles", ", ".join(f"{a:.4g}" for a in design.nominal_angles) + " rad"),
            ("mass", f"{design.total_mass:.4g} kg (body {design.body_mass:g} kg{_drive(design)})"),
            ("rated torques", ", ".join(f"{t:g}" for t in design.rated_torques) + " N·m"),
            ("rated speeds", ", ".join(f"{w:g}" for w in design.rated_speeds) + " rad/s"),
        ],
    )
    print("  mounts (body frame)       x [m]    y [m]    z [m]   yaw [rad]  foothold x, y, z [m]")
    for mount, foot in zip(design.legs, design.nominal_footholds, strict=True):
        print(
            f"    {mount.name:<20} {mount.x:8.4f} {mount.y:8.4f} {mount.z:8.4f} "
            f"{mount.yaw:8.4f} ({math.degrees(mount.yaw):6.1f}°)  "
            + ", ".join(f"{v:.4f}" for v in foot)
        )


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
