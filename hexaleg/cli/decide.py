"""``hexaleg decide``: requirements in, design out — the best leg that meets them, and yours."""

from __future__ import annotations

import argparse
import math
from concurrent.futures import Executor
from contextlib import AbstractContextManager

from hexaleg._checks import require_in_range
from hexaleg.actuator_catalog import shipped_catalog
from hexaleg.actuators import Actuator
from hexaleg.cli.inputs import inputs_from_args
from hexaleg.cli.options import (
    UsageError,
    add_design_options,
    bounded_int,
    capped_workers,
)
from hexaleg.cli.output import print_json
from hexaleg.cli.requirement_options import add_requirement_options, requirements_from_args
from hexaleg.evaluation.goal import Objective
from hexaleg.evaluation.metrics import objectives
from hexaleg.evaluation.requirements import RequirementCheck, format_margin
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.robot import SEGMENT_SPAN, Robot
from hexaleg.study.decide import CheckedDesign, DecideResult, decide
from hexaleg.study.decide_grid import ANGLE_STEP, DEFAULT_RESOLUTION, RESOLUTION_RANGE, Rounding
from hexaleg.study.decide_rows import AnswerRows, PostureRow, answer_rows, exact, value_text
from hexaleg.study.executors import dask_executor, local_pool
from hexaleg.study.optimize import (
    GENERATIONS,
    MAX_EVALUATIONS,
    MIN_POPULATION,
    POPULATION_PER_VARIABLE,
    SearchSettings,
)
from hexaleg.study.search_space import FREEABLE, GEARS, AtBound, FreeVariable

DESCRIPTION = (
    "Find the best leg for what the robot must do: of the designs meeting every requirement "
    "(payload at a point, a slope in every heading with that payload, ground clearance, "
    "least FB, leg length, least coxa, a tripod gait's speed within the motor ratings), the "
    "one with the best objective (default: the largest axis-locked FB), by pymoo's "
    "differential evolution over l1, l2, l3 (and the posture or body fields if freed), on a "
    "local process pool or a Dask cluster. The winner is measured again from its own URDF "
    "before it is printed, with each requirement's value, margin, whether it binds and what "
    "limits it, and every joint over its rating standing with the payload and walking; the "
    "--design is checked the same way. If nothing meets them all, it names the requirements "
    "that conflict and the nearest value of each that the others allow. With --urdf, your "
    "robot: its file with every leg's segments changed, each searched within "
    f"{SEGMENT_SPAN:.0%} of its own length (the robot as read is the start and 'your design')."
)

SHOWN_OVER_RATING = 4
"""Joints over their ratings a design's text lists, the furthest over first."""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add this command's options."""
    add_design_options(parser)
    add_requirement_options(parser)
    search = parser.add_argument_group("search")
    objective = search.add_mutually_exclusive_group()
    objective.add_argument(
        "--maximize", choices=objectives("maximize"), help="what to make largest (default fb)"
    )
    objective.add_argument(
        "--minimize", choices=objectives("minimize"), help="what to make smallest"
    )
    _add_answer_options(search)
    search.add_argument(
        "--free",
        action="append",
        default=[],
        metavar="FIELD=LOWER:UPPER",
        help="free one more field (repeatable), or bound l1/l2/l3: FIELD is one of "
        + ", ".join(FREEABLE)
        + " [m or rad]; a body field renders each design's URDF (~0.4 s a design)",
    )
    search.add_argument(
        "--choose-actuators",
        action="store_true",
        help="also choose each joint type's actuator from the catalog (hexaleg actuators), "
        "one categorical variable per joint type",
    )
    search.add_argument(
        "--free-gear-ratio",
        action="store_true",
        help="with --choose-actuators, also free each joint type's gear ratio within its "
        "chosen entry's gear_ratio_range (a datasheet's ratios: the Harmonic Drive CHA "
        "units); an entry without one keeps its ratio. The same motor at ratio N' = s·N: "
        "speed rating /s, armature ·s², peak and continuous torque ·min(s, 1)",
    )
    search.add_argument("--seed", type=bounded_int(0, 2**32 - 1), default=0, help="default 0")
    search.add_argument(
        "--evaluations",
        type=bounded_int(2 * MIN_POPULATION, MAX_EVALUATIONS),
        metavar="N",
        help="designs to evaluate per search: whole generations (at least two) of "
        f"{POPULATION_PER_VARIABLE} designs a free variable (at least {MIN_POPULATION}), "
        f"at most {MAX_EVALUATIONS} (default: {GENERATIONS} generations)",
    )
    search.add_argument(
        "--workers", type=bounded_int(1), metavar="N", help="local worker processes"
    )
    search.add_argument("--scheduler", metavar="ADDRESS", help="run on a Dask cluster")
    search.add_argument(
        "--journal", metavar="FILE", help="keep every evaluated design in FILE (JSON lines)"
    )
    search.add_argument("--resume", action="store_true", help="continue the --journal FILE")
    parser.add_argument("--json", action="store_true", help="print one JSON object")


