"""Options shared by several commands, declared once: design, sweep, stance and output."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, cast

from hexaleg._typing import FlexibilityMode, StanceSet, choices
from hexaleg.design import (
    DEFAULT_LEG_LENGTH,
    DESIGN_FIELDS,
    L3_RATIO_POINTS,
    MAX_L3_POINTS,
    SEGMENTS,
    HexapodDesign,
)
from hexaleg.exceptions import HexalegError
from hexaleg.field_spec import FieldSpec
from hexaleg.gait.defaults import default_gait
from hexaleg.gait.spec import Gait
from hexaleg.layouts import Layout
from hexaleg.ratios import MAX_L1_RATIOS
from hexaleg.study.executors import WORKERS_PER_CPU, max_workers

if TYPE_CHECKING:
    from hexaleg.evaluation.requirements import Requirements
    from hexaleg.robot.model import HexapodModel

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


def design_from_args(args: argparse.Namespace) -> HexapodDesign:
    """Build the design the shared options describe (validated).

    A ``--design`` file gives the starting design (it must be valid on its own, its
    ``[requirements]`` table included); the options given beside it override its values.
    """
    return inputs_from_args(args)[0]


def design_gait(args: argparse.Namespace, model: HexapodModel | None = None) -> Gait:
    """The ``--design`` file's ``[gait]`` table's gait, its keys over the default gait.

    The default gait is ``model``'s own (:func:`~hexaleg.gait.defaults.default_gait`: a
    robot file's is sized to it), or :class:`Gait`'s defaults without a model.
    """
    path = getattr(args, "design", None)
    base = None if model is None else default_gait(model)
    if path is None:
        return Gait() if base is None else base
    return load_gait(path, base)


def walked_by(
    args: argparse.Namespace, requirements: Requirements, model: HexapodModel
) -> Requirements:
    """``requirements`` walking ``model``'s gait: the file's ``[gait]`` over its own default."""
    return requirements.walking(design_gait(args, model))


def load_gait(path: str | os.PathLike[str], base: Gait | None = None) -> Gait:
    """The gait a design file's ``[gait]`` table describes, over ``base`` (without one: it).

    Raises:
        DesignFileError: naming the file, the line and ``gait.<key>``.

    """
    from hexaleg.design_file import GAIT, load_table  # reads TOML only when asked

    return load_table(path, GAIT, lambda table: Gait.from_table(table, base))


def inputs_from_args(args: argparse.Namespace) -> tuple[HexapodDesign, Requirements]:
    """The design the shared options describe, and the ``--design`` file's requirements.

    The file is read once, and every command reads it the same way: a bad
    ``[requirements]`` table is refused by a command that does not use it too.
    """
    from hexaleg.design_file import load_design_file  # reads TOML only when asked
    from hexaleg.evaluation.requirements import Requirements

    path = getattr(args, "design", None)
    base, requirements = (
        (HexapodDesign(), Requirements())
        if path is None
        else load_design_file(path, Requirements.from_table)
    )
    if path is not None:
        requirements = requirements.walking(load_gait(path))
    if path is not None and not getattr(args, "robot_options", False):
        from hexaleg.cli.robot_options import ROBOT_COMMANDS
        from hexaleg.cli.robot_table import load_robot_table

        if load_robot_table(path) is not None:
            raise UsageError(
                f"{path} describes an imported robot ([robot]); this command does not run "
                f"on one yet ({', '.join(ROBOT_COMMANDS)} do)"
            )
    changes: dict[str, Any] = {
        name: _value(getattr(args, name))
        for name in DESIGN_FLAGS
        if getattr(args, name, None) is not None
    }
    if getattr(args, "ratios", None) is not None:
        given = [f"--{n}" for n in SEGMENTS if getattr(args, n) is not None]
        if given:
            raise UsageError(f"--ratios cannot be combined with {', '.join(given)}")
        total = study_total(args, base)
        design = base.replace(**changes).with_ratios(args.ratios[0], args.ratios[1], total)
        if args.total is None and path is None:  # said once the design stands: errors stay 1 line
            note(f"--ratios without --total: total leg length {DEFAULT_LEG_LENGTH:g} m")
        return design, requirements
    if args.total is not None and hasattr(args, "ratios"):
        raise UsageError("--total only applies together with --ratios")
    if not _imported(args, path):  # a robot's --l1 --l2 --l3 change its file (robot_from_args)
        for name in SEGMENTS:
            if getattr(args, name, None) is not None:
                changes[name] = getattr(args, name)
    return (base.replace(**changes) if changes else base), requirements


def _imported(args: argparse.Namespace, path: str | None) -> bool:
    """Whether the command analyses an imported robot (``--urdf``, or a ``[robot]`` file)."""
    if not getattr(args, "robot_options", False):
        return False
    if getattr(args, "urdf", None) is not None:
        return True
    from hexaleg.cli.robot_table import load_robot_table

    return path is not None and load_robot_table(path) is not None


def _value(given: Any) -> Any:
    """An option's value as the design takes it: a list of numbers becomes a tuple."""
    return tuple(given) if isinstance(given, list) else given


def study_total(args: argparse.Namespace, design: HexapodDesign) -> float:
    """Total leg length [m]: ``--total``, else the ``--design`` file's, else the default."""
    if args.total is not None:
        return float(args.total)
    return design.leg_length if getattr(args, "design", None) else DEFAULT_LEG_LENGTH


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
