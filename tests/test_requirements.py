"""Requirements: their table, their checks and their bounds, and the design file's table."""

from __future__ import annotations

import math
import re

import pytest

from hexaleg import HexapodDesign
from hexaleg.design_file import DesignFileError, load_design, load_design_file
from hexaleg.evaluation.metrics import Causes, Metrics
from hexaleg.evaluation.requirement_specs import (
    BINDING_SHARE,
    LEG_LENGTH,
    PAYLOAD,
    REQUIREMENTS,
    SLOPE,
    STEP_HEIGHT,
)
from hexaleg.evaluation.requirements import Requirements, check
from hexaleg.exceptions import ParameterError


def test_table_keys_are_the_fields_and_degrees_become_radians():
    table = {"payload": 30, "payload_at": [0.1, 0.0, 0.05], "slope_deg": 15, "min_coxa": 0.08}
    requirements = Requirements.from_table(table)
    assert requirements.required(PAYLOAD) == 30.0
    assert requirements.payload_at == (0.1, 0.0, 0.05)
    assert requirements.required(SLOPE) == pytest.approx(math.radians(15))
    assert requirements.given == ("payload", "slope", "min_coxa")
    assert Requirements.from_table(requirements.to_dict()) == requirements


@pytest.mark.parametrize(
    ("table", "field", "words"),
    [
        ({"payload": -1}, "requirements.payload", "[0, 10000] [kg]"),
        ({"slope": 2.0}, "requirements.slope", "[rad]"),
        ({"slope": math.pi / 2}, "requirements.slope", "less than 1.571 rad (90°)"),
        ({"rang_km": 3}, "requirements.rang_km", "did you mean 'range_km'"),
        ({"slope_deg": 95}, "requirements.slope_deg", "[0, 90] [°]"),
        ({"slope": 0.1, "slope_deg": 5}, "requirements.slope_deg", "not both"),
        ({"ground_clearance": 0}, "requirements.ground_clearance", "positive"),
        ({"payload_at": [0, 0, 0.1]}, "requirements.payload_at", "needs a payload"),
        ({"payload": 3, "payload_at": [0, 0]}, "requirements.payload_at", "three coordinates"),
        ({"payload": "heavy"}, "requirements.payload", "real number"),
        ({"payliad": 3}, "requirements.payliad", "did you mean 'payload'"),
    ],
)
def test_a_bad_table_names_the_key_and_what_is_allowed(table, field, words):
    with pytest.raises(ParameterError) as caught:
        Requirements.from_table(table, source="requirements")
    assert caught.value.field == field
    assert words in str(caught.value)


def test_the_leg_length_defaults_to_the_design_own():
    design = HexapodDesign(l1=0.1, l2=0.5, l3=0.45)
    assert Requirements().resolved(design).required(LEG_LENGTH) == pytest.approx(1.05)
    assert Requirements(leg_length=0.9).resolved(design).required(LEG_LENGTH) == 0.9


def test_margins_point_to_the_good_side_and_binding_is_within_one_percent():
    requirements = Requirements(payload=100.0, leg_length=1.0)
    values = Metrics(payload_capacity=100.0 + 0.5 * BINDING_SHARE * 100, leg_length=0.8)
    payload, leg = check(requirements, values, Causes())
    assert payload.margin == pytest.approx(0.5) and payload.met and payload.binds
    assert leg.margin == pytest.approx(0.2) and leg.met and not leg.binds
    short = check(requirements, Metrics(payload_capacity=90.0, leg_length=1.1), Causes())
    assert [c.met for c in short] == [False, False]
    assert [c.binds for c in short] == [False, False]
    assert {k.sense for k in REQUIREMENTS.values()} == {"at least", "at most"}


def test_a_design_file_hands_over_its_requirements_table(tmp_path):
    path = tmp_path / "robot.toml"
    path.write_text("l1 = 0.15\n\n[requirements]\npayload = 30.0\nslope_deg = 10\n")
    design, requirements = load_design_file(path, Requirements.from_table)
    assert design.l1 == 0.15
    assert requirements == Requirements(payload=30.0, slope=math.radians(10))
    assert load_design(path) == design  # the design alone ignores the table


