"""The report's Decision section shows the answer to the user's requirements first."""

from __future__ import annotations

import json
from concurrent.futures import ThreadPoolExecutor
from dataclasses import replace

import pytest

from hexaleg import HexapodDesign, Objective, Requirements, SearchSettings, decide
from hexaleg.output.report import ReportOptions, build_report
from hexaleg.output.report.requirements import requirement_blocks


def _decide(requirements):
    with ThreadPoolExecutor(1) as here:
        return decide(HexapodDesign(), requirements, Objective("improved_area"), executor=here,
                      progress=False, settings=SearchSettings(evaluations=240),
                      free_posture=False)  # fmt: skip


def test_the_blocks_give_the_verdict_and_one_row_per_requirement():
    result = _decide(Requirements(ground_clearance=0.3, min_coxa=0.1))
    verdict, rows, flags, how = requirement_blocks(result)
    lengths = ", ".join(f"{v:.3f}" for v in result.best.design.lengths)
    assert verdict.startswith(f"**The best leg meeting your requirements: l = ({lengths}) m**")
    body = rows.splitlines()[2:]
    assert [line.split(" | ")[0].lstrip("| ") for line in body] == [
        "ground_clearance ≥ 0.3 m", "leg_length ≤ 1 m", "min_coxa ≥ 0.1 m"]  # fmt: skip
    assert [line.rstrip(" |").rsplit(" | ", 1)[1] for line in body] == ["yes", "yes", "yes"]
    assert f"{result.evaluations} designs" in how
    assert flags.startswith("| joints over their ratings | best design | your design |")
    assert "| standing without payload | none | none |" in flags
    assert "limited by geometry: the design's l1 + l2 + l3" in rows


def test_a_free_variable_at_its_search_bound_is_a_row_that_binds():
    # the largest area 2π·l2·l3/3 wants the shortest coxa: l1 goes to the floor, 0.02 m
    result = _decide(Requirements(ground_clearance=0.3))
    assert result.best.design.l1 == pytest.approx(0.02, abs=1e-3)
    rows, how = requirement_blocks(result)[1], requirement_blocks(result)[3]
    (row,) = [line for line in rows.splitlines() if line.startswith("| l1 within")]
    cells = [cell.strip() for cell in row.strip("| ").split(" | ")]
    assert cells[0] == "l1 within its searched 0.02–1 m"
    assert cells[1].startswith("0.02 m (at its lower bound; --min-coxa")
    assert cells[3] == "yes" and cells[4] == "0.2 m"
    assert "a free variable at its search bound" in how


def test_an_infeasible_answer_names_the_conflict():
    result = _decide(Requirements(ground_clearance=0.6, min_coxa=0.5))
    verdict = requirement_blocks(result)[0]
    assert verdict.startswith("**No leg within the bounds meets every requirement:**")
    assert result.conflict is not None and result.conflict.description in verdict


@pytest.mark.slow
def test_a_report_with_requirements_answers_them_first(tmp_path):
    requirements = Requirements(ground_clearance=0.3, min_coxa=0.1)
    options = ReportOptions(l3_points=10, sensitivity_points=4, workers=1, progress=False,
                            vector_figures=False, requirements=requirements)  # fmt: skip
    data = build_report(tmp_path / "out", options=options).to_dict()
    text = (tmp_path / "out" / "report.md").read_text()
    decision = text.split("## Decision")[1].split("## Design")[0]
    assert decision.index("The best leg meeting your requirements") < decision.index(
        "**Recommended:"
    )
    with ThreadPoolExecutor(1) as here:
        direct = decide(HexapodDesign(), requirements, executor=here, progress=False)
    assert data["requirements_decision"] == json.loads(json.dumps(direct.to_dict()))
    plain = build_report(tmp_path / "plain", options=replace(options, requirements=None)).to_dict()
    assert "requirements_decision" not in plain
