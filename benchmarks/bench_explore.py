"""Workload of the explorer: one design's every number, against the commands that print them."""

from __future__ import annotations

import contextlib
import io
import itertools
import json
import statistics
import time

from harness import Row, check_agree

from hexaleg import HexapodDesign
from hexaleg.cli import main
from hexaleg.explore.answer import answer
from hexaleg.study.evaluation import Conditions
from hexaleg.study.requirements import Requirements


def _commands(design: HexapodDesign) -> dict[str, float]:
    """The explorer's numbers from the command line's --json, run in this process."""
    lengths = ["--l1", str(design.l1), "--l2", str(design.l2), "--l3", str(design.l3)]

    def run(*argv: str) -> dict:
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            assert main([*argv, *lengths, "--json"]) == 0
        return json.loads(out.getvalue())

    flexibility, loads, gait = run("flexibility"), run("loads"), run("gait")
    workspace, manipulability = run("workspace", "--samples", "1"), run("manipulability")
    return {
        "fb": flexibility["fb"],
        "improved_area": workspace["area"]["improved_closed_form"],
        "average_manipulability": manipulability["average"]["improved"],
        "payload_capacity": loads["payload_capacity"]["mass"],
        "walking_payload_capacity": loads["walking_payload_capacity"]["mass"],
        "max_speed": gait["max_speed"]["value"],
        **{f"peak_torque.{j}": v for j, v in gait["peak_torque"].items()},
    }


def _explored(design: HexapodDesign) -> dict[str, float]:
    got = answer(design, Conditions(), Requirements())
    names = ("fb", "improved_area", "average_manipulability", "payload_capacity",
             "walking_payload_capacity", "max_speed")  # fmt: skip
    flat = {k: got[k] for k in names}
    return flat | {f"peak_torque.{j}": v for j, v in got["peak_torque"].items()}


def bench_explore(designs: int, repeats: int) -> list[Row]:
    """The explorer's answer for designs of different tibias (nothing reused between them)."""
    base = HexapodDesign()
    cycle = [base.replace(l3=0.36 + 0.08 * k / max(designs - 1, 1)) for k in range(designs)]
    for design in cycle[:3]:
        expected, got = _commands(design), _explored(design)
        difference = check_agree(
            "explore vs commands", [expected[k] for k in expected], [got[k] for k in expected],
            1e-9 * max(abs(v) for v in expected.values()),
        )  # fmt: skip
    explore_s = _median(lambda d: answer(d, Conditions(), Requirements()), cycle, repeats)
    commands_s = _median(_commands, cycle, max(3, repeats // 3))
    name = f"explorer: one design's numbers ({designs} designs, l3 0.36..0.44 m)"
    return [
        Row(name, "hexaleg explore, /api/evaluate's answer", explore_s, None, None, "≤ 100 ms",
            note="model built, every metric, the stance's points"),
        Row(name, "the five commands' --json, in-process", commands_s, commands_s / explore_s,
            difference, note="flexibility, workspace, manipulability, loads, gait"),
    ]  # fmt: skip


def _median(fn, designs: list[HexapodDesign], repeats: int) -> float:
    """Median time of ``fn`` on a design, the designs taken in turn, after a warm-up."""
    for design in designs[:3]:
        fn(design)
    samples = []
    for design in itertools.islice(itertools.cycle(designs), repeats * len(designs)):
        start = time.perf_counter()
        fn(design)
        samples.append(time.perf_counter() - start)
    return statistics.median(samples)
