"""The robot-file options (``--urdf FILE`` ...): analyse a user's hexapod instead of the template.

Commands that run on an imported robot add them with :func:`add_robot_options` and read
them with :func:`robot_from_args`; every other command gets a ``--urdf`` that refuses in
one line (:func:`add_refused_robot_option`), naming the commands that do run on one.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from hexaleg.cli.options import UsageError

if TYPE_CHECKING:
    from hexaleg.design import HexapodDesign
    from hexaleg.robot.imported import ImportedRobot
    from hexaleg.robot.imported_model import ImportedHexapodModel

ROBOT_GROUP = "robot file (your hexapod's URDF or Xacro instead of hexaleg's template)"

ROBOT_COMMANDS = (
    "design show",
    "design import",
    "workspace",
    "manipulability",
    "flexibility",
    "loads",
    "urdf",
)
"""The commands that run on an imported robot."""


def add_robot_options(parser: argparse.ArgumentParser, required: bool = False) -> None:
    """Add ``--urdf`` (or a positional FILE when ``required``) and its companions."""
    parser.set_defaults(robot_options=True)
    group = parser.add_argument_group(ROBOT_GROUP)
    if required:
        group.add_argument("urdf", metavar="FILE", help="the robot's URDF or Xacro file")
    else:
        group.add_argument(
            "--urdf",
            metavar="FILE",
            help="analyse the hexapod of this URDF or Xacro file (six yaw-pitch-pitch legs)",
        )
    group.add_argument(
        "--xacro-arg",
        action="append",
        default=[],
        metavar="NAME:=VALUE",
        help="a Xacro argument (repeatable)",
    )
    group.add_argument(
        "--package",
        action="append",
        default=[],
        metavar="NAME=DIR",
        help="the folder of ROS package NAME, for $(find NAME) and package://NAME/ (repeatable)",
    )
    group.add_argument(
        "--foot-frame",
        metavar="NAME",
        help="the link at each foot (a glob pattern matching one link beyond each knee)",
    )
    group.add_argument(
        "--foot-offset",
        nargs=3,
        type=float,
        metavar=("X", "Y", "Z"),
        help="the foot point in each leg's last link frame [m], when the file draws no foot",
    )


def robot_from_args(args: argparse.Namespace) -> ImportedRobot | None:
    """The robot of ``--urdf`` (or of the ``--design`` file's ``[robot]`` table), or ``None``."""
    from hexaleg.cli.robot_table import load_robot_table
    from hexaleg.robot.feet import FootSearch
    from hexaleg.robot.imported import import_robot

    design = getattr(args, "design", None)
    table = load_robot_table(design) if design and args.urdf is None else None
    if args.urdf is None and table is None:
        given = [f for f in ("foot_frame", "foot_offset") if getattr(args, f, None) is not None]
        given += [f for f in ("xacro_arg", "package") if getattr(args, f, None)]
        if given:
            flag = "--" + given[0].replace("_", "-")
            raise UsageError(f"{flag} only applies together with --urdf FILE")
        return None
    settings = _settings(args, table, Path(design or ".").parent)
    if settings["foot_frame"] is not None and settings["foot_offset"] is not None:
        raise UsageError("--foot-frame and --foot-offset exclude each other: give one")
    offset = settings["foot_offset"]
    foot = FootSearch(
        offset=None if offset is None else tuple(offset),
        frame=settings["foot_frame"],
        packages=settings["packages"],
    )
    return import_robot(settings["urdf"], settings["xacro_args"], settings["packages"], foot)


def _settings(args: argparse.Namespace, table: dict[str, Any] | None, folder: Path) -> dict:
    """The robot file and its reading options: the command line's over the design file's."""
    xacro_args = _pairs(args.xacro_arg, ":=", "--xacro-arg", "NAME:=VALUE")
    packages = _pairs(args.package, "=", "--package", "NAME=DIR")
    if table is None:
        return {
            "urdf": args.urdf,
            "xacro_args": xacro_args,
            "packages": packages,
            "foot_frame": args.foot_frame,
            "foot_offset": args.foot_offset,
        }
    try:
        saved = {k: str(v) for k, v in dict(table.get("xacro_args", {})).items()}
        folders = {k: str(folder / str(v)) for k, v in dict(table.get("packages", {})).items()}
        urdf = (folder / str(table["urdf"])).resolve()
    except (KeyError, TypeError, ValueError):
        raise UsageError(f"{args.design}: [robot] needs urdf = FILE (and tables of text)") from None
    frame, offset = table.get("foot_frame"), table.get("foot_offset")
    return {
        "urdf": urdf,
        "xacro_args": {**saved, **xacro_args},
        "packages": {**folders, **packages},
        "foot_frame": args.foot_frame if args.foot_frame is not None else frame,
        "foot_offset": args.foot_offset if args.foot_offset is not None else offset,
    }


def _pairs(given: list[str], separator: str, flag: str, form: str) -> dict[str, str]:
    pairs = {}
    for text in given:
        name, found, value = text.partition(separator)
        if not found or not name or not value:
            raise UsageError(f"{flag} {text!r}: expected {form}")
        pairs[name] = value
    return pairs


class _Refuse(argparse.Action):
    """An option that a command does not take yet: refused in one line when given."""

    def __call__(self, parser: argparse.ArgumentParser, *args: Any, **kwargs: Any) -> NoReturn:
        parser.error(
            f"{self.option_strings[0]} does not run on this command yet; an imported robot "
            f"runs with: {', '.join(ROBOT_COMMANDS)}"
        )


def add_refused_robot_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--urdf`` and its companions, each refusing in one line when given."""
    for flag, nargs in (
        ("--urdf", 1),
        ("--xacro-arg", 1),
        ("--package", 1),
        ("--foot-frame", 1),
        ("--foot-offset", 3),
    ):
        parser.add_argument(flag, nargs=nargs, action=_Refuse, help=argparse.SUPPRESS)


SEGMENT_FLAGS = ("l1", "l2", "l3", "ratios")
"""Options that would change the segments: not yet applied to an imported robot."""


def refuse_unsupported(args: argparse.Namespace, segments: bool = False) -> None:
    """Refuse, with ``--urdf``, the options not yet applied to an imported robot.

    With ``segments``, ``--l1 --l2 --l3`` are applied by the caller (only ``--ratios`` is
    refused).
    """
    flags = ("ratios",) if segments else SEGMENT_FLAGS
    given = [f for f in flags if getattr(args, f, None) is not None]
    if given and segments:
        raise UsageError("--ratios with --urdf: give --l1 --l2 --l3 to change the segments")
    if given:
        raise UsageError(
            f"--{given[0]} with --urdf: this command does not change an imported robot's "
            f"segments yet (workspace and manipulability do)"
        )
    if getattr(args, "plot", None) is not None:
        raise UsageError("--plot with --urdf is not supported yet: use --json")


def robot_legs(args: argparse.Namespace, design: Any) -> tuple[str, dict[str, Any]] | None:
    """The robot file and each leg's general leg by hexaleg's name; ``None`` without a robot.

    ``design`` (the options' design) only gives the joint-limit sets: the paper's, on
    hexaleg's angles. ``--l1 --l2 --l3`` change every leg's coxa, femur and tibia along
    their own lines, keeping offsets and bends (:meth:`LegGeometry.with_lengths`).
    """
    robot = robot_from_args(args)
    if robot is None:
        return None
    refuse_unsupported(args, segments=True)
    lengths = {"coxa": args.l1, "femur": args.l2, "tibia": args.l3}
    return str(robot.source), {
        leg.name: leg.reading.geometry.with_lengths(**lengths) for leg in robot.legs
    }


def robot_model(args: argparse.Namespace, design: HexapodDesign) -> ImportedHexapodModel | None:
    """The whole imported robot as a Pinocchio model over ``design``; ``None`` without one.

    The path of every command that analyses the robot standing (its masses, its feet, its
    nominal posture): :class:`~hexaleg.robot.imported_model.ImportedHexapodModel`.
    Options that would change the segments are refused (:func:`refuse_unsupported`).
    """
    robot = robot_from_args(args)
    if robot is None:
        return None
    refuse_unsupported(args)
    from hexaleg.robot.imported_model import ImportedHexapodModel

    return ImportedHexapodModel(robot, design)
