"""``hexaleg manipulability``: optimum pose (Table 6) and average w_A (eq 27) of one leg."""

from __future__ import annotations

import argparse
import math

from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import add_design_options, add_output_options
from hexaleg.cli.output import check_outputs, lengths_title, print_json, print_table, write_plots
from hexaleg.cli.workspace import refuse_plot
from hexaleg.design import l3_ratio_grid
from hexaleg.output.figures import write_manipulability_figures
from hexaleg.paper import L1_RATIOS
from hexaleg.swing.manipulability import analyze_manipulability, average_manipulability_map

DESCRIPTION = (
    "Manipulability w = |det J| of one leg (paper §5): optimum pose within eq 26's limits, "
    "condition number and smallest singular value there, and the average w_A on the "
    "rectangular and improved domains. Angles in rad, w in m³. With --urdf, each leg of "
    "your robot (indices from its general leg's Jacobian)."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser, body=False, posture=False)  # one leg: no body, no stance
    add_output_options(parser)


def run(args: argparse.Namespace) -> int:
    """Analyse manipulability; print a table or JSON, and write figures if asked."""
    robot = inputs_from_args(args).robot
    design, legs = robot.design, robot.own_legs
    if legs is not None:  # legs of their own: each measured by its general leg
        refuse_plot(args.plot)
        summaries = {
            name: analyze_manipulability(design, general=leg).to_dict(design=False)
            for name, leg in legs.items()
        }
        if args.json:
            print_json({"robot": robot.name, "legs": summaries})
            return 0
        for name, leg in legs.items():
            _print(summaries[name], f"Manipulability of leg {name}", leg.lengths)
        return 0
    check_outputs({}, {"--plot": args.plot})  # before computing
    analysis = analyze_manipulability(design)
    if args.plot is not None:
        average_map = average_manipulability_map(
            L1_RATIOS, l3_ratio_grid(), design.leg_length, design.manipulability_limits
        )
        write_plots(args.plot, lambda out: write_manipulability_figures(analysis, average_map, out))
    summary = analysis.to_dict()
    if args.json:
        print_json(summary)
        return 0
    _print(summary, "Manipulability", design.lengths)
    return 0


def _print(summary: dict, title: str, lengths: tuple[float, float, float]) -> None:
    optimum, average = summary["optimum"], summary["average"]
    print_table(
        lengths_title(title, lengths),
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
