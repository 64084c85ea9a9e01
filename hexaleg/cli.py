"""Command-line interface: ``hexaleg <command> [design options]``.

Every command takes the same design options (see ``hexaleg urdf --help``);
lengths are in metres and angles in radians. User mistakes end with one line
on stderr and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from typing import Any, NoReturn

from hexaleg._version import __version__
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError

EXIT_USAGE = 2

_DESIGN_HELP = "design (SI units: metres, radians; defaults: the paper's leg on hexaleg's body)"


class _Parser(argparse.ArgumentParser):
    """argparse that reports a usage mistake in one line, without the usage block."""

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def add_design_options(parser: argparse.ArgumentParser) -> None:
    """Add the design options shared by every command."""
    default = HexapodDesign()
    group = parser.add_argument_group(_DESIGN_HELP)
    group.add_argument(
        "--l1", type=float, metavar="M", help=f"coxa length [m] (default {default.l1:g})"
    )
    group.add_argument(
        "--l2", type=float, metavar="M", help=f"femur length [m] (default {default.l2:g})"
    )
    group.add_argument(
        "--l3", type=float, metavar="M", help=f"tibia length [m] (default {default.l3:g})"
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
        help="total leg length l1+l2+l3 for --ratios [m] (default 1.0)",
    )
    for axis, name in (("x", "body_length"), ("y", "body_width"), ("z", "body_height")):
        group.add_argument(
            f"--{name.replace('_', '-')}",
            type=float,
            metavar="M",
            help=f"body extent along {axis} [m] (default {getattr(default, name):g})",
        )
    group.add_argument(
        "--nominal-angles",
        type=float,
        nargs=3,
        metavar=("T1", "T2", "T3"),
        help="standing joint angles θ1 θ2 θ3 of every leg [rad] (default "
        + " ".join(f"{a:.4g}" for a in default.nominal_angles)
        + ")",
    )


def design_from_args(args: argparse.Namespace) -> HexapodDesign:
    """Build the design the shared options describe (validated)."""
    fields: dict[str, Any] = {}
    for name in ("body_length", "body_width", "body_height"):
        if getattr(args, name) is not None:
            fields[name] = getattr(args, name)
    if args.nominal_angles is not None:
        fields["nominal_angles"] = tuple(args.nominal_angles)
    if args.ratios is not None:
        given = [f"--{n}" for n in ("l1", "l2", "l3") if getattr(args, n) is not None]
        if given:
            raise _UsageError(f"--ratios cannot be combined with {', '.join(given)}")
        total = 1.0 if args.total is None else args.total
        return HexapodDesign.from_ratios(args.ratios[0], args.ratios[1], total, **fields)
    if args.total is not None:
        raise _UsageError("--total only applies together with --ratios")
    for name in ("l1", "l2", "l3"):
        if getattr(args, name) is not None:
            fields[name] = getattr(args, name)
    return HexapodDesign(**fields)


class _UsageError(HexalegError):
    """A combination of command-line options that does not make sense."""


# -- commands -------------------------------------------------------------------------


def _cmd_urdf(args: argparse.Namespace) -> int:
    from hexaleg.urdf import render_hexapod, write_urdf

    design = design_from_args(args)
    if args.output is None or args.output == "-":
        sys.stdout.write(render_hexapod(design))
    else:
        path = write_urdf(design, args.output)
        print(f"wrote {path}", file=sys.stderr)
    return 0


Command = Callable[[argparse.Namespace], int]


def build_parser() -> argparse.ArgumentParser:
    """The ``hexaleg`` argument parser with all its subcommands."""
    parser = _Parser(
        prog="hexaleg",
        description=(
            "Choose the segment lengths of a hexapod's legs: URDF, workspace, manipulability "
            "and body flexibility. All inputs and outputs use SI units (m, kg) and radians."
        ),
    )
    parser.add_argument("--version", action="version", version=f"hexaleg {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    commands.required = True

    urdf = commands.add_parser(
        "urdf",
        help="write the hexapod's URDF for a design",
        description=(
            "Render the hexapod URDF from the Xacro templates for the given design. Joint "
            "values of the URDF are the paper's θ1, θ2, θ3 [rad]; lengths are in metres."
        ),
    )
    add_design_options(urdf)
    urdf.add_argument(
        "-o", "--output", metavar="FILE", help="write here (atomically) instead of stdout"
    )
    urdf.set_defaults(handler=_cmd_urdf)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``hexaleg`` command line; return the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    handler: Command = args.handler
    try:
        return handler(args)
    except HexalegError as err:
        print(f"hexaleg {args.command}: error: {err}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print(f"hexaleg {args.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
