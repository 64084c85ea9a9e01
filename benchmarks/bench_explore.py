"""Workload of the explorer: one design's every number, against the commands that print them."""

from __future__ import annotations

import contextlib
import io
import itertools
import json
import statistics
import tempfile
import time
import warnings
from collections.abc import Sequence
from pathlib import Path

import tomli_w
from harness import Row, check_agree

from hexaleg import HexapodDesign
from hexaleg.cli import main
from hexaleg.evaluation.evaluate import Conditions
from hexaleg.evaluation.requirements import Requirements
from hexaleg.explore.answer import answer
from hexaleg.gait.spec import Gait
from hexaleg.robot.imported import import_robot
from hexaleg.robot.imported_model import ImportedHexapodModel

KRABY = Path(__file__).parents[1] / "tests" / "data" / "robots" / "kraby" / "hexapod.urdf"
"""A real public hexapod (MIT), small: 49, 60, 88 mm segments."""
KRABY_GAIT = Gait(stride=0.03, step_height=0.02, period=0.8, samples=60)
"""A gait Kraby walks (the default gait is sized for hexaleg's robot)."""


def _commands(design: HexapodDesign, robot: Sequence[str] = ()) -> dict[str, float]:
    """The explorer's numbers from the command line's --json, run in this process.

    ``robot``: the options naming an imported robot (and the file of its gait).
    """
    lengths = ["--l1", str(design.l1), "--l2", str(design.l2), "--l3", str(design.l3)]

    def run(*argv: str) -> dict:
        out = io.StringIO()
        with contextlib.redirect_stdout(out), warnings.catch_warnings():
            warnings.simplefilter("ignore")  # a robot file's placeholder masses, said once
            assert main([*argv, *robot, *lengths, "--json"]) == 0
        return json.loads(out.getvalue())

    flexibility, loads, gait = run("flexibility"), run("loads"), run("gait")
    workspace, manipulability = run("workspace", "--samples", "1"), run("manipulability")
    if robot:  # per leg: every leg of a robot changed alike is the same
        workspace = next(iter(workspace["legs"].values()))
        manipulability = next(iter(manipulability["legs"].values()))
    return {
        "fb": flexibility["fb"],
        "improved_area": workspace["area"]["improved_closed_form"],
        "average_manipulability": manipulability["average"]["improved"],
        "payload_capacity": loads["payload_capacity"]["mass"],
        "walking_payload_capacity": loads["walking_payload_capacity"]["mass"],
        "max_speed": gait["max_speed"]["value"],
        **{f"peak_torque.{j}": v for j, v in gait["peak_torque"].items()},
    }


def _explored(design: HexapodDesign, robot: ImportedHexapodModel | None = None) -> dict[str, float]:
    if robot is None:
        got = answer(design, Conditions(), Requirements())
    else:
        model = robot.with_design(design)
        got = answer(model.design, Conditions(gait=KRABY_GAIT), Requirements(), model)
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


def bench_explore_robot(designs: int, repeats: int) -> list[Row]:
    """The explorer's answer for an imported robot (Kraby) at different tibias.

    Each design's model is the robot file resized and read again (nothing reused between
    designs), against the five commands run with ``--urdf`` on the same lengths.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        robot = ImportedHexapodModel(import_robot(KRABY))
    base = robot.design
    cycle = [base.replace(l3=0.08 + 0.02 * k / max(designs - 1, 1)) for k in range(designs)]
    with tempfile.TemporaryDirectory() as folder:
        gait = Path(folder) / "gait.toml"
        gait.write_text(
            tomli_w.dumps(
                {
                    "gait": {
                        k: getattr(KRABY_GAIT, k)
                        for k in ("stride", "step_height", "period", "samples")
                    }
                }
            )
        )
        options = ["--urdf", str(KRABY), "--design", str(gait)]
        for design in cycle[:3]:
            expected, got = _commands(design, options), _explored(design, robot)
            difference = check_agree(
                "explore vs commands (robot)", [expected[k] for k in expected],
                [got[k] for k in expected], 1e-9 * max(abs(v) for v in expected.values()),
            )  # fmt: skip
        explore_s = _median(lambda d: _explored(d, robot), cycle, repeats)
        commands_s = _median(lambda d: _commands(d, options), cycle, max(3, repeats // 3))
    name = f"explorer: Kraby's numbers ({designs} tibias, 80..100 mm; --urdf)"
    return [
        Row(name, "hexaleg explore --urdf, /api/evaluate's answer", explore_s, None, None,
            "≤ 100 ms", note="file resized and read again, model, every metric, stance"),
        Row(name, "the five commands' --json --urdf, in-process", commands_s,
            commands_s / explore_s, difference, note="each reads and resizes the file"),
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
