"""``loads``, ``gait`` and ``design show`` with [structure]: JSON, flags, sizing, refusals."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from hexaleg.cli.main import main
from hexaleg.design_file import load_design
from hexaleg.statics.loads import analyze_loads

KRABY = Path(__file__).parent / "data" / "robots" / "kraby" / "hexapod.urdf"


def design_file(tmp_path, structure, requirements=""):
    path = tmp_path / "design.toml"
    path.write_text(f"[structure]\n{structure}\n{requirements}", encoding="utf-8")
    return str(path)


TUBES = """material = "aluminium_6061_t6"
coxa = { outer_diameter = 0.04, wall = 0.002 }
femur = { outer_diameter = 0.04, wall = 0.002 }
tibia = { outer_diameter = 0.03, wall = 0.0015 }
"""

THIN_PLA = """material = "pla_printed"
coxa = { outer_diameter = 0.012, wall = 0.001 }
femur = { outer_diameter = 0.012, wall = 0.001 }
tibia = { outer_diameter = 0.012, wall = 0.001 }
"""


def run_json(capsys, *argv):
    assert main([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_loads_json_gives_the_structure_the_brief_asks_for(tmp_path, capsys):
    path = design_file(tmp_path, TUBES, "[requirements]\nslope_deg = 10\n")
    structure = run_json(capsys, "loads", "--design", path, "--payload", "10")["structure"]
    for key in ("nominal", "worst", "worst_ratio", "deflection", "feasible", "tubes"):
        assert key in structure
    assert set(structure["nominal"]) == {"lf", "lm", "lr", "rf", "rm", "rr"}
    assert set(structure["nominal"]["lf"]) == {"coxa", "femur", "tibia"}
    assert set(structure["nominal"]["lf"]["femur"]) == {
        "axial",
        "bending",
        "torsion",
        "von_mises",
        "ratio",
    }
    assert set(structure["worst"]) == {"case", "leg", "segment", "ratio"}
    assert structure["worst_ratio"] == structure["worst"]["ratio"]
    assert structure["tubes"]["coxa"]["outer_diameter"] == 0.04
    assert structure["tubes"]["coxa"]["mass"] == pytest.approx(2700 * 2.3876104e-4 * 0.2, rel=1e-6)
    assert structure["feasible"] is True and structure["over_strength"] == []
    assert structure["deflection"] <= structure["deflection_limit"] == pytest.approx(0.01)


def test_the_required_slope_is_a_case_and_the_worst_is_over_every_case(tmp_path, capsys):
    level = run_json(capsys, "loads", "--design", design_file(tmp_path, TUBES))["structure"]
    sloped = design_file(tmp_path, TUBES, "[requirements]\nslope_deg = 25\n")
    steep = run_json(capsys, "loads", "--design", sloped)["structure"]
    assert steep["worst_ratio"] >= level["worst_ratio"]
    check = analyze_loads(load_design(sloped), slope=math.radians(25)).structure
    assert any(case.startswith("slope 25°") for case in check.cases)


def test_a_tube_over_its_strength_is_flagged_and_makes_the_walk_infeasible(tmp_path, capsys):
    path = design_file(tmp_path, THIN_PLA)
    assert main(["loads", "--design", path]) == 0
    text = capsys.readouterr().out
    assert "OVER STRENGTH" in text and "stress ratio" in text
    structure = run_json(capsys, "loads", "--design", path)["structure"]
    assert structure["feasible"] is False and structure["worst_ratio"] > 1
    over = structure["over_strength"][0]
    assert over["ratio"] > 1 and over["von_mises"] > over["allowed"]
    walk = run_json(capsys, "gait", "--design", path)
    assert walk["feasible"] is False and walk["structure"]["worst_ratio"] > 1
    assert walk["structure"]["worst"]["case"].startswith("t = ")
    assert main(["gait", "--design", path]) == 0
    assert "no: a leg segment over its strength" in capsys.readouterr().out


def test_size_true_chooses_the_tubes_first_and_says_how_many_rounds(tmp_path, capsys):
    path = design_file(
        tmp_path,
        'material = "aluminium_7075_t6"\nsize = true\n',
        "[requirements]\npayload = 15\n",
    )
    loads = run_json(capsys, "loads", "--design", path, "--payload", "15")["structure"]
    assert loads["sizing"]["settled"] and loads["sizing"]["iterations"] >= 1
    assert loads["feasible"] and loads["worst_ratio"] <= 1
    shown = run_json(capsys, "design", "show", "--design", path)
    assert shown["design"]["structure"]["coxa"] == {
        key: loads["tubes"]["coxa"][key] for key in ("outer_diameter", "wall")
    }
    assert main(["design", "show", "--design", path]) == 0
    assert "tubes sized" in capsys.readouterr().out


@pytest.mark.parametrize("command", ["loads", "workspace", "design show"])
def test_a_robot_file_refuses_a_structure_in_one_line(tmp_path, capsys, command):
    """Every command resolves the design the same way: one that sizes nothing refuses too."""
    path = design_file(tmp_path, TUBES)
    assert main([*command.split(), "--urdf", str(KRABY), "--design", path]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "[structure]" in err


def test_without_a_structure_nothing_changes(capsys):
    loads = run_json(capsys, "loads")
    assert loads["structure"] is None and loads["mass"] == pytest.approx(60 + 6 * (4.0 + 1e-3))