def test_a_bad_requirement_in_a_file_names_the_file_and_line(tmp_path):
    path = tmp_path / "robot.toml"
    path.write_text("l1 = 0.15\n\n[requirements]\npayload = 30.0\nslope_deg = 100\n")
    with pytest.raises(DesignFileError, match=r"robot.toml, line 5: requirements.slope_deg"):
        load_design_file(path, Requirements.from_table)
    path.write_text("l1 = 0.15\nrequirements = 3\n")
    with pytest.raises(DesignFileError, match=r"line 2: requirements = 3 .* table"):
        load_design_file(path, Requirements.from_table)


def test_the_step_height_is_a_condition_of_the_speed():
    requirements = Requirements.from_table({"speed": 0.3, "step_height": 0.1})
    assert requirements.given == ("speed",) and requirements.condition(STEP_HEIGHT) == 0.1
    assert requirements.gait.step_height == 0.1
    assert Requirements.from_table(requirements.to_dict()) == requirements
    with pytest.raises(ParameterError, match="needs a speed"):
        Requirements(step_height=0.1)


def test_design_init_writes_every_requirement_commented_out_with_its_unit(tmp_path):
    from conftest import run_cli

    from hexaleg.design_file import load_design_file

    path = tmp_path / "robot.toml"
    assert run_cli(["design", "init", str(path)]) == 0
    text = path.read_text()
    assert load_design_file(path, Requirements.from_table)[1] == Requirements()  # all comments
    block = text[text.index("# [requirements]") :].splitlines()
    assert all(line.startswith("# ") for line in block)
    keys = [line[2:].split(" = ")[0] for line in block[1:]]
    written = {name for name, spec in REQUIREMENTS.items() if not spec.implied}  # not structure
    conditions = {"payload_at", "step_height", "slope_deg", "walking_slope_deg",
                  "motor_safety_factor"}  # fmt: skip
    assert set(keys) == (written | conditions) - {"slope"}
    assert all(re.search(r"\[(kg|m|°|-|m/s|km)\]", line) for line in block[1:])  # units
    uncommented = text[: text.index("# [requirements]")] + "\n".join(line[2:] for line in block)
    path.write_text(uncommented)
    _, requirements = load_design_file(path, Requirements.from_table)
    assert requirements == Requirements(
        payload=30.0, payload_at=(0.0, 0.0, 0.05), slope=math.radians(15), ground_clearance=0.25,
        min_fb=0.2, leg_length=1.0, min_coxa=0.08, speed=0.3, step_height=0.1,
        walking_payload=10.0, range_km=5.0, continuous_margin=0.8,
        walking_slope=math.radians(10), motor_safety_factor=1.5,
    )  # fmt: skip


def test_design_show_prints_the_files_requirements(tmp_path, capsys):
    import json

    from conftest import run_cli

    path = tmp_path / "robot.toml"
    path.write_text("l1 = 0.15\n\n[requirements]\npayload = 30.0\nslope_deg = 10\nspeed = 0.2\n")
    assert run_cli(["design", "show", "--design", str(path)]) == 0
    out = capsys.readouterr().out
    assert "Requirements (the file's [requirements] table)" in out
    assert "payload ≥ 30 kg (on every slope up to 10°)" in out
    assert "speed ≥ 0.2 m/s (tripod, stride 0.3 m, step height 0.1 m, carrying 30 kg)" in out
    assert run_cli(["design", "show", "--design", str(path), "--json"]) == 0
    shown = json.loads(capsys.readouterr().out)
    assert shown["requirements"] == {"payload": 30.0, "slope": math.radians(10), "speed": 0.2}
    path.write_text("l1 = 0.15\n")
    assert run_cli(["design", "show", "--design", str(path), "--json"]) == 0
    assert "requirements" not in json.loads(capsys.readouterr().out)