def _add_answer_options(search: argparse._ArgumentGroup) -> None:
    """The posture freed or fixed, and the grid the answer is put on."""
    posture = search.add_mutually_exclusive_group()
    posture.add_argument(
        "--free-posture",
        action="store_true",
        help="free the nominal hip and knee angles (theta2, theta3) within the stance limits "
        "beside the lengths (the default, for hexaleg's legs)",
    )
    posture.add_argument(
        "--fixed-posture",
        action="store_true",
        help="keep the design's nominal angles: only the lengths (and --free fields) change",
    )
    search.add_argument(
        "--resolution",
        type=float,
        metavar="M",
        default=DEFAULT_RESOLUTION,
        help="the grid the answer's lengths are put on [m] (default 0.001: a millimetre; "
        f"within [{RESOLUTION_RANGE[0]:g}, {RESOLUTION_RANGE[1]:g}]); its angles are put on "
        f"{ANGLE_STEP:g} rad; that design is measured again and printed as measured",
    )


def run(args: argparse.Namespace) -> int:
    """Decide; print the answer as a table or JSON."""
    rounding = Rounding(require_in_range("--resolution", args.resolution, *RESOLUTION_RANGE, "m"))
    inputs = inputs_from_args(args)
    robot, in_file = inputs.robot, inputs.requirements  # in_file.walked: the robot's gait
    refuse_for_robot(args, robot)
    requirements = requirements_from_args(args, in_file)
    objective = (
        Objective(args.minimize, "minimize")
        if args.minimize
        else Objective(args.maximize)
        if args.maximize
        else Objective()
    )
    free = [FreeVariable.parse(text) for text in args.free]
    settings = SearchSettings(args.seed, args.evaluations)
    if args.resume and args.journal is None:
        raise UsageError("--resume continues a --journal FILE: give it")
    executor: AbstractContextManager[Executor] = (
        local_pool(capped_workers(args.workers))
        if args.scheduler is None
        else dask_executor(args.scheduler)
    )
    actuators, ranges = _catalog_actuators(args.choose_actuators, args.free_gear_ratio)
    with executor as pool:
        result = decide(
            robot,
            requirements,
            objective,
            free_posture=not args.fixed_posture,
            free=free,
            actuators=actuators,
            ratio_ranges=ranges,
            settings=settings,
            executor=pool,
            journal=args.journal,
            resume=args.resume,
            rounding=rounding,
        )
    if args.json:
        print_json(result.to_dict())
    else:
        print(render(result))
    return 0


def refuse_for_robot(args: argparse.Namespace, robot: Robot) -> None:
    """Refuse what would free more of the robot than a search may (a file's: its segments)."""
    for flag, field in (
        ("free_posture", "nominal_angles"),
        ("choose_actuators", "actuators"),
        ("free_gear_ratio", "actuators"),
    ):
        if getattr(args, flag, False) and not robot.searches(field):
            raise UsageError(
                f"--{flag.replace('_', '-')} with --urdf: an imported robot's posture, motors "
                "and masses are its file's; decide searches its segments"
            )


def _catalog_actuators(
    choose: bool, free_ratio: bool
) -> tuple[list[Actuator], list[tuple[float, float] | None] | None]:
    """The shipped catalog's actuators (``--choose-actuators``), and their ratio ranges."""
    if free_ratio and not choose:
        raise UsageError(
            "--free-gear-ratio frees the chosen actuators' ratios: add --choose-actuators"
        )
    if not choose:
        return [], None
    entries = list(shipped_catalog())
    ranges = [entry.gear_ratio_range for entry in entries] if free_ratio else None
    return [entry.actuator for entry in entries], ranges


def render(result: DecideResult) -> str:
    """The answer as text: the best design, yours, and the conflict if any."""
    free = ", ".join(f"{v.name} {v.lower:.4g}..{v.upper:.4g}" for v in result.variables)
    lines = [
        f"Decision: {result.objective.sense} {result.objective.spec.label} over {free}"
        + ("" if result.robot is None else f" of {result.robot}'s legs"),
        f"  search: {result.evaluations} designs, {result.method}, seed {result.seed}",
    ]
    if result.walks:
        lines.append(f"  walking: {result.walking_text()}")
    if result.rounded is not None:
        lines.append(f"  answer: {result.rounded.describe()}")
    lines.append("")
    verdict = "meets every requirement" if result.feasible else "LEAST INFEASIBLE: meets not all"
    answer = answer_rows(result)
    postures = answer.postures or (None, None)
    lines += _design_block("Best design", result.best, result, answer, verdict, postures[0])
    lines += _design_block("Your design", result.yours, result, answer, "", postures[1])
    if result.conflict is not None:
        lines += [f"No design meets every requirement: {result.conflict.description}."]
    return "\n".join(lines).rstrip()


