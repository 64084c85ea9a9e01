"""One declaration per requirement: every reader derives from it, none lists it again."""

from __future__ import annotations

import argparse
import dataclasses
import re

import pytest

from hexaleg.cli.requirement_options import add_requirement_options, requirements_from_args
from hexaleg.evaluation.metrics import METRICS
from hexaleg.evaluation.requirement_specs import CONDITIONS, REQUIREMENTS, table_keys
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


def test_every_requirement_is_a_field_bounds_a_declared_metric_and_reaches_the_table():
    fields = {f.name for f in dataclasses.fields(Requirements)} - {"walked"}  # the gait walked
    degrees = {c.name for c in CONDITIONS.values() if c.kind == "degrees"}
    assert fields == set(REQUIREMENTS) | (set(CONDITIONS) - degrees)
    text = example_table()
    for name, spec in REQUIREMENTS.items():
        assert spec.metric is getattr(METRICS, spec.metric.name)
        assert spec.unit == spec.metric.unit
        in_degrees = [c.name for c in CONDITIONS.values() if c.of == name and c.kind == "degrees"]
        assert f"# {in_degrees[0] if in_degrees else name} = " in text


@pytest.mark.parametrize("name", list(REQUIREMENTS))
def test_every_requirement_is_read_from_the_table_and_the_options_and_bounded(name):
    spec = REQUIREMENTS[name]
    needs = {"payload": 1.0} if name != "payload" else {}
    inside = spec.example if name != "slope" else 0.2
    table = Requirements.from_table({name: inside, **needs})
    assert getattr(table, name) == pytest.approx(inside)
    args = _parser().parse_args([spec.option, str(inside)])
    assert getattr(requirements_from_args(args, Requirements()), name) == pytest.approx(inside)
    with pytest.raises(ParameterError) as caught:
        Requirements.from_table({name: spec.bounds[1] * 2 + 1})
    assert caught.value.field == f"requirements.{name}"


def test_a_condition_without_its_requirement_is_refused_by_its_declared_reason():
    for condition in CONDITIONS.values():
        if condition.needs:
            with pytest.raises(ParameterError, match=re.escape(condition.needs)):
                Requirements.from_table({condition.name: condition.example})
