"""``hexaleg study``: FB over coxa × tibia ratios (Fig 14–15), resumable, local or on Dask."""

from __future__ import annotations

import argparse
from concurrent.futures import Executor
from contextlib import AbstractContextManager
from pathlib import Path

from hexaleg._io import check_output_folder, write_text
from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import (
    UsageError,
    add_collisions_option,
    add_design_options,
    add_field_sweep_option,
    add_l1_ratios_option,
    add_mode_option,
    add_stance_option,
    add_sweep_options,
    capped_workers,
    field_sweep_from_args,
)
from hexaleg.cli.output import report_files
from hexaleg.design import l3_ratio_grid
from hexaleg.output.figures import write_study_figures
from hexaleg.paper import L1_RATIOS
from hexaleg.robot.robot import Robot
from hexaleg.study.executors import dask_executor, local_pool
from hexaleg.study.sensitivity import sensitivity_table
from hexaleg.study.sweep import (
    CHUNK,
    TABLE_CSV,
    TABLE_JSON,
    StudySpec,
    peak_table,
    run_study,
)

DESCRIPTION = (
    "Sweep coxa and tibia ratios at a fixed total leg length and compute body "
    "flexibility, statics and payload for each design, in tasks of "
    f"{CHUNK} axis-locked designs "
    "(one free-coupled design) on a local process pool or a Dask cluster. Rows are "
    "written to DIR/rows.jsonl as each task finishes; --resume "
    "continues an interrupted study. Writes study.csv, study.json and the figures. With "
    "--urdf, your robot: each row its file with every leg's segments at the row's lengths, "
    "at its own total leg length unless --total is given."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser, lengths=False)
    add_mode_option(parser)
    add_stance_option(parser)
    add_collisions_option(parser)
    add_l1_ratios_option(parser, "the paper's " + " ".join(f"{r:.2f}" for r in L1_RATIOS))
    add_sweep_options(parser, "hexaleg-study")
    parser.add_argument(
        "--scheduler", metavar="ADDRESS", help="run on a Dask cluster, e.g. tcp://127.0.0.1:8786"
    )
    parser.add_argument("--resume", action="store_true", help="continue the study already in DIR")
    parser.add_argument(
        "--sensitivity", action="store_true", help="also write the posture/body sensitivity table"
    )
    add_field_sweep_option(
        parser, "also write the sensitivity table (FB peak per value) over one body field"
    )


def run(args: argparse.Namespace) -> int:
    """Run (or resume) the study, write its table and figures, and print the FB peaks."""
    inputs = inputs_from_args(args)
    robot, in_file = inputs.robot, inputs.requirements  # in_file.walked: the robot's gait
    base = robot.design
    field_sweep = field_sweep_from_args(args)
    _refuse(args, robot, field_sweep is not None)
    check_output_folder(args.output)  # the study folder itself is checked as it is claimed
    spec = StudySpec(
        tuple(args.l1_ratios or L1_RATIOS),
        tuple(l3_ratio_grid(args.l3_points)),
        total=base.leg_length if args.total is None else args.total,
        mode=args.mode,
        stance=args.stance,
        base=base,
        collisions=args.collisions,
        walked=in_file.walked,
        robot=robot,
    )
    executor: AbstractContextManager[Executor] = (
        local_pool(capped_workers(args.workers))
        if args.scheduler is None
        else dask_executor(args.scheduler)
    )
    with executor as pool:
        table = run_study(spec, args.output, executor=pool, resume=args.resume)
    out = Path(args.output)
    paths = [out / TABLE_CSV, out / TABLE_JSON, *write_study_figures(table, out)]
    if args.sensitivity or field_sweep is not None:
        variants = None if field_sweep is None else field_sweep.variants()
        sensitivity = sensitivity_table(
            spec.l1_ratios, spec.l3_ratios, spec.total, spec.stance, base, variants
        )
        paths.append(write_text(out / "sensitivity.csv", sensitivity.to_csv(index=False)))
    report_files(paths)
    failed = int((table["error"] != "").sum())
    print(f"{len(table)} designs, {failed} failed; FB peaks (l1 ratio → l3 ratio, FB):")
    for peak in peak_table(table).to_dict(orient="records"):
        print(f"  {peak['l1_ratio']:.3f} → {peak['peak_l3_ratio']:.4f}, {peak['peak_fb']:.4f}")
    return 0


def _refuse(args: argparse.Namespace, robot: Robot, swept: bool) -> None:
    """Refuse what the robot cannot be studied for: its body varied, a coxa of 0 stretched."""
    if (args.sensitivity or swept) and not robot.body_sweepable:
        raise UsageError(
            "--sensitivity and --sweep with --urdf: they vary hexaleg's template body, "
            "not your robot's file"
        )
    if robot.fixed_coxa:
        raise UsageError(
            "--urdf: the robot's coxa is 0 m (its yaw and hip axes meet): a study of coxa "
            "ratios cannot stretch it; use decide --urdf, which keeps it"
        )
