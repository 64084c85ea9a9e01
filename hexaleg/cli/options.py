"""Options shared by several commands, declared once: design, sweep, stance and output."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from typing import Any, cast

from hexaleg._typing import FlexibilityMode, StanceSet, choices
from hexaleg.design import (
    DEFAULT_LEG_LENGTH,
    DESIGN_FIELDS,
    L3_RATIO_POINTS,
    MAX_L3_POINTS,
    SEGMENTS,
)
from hexaleg.exceptions import HexalegError
from hexaleg.field_spec import FieldSpec
from hexaleg.layouts import Layout
from hexaleg.ratios import MAX_L1_RATIOS
from hexaleg.study.executors import WORKERS_PER_CPU, max_workers

DESIGN_GROUP = "design (SI units: metres, radians; defaults: the paper's leg on hexaleg's body)"


class UsageError(HexalegError):
    """A combination of command-line options that does not make sense."""


def bounded_int(minimum: int, maximum: int | None = None) -> Callable[[str], int]:
    """Argparse type: an integer within [minimum, maximum]; argparse reports the rest."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
        if value < minimum or (maximum is not None and value > maximum):
            allowed = f">= {minimum}" if maximum is None else f"in {minimum}..{maximum}"
            raise argparse.ArgumentTypeError(f"{value} is not valid: must be {allowed}")
        return value

    return parse


def add_design_options(
    parser: argparse.ArgumentParser,
    *,
    lengths: bool = True,
    body: bool = True,
    posture: bool = True,
) -> None:
    """Add the design options a command uses, and only those.

    Each design field that a group offers becomes ``--<field>`` with its help, unit and
    default from the field's declaration (:data:`~hexaleg.design.DESIGN_FIELDS`).

    Args:
        parser: The command's parser.
        lengths: Segment lengths (``--l1 --l2 --l3`` or ``--ratios``); without them,
            ``--total`` is the swept designs' leg length.
        body: Body size and layout (``--body-length`` ...): what the stance and the
            robot depend on.
        posture: The nominal joint angles (``--nominal-angles``).

    """
    group = parser.add_argument_group(DESIGN_GROUP)
    group.add_argument(
        "--design",
        metavar="FILE",
        help="read the design from a TOML design file (hexaleg design init) or a .json "
        "design printed by hexaleg; the options below override its values",
    )
    offered = {"lengths": lengths, "body": body, "posture": posture, "ratings": body}
    for spec in DESIGN_FIELDS:
        if spec.option is not None and offered[spec.option]:
            _add_field_option(group, spec)
        if spec.name == SEGMENTS[-1]:
            _add_total_options(group, lengths)
    add_robot_options(parser)


ROBOT_GROUP = "robot file (your hexapod's URDF or Xacro instead of hexaleg's template)"


def add_robot_options(parser: argparse.ArgumentParser, required: bool = False) -> None:
    """``--urdf FILE`` (a positional FILE when ``required``) and how the file is read.

    Every command that takes a design takes them (:func:`add_design_options`); the design
    options then go over the file's robot as they go over the template
    (:func:`~hexaleg.cli.inputs.inputs_from_args`).
    """
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
    group.add_argument(
        "--lock-joint",
        action="append",
        default=[],
        metavar="NAME",
        help="hold this joint of the file at its zero, as a fixed joint (a glob pattern; "
        "repeatable; a [robot] table's lock_joints): a sensor's or a tool's, not the leg's",
    )


def _add_total_options(group: argparse._ArgumentGroup, lengths: bool) -> None:
    """``--ratios`` (with the lengths) and ``--total``: segments as fractions of a total."""
    if lengths:
        group.add_argument(
            "--ratios",
            type=float,
            nargs=2,
            metavar=("L1", "L3"),
            help="coxa and tibia as fractions of --total, instead of --l1/--l2/--l3 [-]",
        )
    what = "for --ratios" if lengths else "of every swept design"
    group.add_argument(
        "--total",
        type=float,
        metavar="M",
        help=f"total leg length l1+l2+l3 {what} [m] (default: the --design file's, "
        f"else {DEFAULT_LEG_LENGTH:g})",
    )


METAVARS = {"m": "M", "rad": "RAD"}
"""Option metavars by unit; others take ``X``."""


def _add_field_option(group: argparse._ArgumentGroup, spec: FieldSpec) -> None:
    """``--<field>`` of one design field, as its declaration describes it."""
    flag = cast(str, spec.flag)
    if spec.kind == "choice":  # custom mounts are given in a --design file
        layouts = tuple(c for c in choices(Layout) if c != "custom")
        help = f"{spec.described} (default {layouts[0]}; custom needs a --design file)"
        group.add_argument(flag, choices=layouts, help=help)
        return
    if spec.kind == "triple":
        default = " ".join(f"{v:.4g}" for v in spec.default)
        group.add_argument(
            flag,
            type=_number_of(spec),
            nargs=len(spec.items),
            metavar=tuple(item.upper() for item in spec.items),
            help=f"{spec.described} (default {default})",
        )
        return
    group.add_argument(
        flag,
        type=_number_of(spec),
        metavar=METAVARS.get(spec.unit, "X"),
        help=f"{spec.described} (default {spec.default:.4g})",
    )


