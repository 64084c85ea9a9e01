"""decide --choose-actuators: one catalog actuator per joint type, against every combination."""

from __future__ import annotations

import itertools
from concurrent.futures import ThreadPoolExecutor

import pytest
from conftest import run_cli

from hexaleg import HexapodDesign
from hexaleg.actuator_catalog import catalog_from_data
from hexaleg.actuators import Actuators
from hexaleg.evaluation.goal import Goal, Objective
from hexaleg.evaluation.metrics import METRICS
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import ParameterError
from hexaleg.study.decide import decide
from hexaleg.study.optimize import SearchSettings
from hexaleg.study.search_space import FreeVariable

KEYS = dict(torque_constant=0.12, resistance=0.3, gearbox_efficiency=0.85, voltage=48.0)
CATALOG = catalog_from_data(
    {
        "actuator": [
            {"name": "light", "source": "test", "gear_ratio": 60.0, "peak_torque": 80.0,
             "continuous_torque": 50.0, "mass": 0.5, **KEYS},
            {"name": "medium", "source": "test", "gear_ratio": 100.0, "peak_torque": 250.0,
             "continuous_torque": 160.0, "mass": 1.5, **KEYS},
            {"name": "heavy", "source": "test", "gear_ratio": 120.0, "peak_torque": 500.0,
             "continuous_torque": 320.0, "mass": 3.0, **KEYS},
        ]
    }
)  # fmt: skip
"""A small catalog of made-up actuators: what the search picks from."""


def test_the_search_picks_the_combination_an_exhaustive_search_does():
    design = HexapodDesign()
    lengths = zip(("l1", "l2", "l3"), design.lengths, strict=True)
    pinned = [FreeVariable(name, value, value + 1e-4) for name, value in lengths]
    requirements = Requirements(continuous_margin=1.0, leg_length=1.001)
    objective = Objective("robot_mass", "minimize")
    entries = [entry.actuator for entry in CATALOG]
    with ThreadPoolExecutor(1) as here:
        found = decide(
            design, requirements, objective, free=pinned, actuators=entries, free_posture=False,
            settings=SearchSettings(seed=3, evaluations=120), executor=here, progress=False,
        )  # fmt: skip
    goal = Goal(requirements.resolved(design), objective)
    best, best_mass = None, float("inf")
    for combination in itertools.product(entries, repeat=3):
        candidate = design.replace(actuators=Actuators(*combination))
        evaluation = goal.evaluate(candidate)
        mass = evaluation.metrics.value(METRICS.robot_mass)
        if goal.meets(evaluation) and mass < best_mass:
            best, best_mass = combination, mass
    assert best is not None and best[1].catalog != "light"  # the light hip is too weak
    assert found.feasible
    assert found.best.design.actuators is not None
    assert found.best.design.actuators.joints == best
    slack = (
        6 * design.link_linear_density * 3 * 1e-4
    )  # six legs' links, each segment ≤ 0.1 mm longer
    assert found.best.evaluation.metrics.robot_mass == pytest.approx(best_mass, abs=slack)


def test_choices_are_freed_by_the_flag_only(capsys):
    with pytest.raises(ParameterError, match="choose-actuators"):
        FreeVariable.parse("actuator_hip=0:3")
    assert run_cli(["decide", "--free", "actuator_hip=0:3"]) == 2
    assert "choose-actuators" in capsys.readouterr().err
