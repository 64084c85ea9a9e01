"""Command-line interface: ``hexaleg <command> [design options]``.

Every command takes the same design options (see ``hexaleg urdf --help``);
lengths are in metres and angles in radians. User mistakes end with one line
on stderr and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, NoReturn

from hexaleg._version import __version__
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.paper import L1_RATIOS, L3_RATIO_POINTS
from hexaleg.report import ReportOptions

EXIT_USAGE = 2

_DESIGN_HELP = "design (SI units: metres, radians; defaults: the paper's leg on hexaleg's body)"


class _Parser(argparse.ArgumentParser):
    """argparse that reports a usage mistake in one line, without the usage block."""

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def _at_least(minimum: int, maximum: int | None = None) -> Callable[[str], int]:
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


def _cmd_workspace(args: argparse.Namespace) -> int:
    from hexaleg.workspace import analyze_workspace

    design = design_from_args(args)
    analysis = analyze_workspace(design, samples=args.samples, seed=args.seed)
    if args.plot is not None:
        from hexaleg.figures import write_workspace_figures

        _report_files(write_workspace_figures(analysis, args.plot))
    summary = analysis.to_dict()
    if args.json:
        _print_json(summary)
        return 0
    area = summary["area"]
    mc = summary["monte_carlo"]
    _print_table(
        f"Swing-phase workspace, l = ({design.l1:.4g}, {design.l2:.4g}, {design.l3:.4g}) m",
        [
            ("planar area, rectangular domain (Table 3)", f"{area['rectangular']:.6f} m²"),
            ("planar area, improved domain (Table 4)", f"{area['improved']:.6f} m²"),
            (
                "improved area, closed form 2π·l2·l3/3 (eq 16)",
                f"{area['improved_closed_form']:.6f} m²",
            ),
            (f"Monte Carlo box min ({mc['samples']} samples)", _vector(mc["lower_bound"], "m")),
            ("Monte Carlo box max", _vector(mc["upper_bound"], "m")),
        ],
    )
    return 0


def _cmd_manipulability(args: argparse.Namespace) -> int:
    from hexaleg.manipulability import analyze_manipulability

    design = design_from_args(args)
    analysis = analyze_manipulability(design)
    if args.plot is not None:
        from hexaleg.design import l3_ratio_grid
        from hexaleg.figures import write_manipulability_figures
        from hexaleg.manipulability import average_manipulability_map
        from hexaleg.paper import L1_RATIOS

        average_map = average_manipulability_map(
            L1_RATIOS, l3_ratio_grid(), design.leg_length, design.manipulability_limits
        )
        _report_files(write_manipulability_figures(analysis, average_map, args.plot))
    summary = analysis.to_dict()
    if args.json:
        _print_json(summary)
        return 0
    optimum, average = summary["optimum"], summary["average"]
    _print_table(
        f"Manipulability, l = ({design.l1:.4g}, {design.l2:.4g}, {design.l3:.4g}) m",
        [
            ("optimum θ2, θ3 (eq 25–26)", f"{optimum['theta2']:.6f}, {optimum['theta3']:.6f} rad"),
            (
                "",
                f"({math.degrees(optimum['theta2']):.4f}°, {math.degrees(optimum['theta3']):.4f}°)",
            ),
            ("optimum w = |det J|", f"{optimum['w']:.6g} m³"),
            ("condition number at optimum", f"{optimum['condition_number']:.4g}"),
            ("smallest singular value at optimum", f"{optimum['min_singular_value']:.4g} m/rad"),
            ("average w_A, rectangular domain (eq 27)", f"{average['rectangular']:.6g} m³"),
            ("average w_A, improved domain", f"{average['improved']:.6g} m³"),
        ],
    )
    return 0


def _cmd_flexibility(args: argparse.Namespace) -> int:
    import warnings

    from hexaleg.flexibility import FlexibilityWarning, flexibility

    design = design_from_args(args)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexibilityWarning)  # reported as "converged"
        result = flexibility(design, mode=args.mode, stance=args.stance)
    if args.plot is not None:
        from hexaleg.figures import extremes_figure, save

        _report_files([save(extremes_figure(result), Path(args.plot) / "flexibility_extremes.png")])
    if args.json:
        _print_json(result.to_dict())
        return 0
    rows = [("FB (eq 29)", f"{result.fb:.6f}")]
    for axis, value in result.ranges.items():
        unit = "m" if axis in ("x", "y", "z") else "rad"
        shown = f"{value:.6f} {unit}" + (f" ({math.degrees(value):.3f}°)" if unit == "rad" else "")
        rows.append((f"range {axis} (eq 28)", shown))
    for extreme in result.extremes:
        unit = "m" if extreme.axis in ("x", "y", "z") else "rad"
        rows.append(
            (
                f"{extreme.axis} {'+' if extreme.sign > 0 else '-'}",
                f"{extreme.value:+.6f} {unit}  limited by {extreme.limited_by}",
            )
        )
    if not result.converged:
        rows.append(
            ("warning", "the optimizer did not converge everywhere; values are lower bounds")
        )
    _print_table(
        f"Body flexibility ({result.mode}, stance {' '.join(result.legs)}), "
        f"l = ({design.l1:.4g}, {design.l2:.4g}, {design.l3:.4g}) m",
        rows,
    )
    return 0


def _cmd_study(args: argparse.Namespace) -> int:
    from hexaleg.design import l3_ratio_grid
    from hexaleg.figures import write_study_figures
    from hexaleg.study import StudySpec, peak_table, run_study, sensitivity_table

    given = [f"--{n}" for n in ("l1", "l2", "l3") if getattr(args, n) is not None]
    if given or args.ratios is not None:
        raise _UsageError(
            f"a study sweeps the segment lengths: {', '.join(given) or '--ratios'} cannot be given"
        )
    base = design_from_args(args)
    spec = StudySpec(
        tuple(args.l1_ratios),
        tuple(l3_ratio_grid(args.l3_points)),
        total=1.0 if args.total is None else args.total,
        mode=args.mode,
        stance=args.stance,
        base=base,
    )
    executor, client = _study_executor(args.scheduler)
    try:
        table = run_study(
            spec, args.output, executor=executor, workers=args.workers, resume=args.resume
        )
    finally:
        if client is not None:
            client.close()
    paths = [Path(args.output) / name for name in ("study.csv", "study.json")]
    paths += write_study_figures(table, args.output)
    if args.sensitivity:
        sensitivity = sensitivity_table(
            spec.l1_ratios, spec.l3_ratios, spec.total, spec.stance, base
        )
        from hexaleg._io import atomic_write_text

        paths.append(
            atomic_write_text(
                Path(args.output) / "sensitivity.csv", sensitivity.to_csv(index=False)
            )
        )
    _report_files(paths)
    failed = int((table["error"] != "").sum())
    print(f"{len(table)} designs, {failed} failed; FB peaks (l1 ratio → l3 ratio, FB):")
    for peak in peak_table(table).to_dict(orient="records"):
        print(f"  {peak['l1_ratio']:.3f} → {peak['peak_l3_ratio']:.4f}, {peak['peak_fb']:.4f}")
    return 0


def _study_executor(scheduler: str | None) -> tuple[Any, Any]:
    if scheduler is None:
        return None, None
    try:
        from distributed import Client
    except ImportError:
        raise _UsageError("--scheduler needs Dask: pip install 'hexaleg[dask]'") from None
    try:
        client = Client(scheduler, timeout="10s")
    except (OSError, TimeoutError) as err:
        raise _UsageError(f"cannot reach the Dask scheduler at {scheduler}: {err}") from None
    return client.get_executor(), client


def _cmd_view(args: argparse.Namespace) -> int:
    import signal
    import time

    from hexaleg.flexibility import axis_locked_flexibility
    from hexaleg.model import HexapodModel

    design = design_from_args(args)
    model = HexapodModel(design)
    result = axis_locked_flexibility(design, args.stance, model)
    if args.workspace is not None and args.workspace not in model.leg_names:
        raise _UsageError(
            f"--workspace = {args.workspace!r} is not valid: legs are {', '.join(model.leg_names)}"
        )
    from hexaleg import viewer as view

    if args.html is not None:
        path = view.write_static_html(model, result, args.html, args.workspace)
        print(f"wrote {path}", file=sys.stderr)
        return 0
    server = view.LoopbackServer(args.host, args.port)
    try:
        view.build_scene(view.client(server), model, result, args.workspace)
        print(f"hexaleg viewer: open {server.web_url}", flush=True)
        print("serving until Ctrl-C", file=sys.stderr, flush=True)
        for signum in (signal.SIGINT, signal.SIGTERM):  # Ctrl-C or kill: stop cleanly
            signal.signal(signum, signal.default_int_handler)
        while True:
            time.sleep(0.5)
    except KeyboardInterrupt:
        print("hexaleg viewer: stopped", file=sys.stderr)
        return 0
    finally:
        server.stop()


def _cmd_report(args: argparse.Namespace) -> int:
    from hexaleg.report import REPORT_HTML, REPORT_MD, ReportOptions, build_report

    design = design_from_args(args)
    options = ReportOptions(
        l3_points=args.l3_points,
        sensitivity_points=args.sensitivity_points,
        workers=args.workers,
    )
    data = build_report(args.output, design, options)
    out = Path(args.output)
    rec = data["recommendation"]
    print(f"wrote {out / REPORT_MD} and {out / REPORT_HTML}")
    print(
        f"recommended l1 : l2 : l3 = {rec['l1_ratio']:.2f} : {rec['l2_ratio']:.3f} : "
        f"{rec['l3_ratio']:.3f} (tibia ratio band "
        f"{rec['l3_band'][0]:.3f}-{rec['l3_band'][1]:.3f}); "
        f"this design: FB = {data['flexibility']['axis']['fb']:.4f}"
    )
    return 0


def _print_json(data: dict[str, Any]) -> None:
    print(json.dumps(data, indent=2, allow_nan=False))


def _print_table(title: str, rows: Sequence[tuple[str, str]]) -> None:
    width = max(len(name) for name, _ in rows)
    print(title)
    for name, value in rows:
        print(f"  {name:<{width}}  {value}")


def _vector(values: Sequence[float], unit: str) -> str:
    return "(" + ", ".join(f"{v:.4f}" for v in values) + f") {unit}"


def _report_files(paths: Sequence[Path]) -> None:
    for path in paths:
        print(f"wrote {path}", file=sys.stderr)


def _add_output_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--json", action="store_true", help="print one JSON object (SI units, radians)"
    )
    parser.add_argument("--plot", metavar="DIR", help="write the figures (PNG) into DIR")


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

    urdf = _add_command(
        commands,
        "urdf",
        _cmd_urdf,
        help="write the hexapod's URDF for a design",
        description=(
            "Render the hexapod URDF from the Xacro templates for the given design. Joint "
            "values of the URDF are the paper's θ1, θ2, θ3 [rad]; lengths are in metres."
        ),
    )
    urdf.add_argument(
        "-o", "--output", metavar="FILE", help="write here (atomically) instead of stdout"
    )

    workspace = _add_command(
        commands,
        "workspace",
        _cmd_workspace,
        help="swing-phase workspace: Monte Carlo cloud, planar and improved areas",
        description=(
            "Workspace of one leg (paper §4): Monte Carlo cloud in the Table 2 limits, planar "
            "workspace areas on the rectangular (Table 3) and improved (Table 4) domains, and "
            "eq 16's closed form. Areas in m², positions in m (leg-root frame)."
        ),
    )
    workspace.add_argument(
        "--samples", type=_at_least(1), default=20_000, help="Monte Carlo samples (default 20000)"
    )
    workspace.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    _add_output_options(workspace)

    manip = _add_command(
        commands,
        "manipulability",
        _cmd_manipulability,
        help="manipulability: optimum pose (Table 6) and average w_A (eq 27)",
        description=(
            "Manipulability w = |det J| of one leg (paper §5): optimum pose within eq 26's limits, "
            "condition number and smallest singular value there, and the average w_A on the "
            "rectangular and improved domains. Angles in rad, w in m³."
        ),
    )
    _add_output_options(manip)

    flex = _add_command(
        commands,
        "flexibility",
        _cmd_flexibility,
        help="body flexibility with the feet planted: the 12 extremes, ranges and FB",
        description=(
            "Body flexibility (paper §6): from the nominal stance the body moves along x, y, z "
            "[m] and rotates about them [rad], one coordinate at a time (--mode axis, the ADAMS "
            "semantics) or with the other five free (--mode free), until a foot leaves its "
            "reach, a joint hits its stance limit or the body touches the ground. Prints the "
            "12 extremes with their causes, the ranges (eq 28) and FB (eq 29)."
        ),
    )
    _add_stance_options(flex)
    _add_output_options(flex)

    study = _add_command(
        commands,
        "study",
        _cmd_study,
        help="design study: FB over coxa x tibia ratios (Fig 14-15), resumable",
        description=(
            "Sweep coxa and tibia ratios at a fixed total leg length and compute body "
            "flexibility for each design, one task per design, on a local process pool or a "
            "Dask cluster. Rows are written to DIR/rows.jsonl as they finish; --resume "
            "continues an interrupted study. Writes study.csv, study.json and the figures."
        ),
    )
    _add_stance_options(study)
    study.add_argument(
        "--l1-ratios",
        type=float,
        nargs="+",
        default=list(L1_RATIOS),
        metavar="R",
        help="coxa ratios l1/L [-] (default: the paper's "
        + " ".join(f"{r:.2f}" for r in L1_RATIOS)
        + ")",
    )
    _add_sweep_options(study, "hexaleg-study")
    study.add_argument(
        "--scheduler", metavar="ADDRESS", help="run on a Dask cluster, e.g. tcp://127.0.0.1:8786"
    )
    study.add_argument("--resume", action="store_true", help="continue the study already in DIR")
    study.add_argument(
        "--sensitivity", action="store_true", help="also write the posture/body sensitivity table"
    )
    _add_view_command(commands)

    report = _add_command(
        commands,
        "report",
        _cmd_report,
        help="the main job: every analysis, figure and table, and a recommendation",
        description=(
            "Run the workspace, manipulability and body-flexibility analyses on the design (the "
            "built-in default unless design options say otherwise) and the paper's sweeps, and "
            "write DIR/report.md, DIR/report.html, the figures (PNG), tables and raw data "
            "(CSV/JSON), the URDF and a static 3-D viewer. The folder is replaced only when the "
            "new report is complete."
        ),
    )
    _add_sweep_options(report, "hexaleg-report")
    report.add_argument(
        "--sensitivity-points",
        type=_at_least(2),
        default=ReportOptions.sensitivity_points,
        metavar="N",
        help="tibia ratios in the posture sensitivity table "
        f"(default {ReportOptions.sensitivity_points})",
    )
    return parser


def _add_sweep_options(parser: argparse.ArgumentParser, output: str) -> None:
    """Options of the commands that sweep designs: output folder, tibia ratios, workers."""
    parser.add_argument(
        "-o", "--output", metavar="DIR", default=output, help=f"output folder (default {output})"
    )
    parser.add_argument(
        "--l3-points",
        type=_at_least(2),
        default=L3_RATIO_POINTS,
        metavar="N",
        help=f"tibia ratios per coxa ratio (default {L3_RATIO_POINTS}, as the paper)",
    )
    parser.add_argument(
        "--workers", type=_at_least(1), metavar="N", help="local worker processes (default: CPUs)"
    )


def _add_command(
    commands: Any, name: str, handler: Command, help: str, description: str
) -> argparse.ArgumentParser:
    """A subcommand taking the shared design options, dispatched to ``handler``."""
    parser = commands.add_parser(name, help=help, description=description)
    add_design_options(parser)
    parser.set_defaults(handler=handler)
    return parser


def _add_view_command(commands: Any) -> None:
    view = _add_command(
        commands,
        "view",
        _cmd_view,
        help="3-D viewer of the nominal stance and the 12 body extremes (meshcat)",
        description=(
            "Serve a meshcat scene of the hexapod: ground, footholds, the nominal stance and the "
            "12 axis-locked extreme poses (scene tree: hexaleg/extremes/x+ ... yaw-, limiting "
            "link in red), with an animation of each from nominal to the extreme and back. "
            "Binds 127.0.0.1 unless --host says otherwise; Ctrl-C stops it. --html writes a "
            "self-contained snapshot instead of serving."
        ),
    )
    view.add_argument(
        "--stance", choices=("all", "tripod"), default="all", help="stance legs (default all six)"
    )
    view.add_argument("--host", default="127.0.0.1", help="interface to bind (default 127.0.0.1)")
    view.add_argument(
        "--port", type=_at_least(1, 65535), help="web port (default: the first free from 7000)"
    )
    view.add_argument("--html", metavar="FILE", help="write a static HTML snapshot and exit")
    view.add_argument("--workspace", metavar="LEG", help="also draw this leg's workspace cloud")


def _add_stance_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--mode",
        choices=("axis", "free"),
        default="axis",
        help="axis-locked (default) or free-coupled",
    )
    parser.add_argument(
        "--stance", choices=("all", "tripod"), default="all", help="stance legs (default all six)"
    )


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
