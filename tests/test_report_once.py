"""A report measures each design it shows once: every section reads that one measurement.

The oracle is a count: every evaluation (:func:`~hexaleg.evaluation.evaluate.evaluate`), every
walk of a gait (a :class:`~hexaleg.gait.walk.Walker` made) and every flexibility search (an
axis-locked :class:`~hexaleg.stance.extremes.FlexibilityResult` made, a free-coupled search
called) is counted by the design it measures, while a whole report is built with its tasks
run in this process (an executor that runs each task where it is submitted, so the study's
and the searches' designs are counted too). A design measured twice fails, whichever
sections asked for it.
"""

from __future__ import annotations

import contextlib
from collections import Counter
from collections.abc import Iterator
from concurrent.futures import Executor, Future
from pathlib import Path
from typing import Any

import pytest
from conftest import run_cli

from hexaleg import HexapodDesign
from hexaleg.evaluation import evaluate as evaluate_module
from hexaleg.gait.walk import Walker
from hexaleg.output.report import ReportOptions, build_report
from hexaleg.stance.extremes import FlexibilityResult
from hexaleg.stance.free_coupled import free_flexibility

REDUCED = ReportOptions(
    l3_points=10, sensitivity_points=4, workers=1, progress=False, vector_figures=False
)
KRABY = Path(__file__).parent / "data" / "robots" / "kraby" / "hexapod.urdf"
KRABY_GAIT = "[gait]\nstride = 0.03\nstep_height = 0.02\nperiod = 0.8\nsamples = 60\n"
"""A gait the small robot walks (the default gait's 10 cm step is beyond it)."""


class _HereExecutor(Executor):
    """Runs each task where it is submitted: every design is measured in this process."""

    def submit(self, fn: Any, /, *args: Any, **kwargs: Any) -> Future[Any]:
        future: Future[Any] = Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except BaseException as err:  # handed to the caller, as a pool does
            future.set_exception(err)
        return future


@contextlib.contextmanager
def _here(workers: int | None = None) -> Iterator[Executor]:
    yield _HereExecutor()


def _counted(monkeypatch) -> dict[str, Counter]:
    """Count evaluations, walks and flexibility searches by the design each measures."""
    counts: dict[str, Counter] = {"evaluate": Counter(), "walk": Counter(), "flex": Counter()}
    evaluation = evaluate_module._Measuring.evaluation

    def counted_evaluation(self, metrics):
        counts["evaluate"][self.design] += 1
        return evaluation(self, metrics)

    walker = Walker.__init__

    def counted_walker(self, model, gait, payload=None, *args, **kwargs):
        mass = None if payload is None else payload.mass
        counts["walk"][(model.design, gait, mass)] += 1
        walker(self, model, gait, payload, *args, **kwargs)

    flexibility = FlexibilityResult.__init__

    def counted_flexibility(self, design, legs, mode, *args, **kwargs):
        if mode == "axis":  # a free search makes its result, then a copy saying if it converged
            counts["flex"][(design, mode)] += 1
        flexibility(self, design, legs, mode, *args, **kwargs)

    def counted_free(design, *args, **kwargs):
        counts["flex"][(design, "free")] += 1
        return free_flexibility(design, *args, **kwargs)

    monkeypatch.setattr(evaluate_module._Measuring, "evaluation", counted_evaluation)
    monkeypatch.setattr(Walker, "__init__", counted_walker)
    monkeypatch.setattr(FlexibilityResult, "__init__", counted_flexibility)
    for user in ("hexaleg.output.report.flexibility", "hexaleg.evaluation.evaluate"):
        monkeypatch.setattr(f"{user}.free_flexibility", counted_free)
    for module in ("study", "recommendation", "robot"):
        monkeypatch.setattr(f"hexaleg.output.report.{module}.local_pool", _here)
    return counts


def _twice(counts: dict[str, Counter]) -> dict[str, list[Any]]:
    return {kind: [key for key, n in found.items() if n > 1] for kind, found in counts.items()}


@pytest.mark.slow  # a whole reduced report, its study and searches in this process
def test_the_default_report_measures_each_design_once(tmp_path, monkeypatch):
    counts = _counted(monkeypatch)
    build_report(tmp_path / "r", HexapodDesign(), REDUCED)
    assert _twice(counts) == {"evaluate": [], "walk": [], "flex": []}
    yours = HexapodDesign()
    assert counts["evaluate"][yours] == 1  # measured, once, for every section
    assert counts["flex"][(yours, "axis")] == 1 and counts["flex"][(yours, "free")] == 1
    assert len(counts["evaluate"]) > 100  # the searches' legs were counted too


@pytest.mark.slow  # a whole reduced report of a robot file
def test_the_robot_report_measures_each_design_once(tmp_path, monkeypatch, capsys):
    gait = tmp_path / "gait.toml"
    gait.write_text(KRABY_GAIT)
    counts = _counted(monkeypatch)
    argv = ["report", "--urdf", str(KRABY), "--design", str(gait), "--l1-ratios", "0.25",
            "--l3-points", "10", "--workers", "1", "-o",
            str(tmp_path / "r")]  # fmt: skip
    assert run_cli(argv) == 0, capsys.readouterr().err
    assert _twice(counts) == {"evaluate": [], "walk": [], "flex": []}
    assert len(counts["evaluate"]) >= 10  # the robot and its study's designs were counted