def _design_block(
    title: str,
    checked: CheckedDesign,
    result: DecideResult,
    answer: AnswerRows,
    verdict: str,
    posture: PostureRow | None,
) -> list[str]:
    """One design: head line, posture, requirements, the bounds that bind, joints over ratings.

    The best design's rows say what binds, your design's what it passes; the bounds that
    bind are the best design's. Lengths and angles are printed exactly as measured.
    """
    binding = checked is result.best
    lengths = ", ".join(exact(v) for v in checked.design.lengths)
    head = f"{title}: l = ({lengths}) m"
    motors = checked.design.actuators
    if motors is not None:
        geared = any(v.name in GEARS for v in result.variables)
        names = (
            (a.catalog or "given") + (f" at N = {a.gear_ratio:.4g}" if geared else "")
            for a in motors.joints
        )
        head += " with " + ", ".join(f"{j} {n}" for j, n in zip(LEG_JOINTS, names, strict=True))
    if checked.design.battery is not None:
        head += f", battery {checked.design.battery.capacity:.4g} Wh"
    if checked.evaluation.error:
        return [head, f"  cannot be measured: {checked.evaluation.error}", ""]
    spec = result.objective.spec
    value = checked.evaluation.metrics.value(spec)
    unit = "" if spec.unit == "1" else f" {spec.unit}"
    head += f", {spec.label} = {value:.6g}{unit}" + (f" ({verdict})" if verdict else "")
    cause = checked.evaluation.causes[spec]
    above = [] if posture is None else [f"  {posture.text()}"]
    above += [] if cause is None else [f"  {spec.label} limited by {cause}"]
    rows = []
    for requirement in answer.requirements:
        check = requirement.best if binding else requirement.yours
        if check is not None:
            rows.append(_row(requirement.text, check, binding))
    if binding:
        rows += [_bound_row(bound.at) for bound in answer.bounds]
    width = [max((len(r[k]) for r in rows), default=0) for k in range(3)]
    lines = [head, *above]
    for row in rows:
        cells = "  ".join(cell.ljust(w) for cell, w in zip(row, width, strict=False))
        lines.append(f"  {cells}  {row[3]}".rstrip())
    return [*lines, *over_rating_lines(checked, result), ""]


def over_rating_lines(checked: CheckedDesign, result: DecideResult) -> list[str]:
    """Each joint over its rating standing (and walking), or that none is."""
    lines = []
    groups = checked.over_rating_groups(result)  # standing, then each walk (if walked)
    violations = ["", *(walk.violation for walk in checked.walks)][: len(groups)]
    for (where, flagged), violation in zip(groups, violations, strict=True):
        where += " (nominal stance and the 12 body extremes)" if where.startswith("stand") else ""
        if violation:
            lines.append(f"  {where}: cannot walk it, {violation}")
            continue
        if not flagged:
            lines.append(f"  over its rating {where}: no joint")
        for flag in flagged[:SHOWN_OVER_RATING]:
            lines.append(f"  OVER RATING {where}: {flag}")
        if len(flagged) > SHOWN_OVER_RATING:
            more = len(flagged) - SHOWN_OVER_RATING
            lines.append(f"  OVER RATING {where}: and {more} more, the worst above (--json: all)")
    return lines


def _bound_row(at: AtBound) -> tuple[str, ...]:
    """A free variable at its search bound, as a row beside the requirements that bind."""
    variable, unit = at.variable, at.variable.unit
    searched = f"{variable.name} searched in {variable.lower:.4g}..{variable.upper:.4g} {unit}"
    return searched, f"{at.value:.4g} {unit}", f"its {at.bound} bound", f"binds ({at.remedy})"


def _row(text: str, check: RequirementCheck, binding: bool) -> tuple[str, ...]:
    """A requirement checked on one design: the best (binds?) or yours (passes?)."""
    if binding:
        state = (
            "binds, at the limit"
            if check.at_limit
            else "binds"
            if check.binds
            else ("" if check.met else "NOT MET")
        )
    else:
        state = "pass" if check.met else "FAIL"
    if math.isnan(check.value):  # nothing to measure it on: no actuators, no battery
        return (text, value_text(check), "", state + " (not measured)")
    return (
        text,
        value_text(check),
        "margin " + format_margin(check),
        f"{state} (limited by {check.limited_by})",
    )
