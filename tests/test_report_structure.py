"""The report's structure section: each segment's tube, mass, worst ratio and case, deflection.

Oracle: ``hexaleg loads --json`` on the same design file (its tubes given), which checks the
tubes at the nominal stance and the extremes of the axis-locked flexibility as the report's
one evaluation of your design does.
"""

from __future__ import annotations

import json

import pytest
from conftest import run_cli

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.design_file import load_design
from hexaleg.output.report import ReportOptions, yours
from hexaleg.output.report import structure as structure_part
from hexaleg.output.report.part import ReportData
from hexaleg.output.report.registry import PARTS
from hexaleg.robot.recipe import RobotSource
from hexaleg.robot.robot import robot_of

TUBES = """[structure]
material = "aluminium_6061_t6"
[structure.coxa]
outer_diameter = 0.047
wall = 0.001
[structure.femur]
outer_diameter = 0.04
wall = 0.001
[structure.tibia]
outer_diameter = 0.026
wall = 0.001
"""


@pytest.mark.slow  # your design's whole evaluation and the loads command
def test_the_structure_section_shows_each_segment_as_loads_checks_it(tmp_path, capsys):
    path = tmp_path / "tubes.toml"
    path.write_text(TUBES)
    design = load_design(path)
    assert structure_part.holds(robot_of(RobotSource(), design), ReportOptions()) is None
    data = ReportData(design, ReportOptions(l3_points=10), HexapodModel(design), parts=PARTS)
    data = data.with_record(yours.compute(data))
    data = data.with_record(structure_part.compute(data))
    text = "\n".join(b for b in structure_part.section(data).blocks if isinstance(b, str))
    assert run_cli(["loads", "--design", str(path), "--json"]) == 0
    expected = json.loads(capsys.readouterr().out)["structure"]
    check = data[structure_part.StructureRecord].check
    assert check is not None and check.to_dict()["worst_ratio"] == pytest.approx(
        expected["worst_ratio"], rel=1e-9
    )
    rows = {row[0]: row for row in structure_part.segment_rows(check)}
    for segment, tube in expected["tubes"].items():
        row = rows[segment]
        assert f"D {tube['outer_diameter'] * 1e3:.4g} mm" in row[1]
        assert row[2] == f"{tube['mass']:.4g}"
    worst = expected["worst"]
    assert rows[worst["segment"]][3].startswith(f"{worst['ratio']:.3f}")
    assert rows[worst["segment"]][4] == f"{worst['leg']}, {worst['case']}"
    assert f"{expected['deflection'] * 1e3:.3g} mm" in text
    plain = robot_of(RobotSource(), HexapodDesign())
    assert structure_part.holds(plain, ReportOptions()) is not None  # no [structure]: no section
