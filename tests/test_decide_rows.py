"""The decide answer's rows: built once, laid out by the command line and by the report."""

from __future__ import annotations

import math

import pytest

from hexaleg import HexapodDesign
from hexaleg.cli.decide import render
from hexaleg.evaluation.evaluate import Evaluation
from hexaleg.evaluation.goal import Objective
from hexaleg.evaluation.metrics import Causes, Metrics
from hexaleg.evaluation.requirements import Requirements, check
from hexaleg.output.report.requirements import requirement_blocks
from hexaleg.study.decide import CheckedDesign, DecideResult
from hexaleg.study.decide_rows import answer_rows, value_text
from hexaleg.study.search_space import FreeVariable

REQUIRED = Requirements(payload=30.0, ground_clearance=0.3, leg_length=1.0, continuous_margin=0.8)
"""Four requirements: two at least, one at most, one measured on neither design (no motors)."""


def _checked(design: HexapodDesign, payload: float, clearance: float) -> CheckedDesign:
    """A design measured by hand: its payload capacity and clearance [kg, m], no motors."""
    metrics = Metrics(
        payload_capacity=payload,
        ground_clearance=clearance,
        leg_length=design.leg_length,
        continuous_load=math.nan,
    )
    evaluation = Evaluation(metrics=metrics)
    return CheckedDesign(design, evaluation, check(REQUIRED, metrics, Causes()))


def _result() -> DecideResult:
    best = HexapodDesign(l1=0.1, l2=0.45, l3=0.45)  # l1 at the lower bound searched
    return DecideResult(
        requirements=REQUIRED,
        objective=Objective(),
        variables=(FreeVariable("l1", 0.1, 0.4), FreeVariable("l3", 0.2, 0.6)),
        best=_checked(best, 30.2, 0.35),  # the payload binds: within 1 % of 30 kg
        yours=_checked(HexapodDesign(), 25.0, 0.35),  # too little payload
        feasible=False,
        conflict=None,
        method="by hand",
        evaluations=0,
        seed=0,
    )


def test_one_row_per_requirement_with_each_design_s_margin_by_its_definition():
    rows = answer_rows(_result())
    assert [row.best.name for row in rows.requirements if row.best] == [
        "payload", "ground_clearance", "leg_length", "continuous_margin"
    ]  # fmt: skip
    payload, clearance, leg, motors = rows.requirements
    # margins from the definitions: at least → value − required, at most → required − value
    assert payload.best is not None and payload.yours is not None
    assert payload.best.margin == pytest.approx(30.2 - 30.0) and payload.best.binds
    assert payload.yours.margin == pytest.approx(25.0 - 30.0) and not payload.yours.met
    assert clearance.best is not None and clearance.best.margin == pytest.approx(0.05)
    assert leg.yours is not None and leg.yours.margin == pytest.approx(1.0 - 1.0, abs=1e-12)
    assert motors.best is not None and not motors.best.met and value_text(motors.best) == "-"
    assert payload.text == "payload ≥ 30 kg" and leg.text == "leg_length ≤ 1 m"
    (bound,) = rows.bounds
    assert (bound.at.variable.name, bound.at.bound, bound.yours) == ("l1", "lower", 0.2)


def test_the_command_line_and_the_report_lay_out_the_same_rows():
    result = _result()
    text = render(result)
    best_block, your_block = text.split("Your design")
    table = requirement_blocks(result)[1]
    for row in answer_rows(result).requirements:
        assert row.best is not None and row.yours is not None
        (cli_best,) = [
            line for line in best_block.splitlines() if line.strip().startswith(row.text)
        ]
        (cli_yours,) = [
            line for line in your_block.splitlines() if line.strip().startswith(row.text)
        ]
        (report,) = [line for line in table.splitlines() if line.startswith(f"| {row.text} |")]
        measured = not math.isnan(row.best.value)  # else: "not measured", nothing limits it
        for shown in (value_text(row.best), *([str(row.best.limited_by)] if measured else [])):
            assert shown in cli_best and shown in report
        assert value_text(row.yours) in cli_yours and value_text(row.yours) in report
        cells = [cell.strip() for cell in report.strip("| ").split(" | ")]
        assert ("binds" in cli_best) == row.best.binds == (cells[3] == "yes")
        assert ("pass" in cli_yours) == row.yours.met
    assert "l1 searched in 0.1..0.4 m" in best_block and "its lower bound" in best_block
    assert "| l1 within its searched 0.1–0.4 m |" in table and "| 0.2 m | — |" in table
