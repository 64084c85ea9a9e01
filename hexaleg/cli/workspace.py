"""``hexaleg workspace``: the swing-phase workspace of one leg (paper §4)."""

from __future__ import annotations

import argparse

from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import UsageError, add_design_options, add_output_options, bounded_int
from hexaleg.cli.output import (
    check_outputs,
    lengths_title,
    print_json,
    print_table,
    vector,
    write_plots,
)
from hexaleg.output.figures import write_workspace_figures
from hexaleg.swing.workspace import MAX_SAMPLES, MAX_SEED, analyze_workspace

DESCRIPTION = (
    "Workspace of one leg (paper §4): Monte Carlo cloud in the Table 2 limits, planar "
    "workspace areas on the rectangular (Table 3) and improved (Table 4) domains, and "
    "eq 16's closed form. Areas in m², positions in m (leg-root frame). With --urdf, each "
    "leg of your robot (its general leg: offsets, bends and all)."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser, body=False, posture=False)  # one leg: no body, no stance
    parser.add_argument(
        "--samples",
        type=bounded_int(1, MAX_SAMPLES),
        default=20_000,
        help=f"Monte Carlo samples, 1..{MAX_SAMPLES} (default 20000)",
    )
    parser.add_argument(
        "--seed",
        type=bounded_int(0, MAX_SEED),
        default=0,
        help=f"random seed, 0..{MAX_SEED} (default 0)",
    )
    add_output_options(parser)


def run(args: argparse.Namespace) -> int:
    """Analyse the workspace; print a table or JSON, and write figures if asked."""
    robot = inputs_from_args(args).robot
    design, legs = robot.design, robot.own_legs
    if legs is not None:  # legs of their own: each measured by its general leg
        refuse_plot(args.plot)
        summaries = {
            name: analyze_workspace(design, args.samples, args.seed, leg=leg).to_dict(design=False)
            for name, leg in legs.items()
        }
        if args.json:
            print_json({"robot": robot.name, "legs": summaries})
        for name, leg in legs.items():
            if not args.json:
                _print(summaries[name], f"leg {name}", leg.lengths)
        return 0
    check_outputs({}, {"--plot": args.plot})  # before computing
    analysis = analyze_workspace(design, samples=args.samples, seed=args.seed)
    if args.plot is not None:
        write_plots(args.plot, lambda out: write_workspace_figures(analysis, out))
    summary = analysis.to_dict()
    if args.json:
        print_json(summary)
        return 0
    _print(summary, "", design.lengths)
    return 0


def refuse_plot(plot: str | None) -> None:
    """Refuse ``--plot`` for a robot whose legs are its own: the figures draw the design's."""
    if plot is not None:
        raise UsageError(
            "--plot with --urdf is not supported yet: the figures draw the design's leg, your "
            "robot's legs are each measured on their own (use --json)"
        )


def _print(summary: dict, leg: str, lengths: tuple[float, float, float]) -> None:
    area = summary["area"]
    mc = summary["monte_carlo"]
    title = "Swing-phase workspace" + (f" of {leg}" if leg else "")
    print_table(
        lengths_title(title, lengths),
        [
            ("planar area, rectangular domain (Table 3)", f"{area['rectangular']:.6f} m²"),
            ("planar area, improved domain (Table 4)", f"{area['improved']:.6f} m²"),
            (
                "improved area, closed form 2π·l2·l3/3 (eq 16)",
                f"{area['improved_closed_form']:.6f} m²",
            ),
            (f"Monte Carlo box min ({mc['samples']} samples)", vector(mc["lower_bound"], "m")),
            ("Monte Carlo box max", vector(mc["upper_bound"], "m")),
        ],
    )
