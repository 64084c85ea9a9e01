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
            f"total leg length l1+l2+l3 for --ratios [m] (default {DEFAULT_TOTAL:g})"
            if lengths
            else f"total leg length l1+l2+l3 of every swept design [m] (default {DEFAULT_TOTAL:g})"
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


def _add_body_options(group: argparse._ArgumentGroup, default: HexapodDesign) -> None:
    for axis, name in (("x", "body_length"), ("y", "body_width"), ("z", "body_height")):
        group.add_argument(
            f"--{name.replace('_', '-')}",
            type=float,
            metavar="M",
            help=f"body extent along {axis} [m] (default {getattr(default, name):g})",
        )


def design_from_args(args: argparse.Namespace) -> HexapodDesign:
    """Build the design the shared options describe (validated)."""
    fields: dict[str, Any] = {}
    for name in ("body_length", "body_width", "body_height"):
        if getattr(args, name, None) is not None:
            fields[name] = getattr(args, name)
    if getattr(args, "nominal_angles", None) is not None:
        fields["nominal_angles"] = tuple(args.nominal_angles)
    if getattr(args, "ratios", None) is not None:
        given = [f"--{n}" for n in ("l1", "l2", "l3") if getattr(args, n) is not None]
        if given:
            raise UsageError(f"--ratios cannot be combined with {', '.join(given)}")
        total = DEFAULT_TOTAL if args.total is None else args.total
        design = HexapodDesign.from_ratios(args.ratios[0], args.ratios[1], total, **fields)
        if args.total is None:  # said only once the design stands: an error stays one line
            note(f"--ratios without --total: total leg length {DEFAULT_TOTAL:g} m")
        return design
    if args.total is not None and hasattr(args, "ratios"):
        raise UsageError("--total only applies together with --ratios")
    for name in ("l1", "l2", "l3"):
        if getattr(args, name, None) is not None:
            fields[name] = getattr(args, name)
    return HexapodDesign(**fields)


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


def add_collisions_option(parser: argparse.ArgumentParser) -> None:
    """``--collisions``: the robot's own parts touching also stop the body."""
    parser.add_argument(
        "--collisions",
        action="store_true",
        help="also stop the body where two of the robot's own parts touch (coal; slower)",
    )
