"""One declaration per requirement: every reader derives from it, none lists it again."""

from __future__ import annotations

import argparse
import re

import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.cli.requirement_options import add_requirement_options, requirements_from_args
from hexaleg.evaluation.goal import Goal
from hexaleg.evaluation.metrics import METRICS
from hexaleg.evaluation.requirement_specs import (
    CONDITIONS,
    REQUIREMENTS,
    RequirementSpec,
    table_keys,
)
from hexaleg.evaluation.requirements import Requirements
from hexaleg.evaluation.requirements_table import example_table
from hexaleg.exceptions import ParameterError


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="t")
    add_requirement_options(parser)
    return parser


def test_every_key_is_an_option_with_its_declared_metavar_and_help():
    actions = {a.dest: a for a in _parser()._actions}
    for key in table_keys():
        action = actions[key.name]
        assert action.option_strings == [key.option]
        assert action.help == key.help
        metavar = (key.metavar,) if isinstance(key.metavar, str) else key.metavar
        assert action.metavar == (metavar[0] if len(metavar) == 1 else metavar)


def test_every_requirement_bounds_a_declared_metric_and_reaches_the_table():
    text = example_table()
    for name, spec in REQUIREMENTS.items():
        assert spec.metric is getattr(METRICS, spec.metric.name)
        assert spec.unit == spec.metric.unit
        key = name if spec.in_degrees is None else spec.in_degrees.name
        assert (f"# {key} = " in text) != spec.implied  # the design asks an implied one
    assert REQUIREMENTS["ground_clearance"].name == METRICS.ground_clearance.name  # its metric's
    assert REQUIREMENTS["slope"].in_degrees is not None  # slope_deg: the slope in degrees


@pytest.mark.parametrize("name", [n for n, spec in REQUIREMENTS.items() if not spec.implied])
def test_every_requirement_is_read_from_the_table_and_the_options_and_bounded(name):
    spec = REQUIREMENTS[name]
    needs = {"payload": 1.0} if name != "payload" else {}
    inside = spec.example if name != "slope" else 0.2
    table = Requirements.from_table({name: inside, **needs})
    assert table.required(spec) == pytest.approx(inside)
    args = _parser().parse_args([spec.option, str(inside)])
    assert requirements_from_args(args, Requirements()).required(spec) == pytest.approx(inside)
    with pytest.raises(ParameterError) as caught:
        Requirements.from_table({name: spec.bounds[1] * 2 + 1})
    assert caught.value.field == f"requirements.{name}"


def test_a_condition_without_its_requirement_is_refused_by_its_declared_reason():
    for condition in CONDITIONS.values():
        if condition.needs:
            with pytest.raises(ParameterError, match=re.escape(condition.needs)):
                Requirements.from_table({condition.name: condition.example})


MIN_HEIGHT = RequirementSpec(
    METRICS.nominal_height,
    "at least",
    (0.0, 10.0),
    "least body height above the ground at the nominal stance [m]",
    "M",
    0.35,
    "geometry: the posture and the tibia",
    name="min_height",
)
"""A requirement hexaleg does not have, declared here alone."""


def test_a_requirement_declared_once_reaches_the_options_the_table_and_the_checks(monkeypatch):
    """One declaration (on a metric the evaluation measures) and nothing else: it is an option,
    a key of the file's table and its example, stored, checked and printed in JSON."""
    monkeypatch.setitem(REQUIREMENTS, MIN_HEIGHT.name, MIN_HEIGHT)  # type: ignore[index]
    actions = {a.dest: a for a in _parser()._actions}
    assert actions["min_height"].option_strings == ["--min-height"]
    assert "# min_height = 0.35  # least body height" in example_table()
    args = _parser().parse_args(["--min-height", "0.3"])
    required = requirements_from_args(args, Requirements.from_table({"min_height": 0.5}))
    assert required.required(MIN_HEIGHT) == 0.3 and required.given == ("min_height",)
    assert required.to_dict() == {"min_height": 0.3}
    with pytest.raises(ParameterError, match=re.escape("requirements.min_height")):
        Requirements.from_table({"min_height": 11.0})
    design = HexapodDesign()
    goal = Goal(required.resolved(design))
    assert METRICS.nominal_height in goal.metrics
    checks = {c.name: c for c in goal.checks(goal.evaluate(design))}
    assert set(checks) == {"min_height", "leg_length"}  # the leg length: the design's own
    height = checks["min_height"]
    # the oracle: the body frame's height at the nominal stance, read from Pinocchio
    expected = float(HexapodModel(design).nominal_base_pose().translation[2])
    assert height.value == pytest.approx(expected, rel=1e-12)
    assert height.margin == pytest.approx(expected - 0.3, rel=1e-12) and height.met
    assert height.to_dict(binding=False)["limited_by"]["description"] == MIN_HEIGHT.reason
    assert "min_height ≥ 0.3 m" == required.describe("min_height")
