"""The ``hexaleg`` command line: parser, dispatch, and the one-line error contract.

Each command lives in its own module of this package with ``DESCRIPTION``,
``add_arguments(parser)`` and ``run(args) -> int``. :data:`COMMANDS` names them
with their one-line help, so ``hexaleg --help`` lists every command without
importing any analysis; only the command that runs is imported.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
import warnings
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple, NoReturn

from hexaleg._compiled import use_private_matplotlib_cache
from hexaleg._io import os_reason
from hexaleg._version import __version__
from hexaleg.exceptions import HexalegError, ParameterError

EXIT_USAGE = 2
"""Exit status of a user mistake (argparse's own convention)."""
EXIT_INTERRUPTED = 130


class Command(NamedTuple):
    """A subcommand: its name, the module that implements it, and its one-line help."""

    name: str
    module: str
    help: str


COMMANDS: tuple[Command, ...] = (
    Command(
        "design",
        "hexaleg.cli.design",
        "start a TOML design file, or show the design it and the options resolve to",
    ),
    Command("urdf", "hexaleg.cli.urdf", "write the hexapod's URDF for a design"),
    Command(
        "actuators", "hexaleg.cli.actuators", "the actuator catalog: datasheet numbers, sources"
    ),
    Command(
        "materials",
        "hexaleg.cli.materials",
        "the materials catalog of the legs' tubes: density, stiffness, strength, sources",
    ),
    Command(
        "workspace",
        "hexaleg.cli.workspace",
        "swing-phase workspace: Monte Carlo cloud, planar and improved areas",
    ),
    Command(
        "manipulability",
        "hexaleg.cli.manipulability",
        "manipulability: optimum pose (Table 6) and average w_A (eq 27)",
    ),
    Command(
        "flexibility",
        "hexaleg.cli.flexibility",
        "body flexibility with the feet planted: the 12 extremes, ranges and FB",
    ),
    Command(
        "loads",
        "hexaleg.cli.loads",
        "statics: foot forces, joint torques, stability, slopes and payload capacity",
    ),
    Command(
        "gait",
        "hexaleg.cli.gait",
        "walking: torques, joint speeds, power and energy of a gait period; max stride and speed",
    ),
    Command(
        "posture",
        "hexaleg.cli.posture",
        "the best nominal posture of your lengths for an objective, meeting the requirements",
    ),
    Command(
        "simulate",
        "hexaleg.cli.simulate",
        "the planned gait walked in MuJoCo, and the tripod statics checked (the [sim] extra)",
    ),
    Command(
        "decide",
        "hexaleg.cli.decide",
        "requirements in, design out: the best leg meeting payload, slope, clearance, ...",
    ),
    Command(
        "study",
        "hexaleg.cli.study",
        "design study: FB over coxa x tibia ratios (Fig 14-15), resumable",
    ),
    Command(
        "view",
        "hexaleg.cli.view",
        "3-D viewer of the nominal stance and the 12 body extremes (meshcat)",
    ),
    Command(
        "explore",
        "hexaleg.cli.explore",
        "live design explorer: sliders re-measure the design in the browser (loopback)",
    ),
    Command(
        "report",
        "hexaleg.cli.report",
        "the main job: every analysis, figure and table, and a recommendation",
    ),
)


class Parser(argparse.ArgumentParser):
    """argparse that reports a usage mistake in one line, without the usage block.

    Abbreviations are off: ``study --l1 0.2`` must not quietly mean ``--l1-ratios 0.2``.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)

    def error(self, message: str) -> NoReturn:
        """Exit with status 2 and one line naming the mistake."""
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The ``hexaleg`` parser; with ``only``, just that command's module is imported."""
    parser = Parser(
        prog="hexaleg",
        description=(
            "Choose the segment lengths of a hexapod's legs: URDF, workspace, manipulability "
            "and body flexibility. All inputs and outputs use SI units (m, kg) and radians."
        ),
    )
    parser.add_argument("--version", action="version", version=f"hexaleg {__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    commands.required = True
    for command in COMMANDS:
        sub = commands.add_parser(command.name, help=command.help)
        if only is None or command.name == only:
            module = importlib.import_module(command.module)
            sub.description = module.DESCRIPTION
            module.add_arguments(sub)
            sub.set_defaults(run=module.run)
    return parser


def _chosen_command(argv: Sequence[str]) -> str | None:
    names = {c.name for c in COMMANDS}
    first = next((arg for arg in argv if not arg.startswith("-")), None)
    return first if first in names else None


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``hexaleg`` command line; return the exit status."""
    argv = list(sys.argv[1:] if argv is None else argv)
    command = _chosen_command(argv)
    args = build_parser(command or "").parse_args(argv)
    use_private_matplotlib_cache()  # before any command imports Matplotlib
    try:
        with warnings.catch_warnings():  # a warning is one line, not a source line
            warnings.formatwarning = _one_line_warning(args.command)
            status = int(args.run(args))
        _flush_stdout()
        return status
    except HexalegError as err:
        return _fail(args.command, _as_typed(err, argv))
    except KeyboardInterrupt:
        print(f"hexaleg {args.command}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except BrokenPipeError:  # stdout closed early, as by `| head`: not a failure to report
        _drop_stdout()
        return 0
    except OSError as err:  # the system refused: a full disk, a closed stream, a lost mount
        where = f" ({err.filename})" if err.filename else ""
        return _fail(args.command, f"{os_reason(err)}{where}")


def _one_line_warning(command: str) -> Callable[..., str]:
    """A :func:`warnings.formatwarning` of one line: ``hexaleg COMMAND: warning: MESSAGE``.

    Warnings recorded rather than shown (as by a test's ``pytest.warns``) are untouched.
    """

    def line(message: Warning | str, *_: object, **__: object) -> str:
        return f"hexaleg {command}: warning: {message}\n"

    return line


def _as_typed(err: HexalegError, argv: Sequence[str]) -> str:
    """The error's line, naming the option the user typed (``--leg-length``) for its field."""
    if isinstance(err, ParameterError):
        option = "--" + err.field.replace("_", "-")
        if any(arg == option or arg.startswith(option + "=") for arg in argv):
            return str(ParameterError(option, err.value, err.allowed))
    return str(err)


def _fail(command: str, message: str) -> int:
    """One line on stderr; what stdout still holds is written, or dropped if it cannot be."""
    try:
        _flush_stdout()
    except OSError:
        _drop_stdout()
    print(f"hexaleg {command}: error: {message}", file=sys.stderr)
    return EXIT_USAGE


def _flush_stdout() -> None:
    """Flush stdout here, where a failure (``> /dev/full``) can still be one line."""
    if sys.stdout is not None:
        try:
            sys.stdout.flush()
        except OSError as err:
            if isinstance(err, BrokenPipeError):
                raise
            raise HexalegError(f"cannot write to standard output: {os_reason(err)}") from None


def _drop_stdout() -> None:
    """Point stdout at /dev/null, so that the interpreter's last flush cannot fail."""
    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except (OSError, AttributeError, ValueError):  # no stdout at all
        pass