def _number_of(spec: FieldSpec) -> Callable[[str], float]:
    """Argparse type of a design field's number: text that is none names the valid range.

    The range itself is checked with the design (one home: the field's declaration).
    """
    unit = f" [{spec.unit}]" if spec.unit else ""
    allowed = "a number" if spec.bounds is None else "a number in [{:g}, {:g}]".format(*spec.bounds)

    def parse(text: str) -> float:
        try:
            return float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not valid: must be {allowed}{unit}"
            ) from None

    return parse


DESIGN_FLAGS: tuple[str, ...] = tuple(
    spec.name for spec in DESIGN_FIELDS if spec.option is not None and spec.name not in SEGMENTS
)
"""Design fields set by an option of the same name (the segments also take --ratios)."""


def add_sweep_options(
    parser: argparse.ArgumentParser, output: str, least_l3_points: int = 2
) -> None:
    """Options of the commands that sweep designs: output folder, tibia ratios, workers.

    ``least_l3_points`` is the fewest tibia ratios the command accepts (the report needs
    more than a study to bracket its peaks).
    """
    parser.add_argument(
        "-o", "--output", metavar="DIR", default=output, help=f"output folder (default {output})"
    )
    parser.add_argument(
        "--l3-points",
        type=bounded_int(least_l3_points, MAX_L3_POINTS),
        default=L3_RATIO_POINTS,
        metavar="N",
        help=f"tibia ratios per coxa ratio, {least_l3_points}..{MAX_L3_POINTS} "
        f"(default {L3_RATIO_POINTS}, as the paper)",
    )
    parser.add_argument(
        "--workers",
        type=bounded_int(1),
        metavar="N",
        help=f"local worker processes (default: CPUs; at most {WORKERS_PER_CPU} per CPU, "
        f"here {max_workers()})",
    )


def capped_workers(requested: int | None) -> int | None:
    """``--workers`` within :func:`max_workers`; says so on stderr when it caps."""
    if requested is not None and requested > max_workers():
        note(
            f"--workers {requested} capped at {max_workers()} "
            f"({WORKERS_PER_CPU} per CPU on this machine)"
        )
        return max_workers()
    return requested


def note(message: str) -> None:
    """One line on stderr telling the user what hexaleg chose for them."""
    print(f"hexaleg: note: {message}", file=sys.stderr)


def add_stance_option(parser: argparse.ArgumentParser) -> None:
    """``--stance``: which legs stand."""
    parser.add_argument(
        "--stance", choices=choices(StanceSet), default="all", help="stance legs (default all six)"
    )


def add_mode_option(parser: argparse.ArgumentParser) -> None:
    """``--mode``: axis-locked or free-coupled flexibility."""
    parser.add_argument(
        "--mode",
        choices=choices(FlexibilityMode),
        default="axis",
        help="axis-locked (default) or free-coupled",
    )


def add_output_options(parser: argparse.ArgumentParser) -> None:
    """``--json`` and ``--plot DIR`` of the single-design analyses."""
    parser.add_argument(
        "--json", action="store_true", help="print one JSON object (SI units, radians)"
    )
    parser.add_argument("--plot", metavar="DIR", help="write the figures (PNG) into DIR")


def add_l1_ratios_option(parser: argparse.ArgumentParser, default: str) -> None:
    """``--l1-ratios``: the coxa ratios a sweep covers."""
    parser.add_argument(
        "--l1-ratios",
        type=float,
        nargs="+",
        metavar="R",
        help=f"coxa ratios l1/L in (0, 1), at most {MAX_L1_RATIOS} [-] (default: {default})",
    )


def add_field_sweep_option(parser: argparse.ArgumentParser, what: str) -> None:
    """``--sweep FIELD=START:STOP:COUNT``: a body field swept in the sensitivity table."""
    from hexaleg.study.sensitivity import MAX_SWEEP_POINTS, SWEEPABLE

    parser.add_argument(
        "--sweep",
        metavar="FIELD=A:B:N",
        help=f"{what}: FIELD from A to B in N steps (2..{MAX_SWEEP_POINTS}), e.g. "
        f"body_width=0.4:0.8:9; FIELD is one of {', '.join(SWEEPABLE)}",
    )


def field_sweep_from_args(args: argparse.Namespace) -> Any:
    """The parsed ``--sweep`` (a :class:`~hexaleg.study.sensitivity.FieldSweep`) or ``None``."""
    from hexaleg.study.sensitivity import FieldSweep

    return None if args.sweep is None else FieldSweep.parse(args.sweep)


def add_collisions_option(parser: argparse.ArgumentParser) -> None:
    """``--collisions``: the robot's own parts touching also stop the body."""
    parser.add_argument(
        "--collisions",
        action="store_true",
        help="also stop the body where two of the robot's own parts touch (coal; slower)",
    )
