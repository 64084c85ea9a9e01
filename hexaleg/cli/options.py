"""Options shared by several commands, declared once: design, sweep, stance and output."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from typing import Any

from hexaleg._typing import FlexibilityMode, StanceSet, choices
from hexaleg.design import MAX_L3_POINTS, HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.paper import L3_RATIO_POINTS
from hexaleg.study.executors import WORKERS_PER_CPU, max_workers
from hexaleg.study.sweep import MAX_L1_RATIOS

DEFAULT_TOTAL = 1.0
"""Total leg length [m] of ``--ratios`` when ``--total`` is not given (the paper's 1000 mm)."""

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

    Args:
        parser: The command's parser.
        lengths: Segment lengths (``--l1 --l2 --l3`` or ``--ratios``); without them,
            ``--total`` is the swept designs' leg length.
        body: Body size (``--body-length`` ...): what the stance and the robot depend on.
        posture: The nominal joint angles (``--nominal-angles``).

    """
    default = HexapodDesign()
    group = parser.add_argument_group(DESIGN_GROUP)
    group.add_argument(
        "--design",
        metavar="FILE",
        help="read the design from a TOML design file (hexaleg design init) or a .json "
        "design printed by hexaleg; the options below override its values",
    )
    if lengths:
        for name, what in (("l1", "coxa"), ("l2", "femur"), ("l3", "tibia")):
            group.add_argument(
                f"--{name}",
                type=float,
                metavar="M",
                help=f"{what} length [m] (default {getattr(default, name):g})",
            )
        group.add_argument(
            "--ratios",
            type=float,
            nargs=2,
            metavar=("L1", "L3"),
            help="coxa and tibia as fractions of --total, instead of --l1/--l2/--l3 [-]",
        )
    group.add_argument(
        "--total",
        type=float,
        metavar="M",
        help=(
            f"total leg length l1+l2+l3 for --ratios [m] (default: the --design file's, "
            f"else {DEFAULT_TOTAL:g})"
            if lengths
            else f"total leg length l1+l2+l3 of every swept design [m] (default: the --design "
            f"file's, else {DEFAULT_TOTAL:g})"
        ),
    )
    if body:
        _add_body_options(group, default)
    if posture:
        group.add_argument(
            "--nominal-angles",
            type=float,
            nargs=3,
            metavar=("T1", "T2", "T3"),
            help="standing joint angles θ1 θ2 θ3 of every leg [rad] (default "
            + " ".join(f"{a:.4g}" for a in default.nominal_angles)
            + ")",
        )


LAYOUT_OPTIONS: tuple[tuple[str, str], ...] = (
    ("body_radius", "hexagon: leg roots' radius and the round body's [m]"),
    ("first_leg_angle", "hexagon: left front leg's direction from straight ahead, 0..π/3 [rad]"),
    ("middle_leg_offset", "rectangle: middle legs this much wider than the body [m]"),
    ("front_yaw", "rectangle: left front coxa direction, the right one mirrored [rad]"),
    ("rear_yaw", "rectangle: left rear coxa direction, the right one mirrored [rad]"),
)
"""The layout's number-valued options: design field and help."""


def _add_body_options(group: argparse._ArgumentGroup, default: HexapodDesign) -> None:
    for axis, name in (("x", "body_length"), ("y", "body_width"), ("z", "body_height")):
        group.add_argument(
            f"--{name.replace('_', '-')}",
            type=float,
            metavar="M",
            help=f"body extent along {axis} [m] (default {getattr(default, name):g})",
        )
    group.add_argument(
        "--layout",
        choices=("rectangle", "hexagon"),
        help="legs on a rectangular body's corners and sides (default), or every 60° "
        "around a round one (custom mounts: in a --design file)",
    )
    for name, what in LAYOUT_OPTIONS:
        unit = "RAD" if "[rad]" in what else "M"
        group.add_argument(
            f"--{name.replace('_', '-')}",
            type=float,
            metavar=unit,
            help=f"{what} (default {getattr(default, name):.4g})",
        )


DESIGN_FLAGS: tuple[str, ...] = (
    "body_length",
    "body_width",
    "body_height",
    "layout",
    *(name for name, _ in LAYOUT_OPTIONS),
)
"""Design fields set by an option of the same name."""


def design_from_args(args: argparse.Namespace) -> HexapodDesign:
    """Build the design the shared options describe (validated).

    A ``--design`` file gives the starting design (it must be valid on its own); the
    options given beside it override its values.
    """
    from hexaleg.design_file import load_design  # reads TOML only when asked

    path = getattr(args, "design", None)
    base = HexapodDesign() if path is None else load_design(path)
    changes: dict[str, Any] = {
        name: getattr(args, name) for name in DESIGN_FLAGS if getattr(args, name, None) is not None
    }
    if getattr(args, "nominal_angles", None) is not None:
        changes["nominal_angles"] = tuple(args.nominal_angles)
    if getattr(args, "ratios", None) is not None:
        given = [f"--{n}" for n in ("l1", "l2", "l3") if getattr(args, n) is not None]
        if given:
            raise UsageError(f"--ratios cannot be combined with {', '.join(given)}")
        total = study_total(args, base)
        design = base.replace(**changes).with_ratios(args.ratios[0], args.ratios[1], total)
        if args.total is None and path is None:  # said once the design stands: errors stay 1 line
            note(f"--ratios without --total: total leg length {DEFAULT_TOTAL:g} m")
        return design
    if args.total is not None and hasattr(args, "ratios"):
        raise UsageError("--total only applies together with --ratios")
    for name in ("l1", "l2", "l3"):
        if getattr(args, name, None) is not None:
            changes[name] = getattr(args, name)
    return base.replace(**changes) if changes else base


def study_total(args: argparse.Namespace, design: HexapodDesign) -> float:
    """Total leg length [m]: ``--total``, else the ``--design`` file's, else the default."""
    if args.total is not None:
        return float(args.total)
    return design.leg_length if getattr(args, "design", None) else DEFAULT_TOTAL


def add_sweep_options(parser: argparse.ArgumentParser, output: str) -> None:
    """Options of the commands that sweep designs: output folder, tibia ratios, workers."""
    parser.add_argument(
        "-o", "--output", metavar="DIR", default=output, help=f"output folder (default {output})"
    )
    parser.add_argument(
        "--l3-points",
        type=bounded_int(2, MAX_L3_POINTS),
        default=L3_RATIO_POINTS,
        metavar="N",
        help=f"tibia ratios per coxa ratio, 2..{MAX_L3_POINTS} "
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
