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
    from hexaleg.study.robot_designs import RobotDesigns, RobotFile

ROBOT_GROUP = "robot file (your hexapod's URDF or Xacro instead of hexaleg's template)"

ROBOT_COMMANDS = (
    "design show",
    "design import",
    "workspace",
    "manipulability",
    "flexibility",
    "loads",
    "gait",
    "simulate",
    "urdf",
    "view",
    "study",
    "decide",
    "report",
    "explore",
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
    add_lock_option(group)


def robot_from_args(args: argparse.Namespace) -> ImportedRobot | None:
    """The robot of ``--urdf`` (or of the ``--design`` file's ``[robot]`` table), or ``None``.

    ``--l1 --l2 --l3`` (every leg) and the design file's ``[robot.segments]`` (per leg, the
    command line's first) change the robot's segments along their own lines
    (:func:`~hexaleg.robot.resize.resize_robot`).
    """
    found = _robot_and_file(args)
    return None if found is None else found[0]


def _robot_and_file(args: argparse.Namespace) -> tuple[ImportedRobot, RobotFile] | None:
    """:func:`robot_from_args`'s robot, and how to read it again in another process."""
    from hexaleg.cli.robot_table import load_robot_table
    from hexaleg.robot.feet import FootSearch
    from hexaleg.robot.imported import import_robot
    from hexaleg.study.robot_designs import RobotFile

    design = getattr(args, "design", None)
    table = load_robot_table(design) if design and args.urdf is None else None
    if args.urdf is None and table is None:
        given = [f for f in ("foot_frame", "foot_offset") if getattr(args, f, None) is not None]
        given += [f for f in ("xacro_arg", "package", "lock_joint") if getattr(args, f, None)]
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
    lengths, fields = _segment_lengths(args, table)
    lock = settings["lock_joints"]
    robot = import_robot(settings["urdf"], settings["xacro_args"], settings["packages"], foot, lock)
    if table is not None:
        _check_file_segments(args, robot)
    file = RobotFile.of(
        str(settings["urdf"]), settings["xacro_args"], settings["packages"], foot, lengths, lock
    )
    if not lengths:
        return robot, file
    from hexaleg.robot.resize import resize_robot

    return resize_robot(robot, lengths, lambda leg, segment: fields[leg, segment]), file


def robot_designs(args: argparse.Namespace, design: HexapodDesign) -> RobotDesigns | None:
    """The imported robot's designs (the study's, the decision's, the report's), or ``None``.

    The robot of :func:`robot_from_args` over ``design`` (the options' design, as every
    single-design command takes it); each design point is that file with its segments
    changed (:class:`~hexaleg.study.robot_designs.RobotDesigns`).
    """
    from hexaleg.study.robot_designs import RobotDesigns

    found = _robot_and_file(args)
    if found is None:
        return None
    refuse_unsupported(args)
    designs = RobotDesigns(found[1], design)
    designs.point()  # the robot as given stands over this design, or is refused now
    return designs


def _check_file_segments(args: argparse.Namespace, robot: ImportedRobot) -> None:
    """Refuse a design file whose ``l1 l2 l3`` were edited: a ``[robot]``'s are its file's."""
    from hexaleg.cli.robot_table import file_segments
    from hexaleg.leg_geometry import SEGMENT_NAMES
    from hexaleg.robot.resize import SAME_LENGTH

    written = file_segments(args.design)
    read = robot.legs[0].reading.geometry
    for flag, segment in zip(("l1", "l2", "l3"), SEGMENT_NAMES, strict=True):
        value = written.get(flag)
        if getattr(args, flag, None) is not None or not isinstance(value, int | float):
            continue
        length = getattr(read, segment)
        if abs(value - length) > SAME_LENGTH:
            raise UsageError(
                f"{args.design}: {flag} = {value:g} is not the robot file's {segment} "
                f"({length:.6g} m): an imported robot's segments are read from its file; "
                f"change them in [robot.segments] or with --{flag}"
            )


def _segment_lengths(
    args: argparse.Namespace, table: dict[str, Any] | None
) -> tuple[dict[str, dict[str, float]], dict[tuple[str, str], str]]:
    """The new segment lengths by leg [m], and the field each came from (for errors)."""
    from hexaleg.cli.robot_table import segment_lengths
    from hexaleg.layouts import LEG_NAMES
    from hexaleg.leg_geometry import SEGMENT_NAMES

    lengths: dict[str, dict[str, float]] = {}
    fields: dict[tuple[str, str], str] = {}
    if table is not None:
        for leg, segments in segment_lengths(table).items():
            for segment, (value, field) in segments.items():
                lengths.setdefault(leg, {})[segment] = value
                fields[leg, segment] = field
    for flag, segment in zip(("l1", "l2", "l3"), SEGMENT_NAMES, strict=True):
        given = getattr(args, flag, None)
        if given is None:
            continue
        for leg in LEG_NAMES:
            lengths.setdefault(leg, {})[segment] = float(given)
            fields[leg, segment] = f"--{flag}"
    return lengths, fields


def robot_table(
    args: argparse.Namespace, output: Path | None, robot: ImportedRobot
) -> dict[str, Any]:
    """The ``[robot]`` table of a design file at ``output`` that reads ``robot`` back.

    The robot file and the package folders relative to the design file's folder (absolute
    paths without ``output``), the Xacro arguments and foot options as given (``--urdf``
    and its companions, else the ``--design`` file's ``[robot]``), and what was read
    (``read``, for reference only).
    """
    import os

    from hexaleg.cli.robot_table import load_robot_table
    from hexaleg.robot.robot_design import robot_record

    design = getattr(args, "design", None)
    table = load_robot_table(design) if design and args.urdf is None else None
    settings = _settings(args, table, Path(design or ".").parent)

    def where(path: Any) -> str:
        found = os.path.abspath(path)
        return found if output is None else os.path.relpath(found, output.resolve().parent)

    written: dict[str, Any] = {
        "urdf": where(settings["urdf"]),
        "xacro_args": dict(settings["xacro_args"]),
        "packages": {name: where(path) for name, path in settings["packages"].items()},
    }
    if settings["foot_frame"] is not None:
        written["foot_frame"] = settings["foot_frame"]
    if settings["foot_offset"] is not None:
        written["foot_offset"] = list(settings["foot_offset"])
    if settings["lock_joints"]:
        written["lock_joints"] = list(settings["lock_joints"])
    record = robot_record(robot)
    written["read"] = _toml_ready({k: v for k, v in record.items() if k != "source"})
    return written


def _toml_ready(value: Any) -> Any:
    """``value`` with every ``None`` (an unbounded limit, a rating not given) as "none"."""
    if isinstance(value, dict):
        return {k: _toml_ready(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_toml_ready(v) for v in value]
    return "none" if value is None else value


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
            "lock_joints": lock_patterns(args, None),
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
        "lock_joints": lock_patterns(args, table),
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
        ("--lock-joint", 1),
    ):
        parser.add_argument(flag, nargs=nargs, action=_Refuse, help=argparse.SUPPRESS)


def refuse_unsupported(args: argparse.Namespace, plots: bool = False) -> None:
    """Refuse, with ``--urdf``, the options not yet applied to an imported robot.

    ``--l1 --l2 --l3`` change its segments (:func:`robot_from_args`); ``--ratios`` would
    need a total leg length the file does not have, so it is refused; with ``plots``, the
    caller draws ``--plot``.
    """
    if getattr(args, "ratios", None) is not None:
        raise UsageError("--ratios with --urdf: give --l1 --l2 --l3 to change the segments")
    if getattr(args, "plot", None) is not None and not plots:
        raise UsageError("--plot with --urdf is not supported yet: use --json")


def robot_legs(args: argparse.Namespace, design: Any) -> tuple[str, dict[str, Any]] | None:
    """The robot file and each leg's general leg by hexaleg's name; ``None`` without a robot.

    ``design`` (the options' design) only gives the joint-limit sets: the paper's, on
    hexaleg's angles. The legs are read from the robot file as changed by ``--l1 --l2
    --l3`` and ``[robot.segments]`` (:func:`robot_from_args`).
    """
    robot = robot_from_args(args)
    if robot is None:
        return None
    refuse_unsupported(args)
    return str(robot.source), {leg.name: leg.reading.geometry for leg in robot.legs}


def robot_model(
    args: argparse.Namespace, design: HexapodDesign, plots: bool = False
) -> ImportedHexapodModel | None:
    """The whole imported robot as a Pinocchio model over ``design``; ``None`` without one.

    The path of every command that analyses the robot standing or walking (its masses, its
    feet, its nominal posture): :class:`~hexaleg.robot.imported_model.ImportedHexapodModel`,
    with the segments changed by ``--l1 --l2 --l3`` and ``[robot.segments]``; ``--plot``
    is refused unless the command draws the robot's figures (``plots``).
    """
    robot = robot_from_args(args)
    if robot is None:
        return None
    refuse_unsupported(args, plots=plots)
    from hexaleg.robot.imported_model import ImportedHexapodModel

    return ImportedHexapodModel(robot, design)


def robot_angles(model: ImportedHexapodModel) -> dict[str, Any]:
    """The robot file and each leg's nominal posture, JSON-ready [rad].

    ``robot`` (the file), ``joint_angles`` (hexaleg's θ) and ``urdf_joint_angles`` (the
    file's q = s·θ + o).
    """
    nominal = {leg: list(model.nominal_angles(leg)) for leg in model.leg_names}
    files = {leg: model.joint_values(leg, a).tolist() for leg, a in nominal.items()}
    return {"robot": str(model.robot.source), "joint_angles": nominal, "urdf_joint_angles": files}


# -- locked joints (#40): kept apart so that the robot-options rework can move them as one --

LOCK_KEY = "lock_joints"
"""A ``[robot]`` table's list of joints (glob patterns) locked at their zero."""


def add_lock_option(group: argparse._ArgumentGroup) -> None:
    """``--lock-joint NAME`` (repeatable): a joint of the file held at its zero."""
    group.add_argument(
        "--lock-joint",
        action="append",
        default=[],
        metavar="NAME",
        help="hold this joint of the file at its zero, as a fixed joint (a glob pattern; "
        "repeatable; a [robot] table's lock_joints): a sensor's or a tool's, not the leg's",
    )


def lock_patterns(args: argparse.Namespace, table: dict[str, Any] | None) -> tuple[str, ...]:
    """The joints to lock: the ``[robot]`` table's ``lock_joints``, then ``--lock-joint``."""
    saved = [] if table is None else table.get(LOCK_KEY, [])
    if not isinstance(saved, list) or not all(isinstance(p, str) and p for p in saved):
        raise UsageError(f"{args.design}: [robot] {LOCK_KEY} must be a list of joint names")
    given = getattr(args, "lock_joint", None) or []
    return tuple(dict.fromkeys([*saved, *given]))
