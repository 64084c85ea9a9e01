"""decide --free-gear-ratio: each joint type's gear ratio free within its entry's range.

The rule (:meth:`~hexaleg.actuators.Actuator.with_gear_ratio`) is checked against the
ratios Harmonic Drive prints beside the catalog's (the datasheet rows quoted in
``hexaleg/data/actuators_notes.md``), and decide against a brute-force search over the
three gear ratios written here.
"""

from __future__ import annotations

import functools
import itertools
import math
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest
from conftest import run_cli

from hexaleg import HexapodDesign
from hexaleg.actuator_catalog import actuators_from_table, catalog_from_data, shipped_catalog
from hexaleg.actuators import Actuator, Actuators
from hexaleg.evaluation.goal import Goal, Objective
from hexaleg.evaluation.metrics import METRICS
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import ParameterError
from hexaleg.study.decide import decide
from hexaleg.study.optimize import SearchSettings
from hexaleg.study.search_space import FreeVariable, search_space

KEYS = dict(torque_constant=0.12, resistance=0.3, gearbox_efficiency=0.85, voltage=48.0,
            rotor_inertia=1e-4, mass=1.5)  # fmt: skip
CATALOG = catalog_from_data(
    {
        "actuator": [
            {"name": "geared", "source": "test", "gear_ratio": 100.0,
             "gear_ratio_range": [40.0, 160.0], "peak_torque": 400.0,
             "continuous_torque": 250.0, **KEYS},
            {"name": "fixed", "source": "test", "gear_ratio": 80.0, "peak_torque": 300.0,
             "continuous_torque": 200.0, **KEYS},
        ]
    }
)  # fmt: skip
"""Made-up actuators: one sold in a range of ratios, one in a single ratio."""

RPM = 2 * math.pi / 60


def test_the_rule_scales_speed_armature_and_torques_with_the_ratio():
    base = Actuator(gear_ratio=100.0, peak_torque=400.0, continuous_torque=250.0,
                    max_speed=6.0, **KEYS)  # fmt: skip
    low, high = base.with_gear_ratio(50.0), base.with_gear_ratio(200.0)
    assert (low.peak_torque, low.continuous_torque, low.max_speed) == (200.0, 125.0, 12.0)
    assert (high.peak_torque, high.continuous_torque, high.max_speed) == (400.0, 250.0, 3.0)
    assert low.armature == pytest.approx(50.0**2 * 1e-4) and high.armature == pytest.approx(4.0)
    for kept in ("torque_constant", "resistance", "gearbox_efficiency", "voltage", "mass"):
        assert getattr(high, kept) == getattr(base, kept)
    derived = Actuator(gear_ratio=100.0, peak_torque=400.0, continuous_torque=250.0, **KEYS)
    assert derived.with_gear_ratio(40.0).rated_speed == pytest.approx(48.0 / (0.12 * 40.0))
    with pytest.raises(ParameterError, match="gear_ratio"):
        base.with_gear_ratio(0.5)


# Harmonic Drive AG, Engineering Data AC Servo Actuators CHA, 1018854 12/2015 V01, p.34
# Table 34.1 (CHA-20A, M512P): ratio 30 / 50 / 80 / 100 / 120 / 160, T_max
# 27 56 74 82 87 92 N·m, T0 19 32 47 49 49 49 N·m, n_max 200 120 75 60 50 38 rpm, and
# Table 34.2: J_out 0.21 0.58 1.48 2.32 3.30 5.90 kg·m² (actuators_notes.md §6).
CHA_20A = {30: (27, 19, 200, 0.21), 50: (56, 32, 120, 0.58), 80: (74, 47, 75, 1.48),
           120: (87, 49, 50, 3.30), 160: (92, 49, 38, 5.90)}  # fmt: skip


@pytest.mark.parametrize("ratio", sorted(CHA_20A))
def test_the_rule_against_the_ratios_harmonic_drive_prints(ratio):
    entry = shipped_catalog().entry("hd_cha_20a_100")
    assert entry.gear_ratio_range == (30.0, 160.0)
    peak, continuous, speed, inertia = CHA_20A[ratio]
    geared = entry.actuator.with_gear_ratio(float(ratio))
    assert geared.rated_speed == pytest.approx(speed * RPM, rel=0.02)  # the motor's top speed
    assert geared.armature == pytest.approx(inertia, rel=0.05)  # printed to two digits
    assert geared.peak_torque <= peak and geared.continuous_torque <= continuous  # conservative


def test_a_point_sets_the_ratio_on_a_log_scale_and_an_entry_without_a_range_keeps_its_own():
    design = HexapodDesign()
    entries = [entry.actuator for entry in CATALOG]
    ranges = [entry.gear_ratio_range for entry in CATALOG]
    space = search_space(design, 1.0, actuators=entries, ratio_ranges=ranges)
    names = space.names
    assert names[-6:] == ("actuator_root", "actuator_hip", "actuator_knee",
                          "gear_ratio_root", "gear_ratio_hip", "gear_ratio_knee")  # fmt: skip
    x = np.array([*design.lengths, 0.5, 0.5, 1.5, 0.0, 0.5, 0.25])
    chosen = space.design(x).actuators
    assert chosen is not None
    assert chosen.root.gear_ratio == pytest.approx(40.0)
    assert chosen.hip.gear_ratio == pytest.approx(80.0)  # √(40·160)
    assert chosen.knee == entries[1]  # no range: its own ratio, whatever the coordinate
    assert chosen.hip == entries[0].with_gear_ratio(chosen.hip.gear_ratio)
    back = space.point(space.design(x))
    assert back[3:6] == pytest.approx([0.5, 0.5, 1.5])
    assert back[6:8] == pytest.approx([0.0, 0.5])
    reread = actuators_from_table(chosen.to_table(), CATALOG)  # a design file holds it
    assert reread == chosen
    kept = search_space(design, 1.0, actuators=entries)  # without ranges: ratios kept
    assert "gear_ratio_hip" not in kept.names


def test_the_ratios_are_freed_by_the_flag_only_and_with_choose_actuators(capsys):
    with pytest.raises(ParameterError, match="free-gear-ratio"):
        FreeVariable.parse("gear_ratio_hip=0:1")
    assert run_cli(["decide", "--free-gear-ratio"]) == 2
    assert "--choose-actuators" in capsys.readouterr().err
    with pytest.raises(ParameterError, match="choose-actuators"):
        search_space(HexapodDesign(), 1.0, ratio_ranges=[])


GOAL_REQUIREMENTS = Requirements(speed=0.5, leg_length=1.001)
"""Walk a tripod at 0.5 m/s within the ratings: a higher ratio loses speed, a lower copper."""
OBJECTIVE = Objective("energy_per_km", "minimize")


def _energy(ratios: tuple[float, float, float]) -> float:
    """Wh/km of the default legs with ``geared`` at these ratios (inf if a requirement fails)."""
    design = HexapodDesign()
    goal = Goal(GOAL_REQUIREMENTS.resolved(design), OBJECTIVE)
    entry = CATALOG.entry("geared").actuator
    motors = Actuators(*(entry.with_gear_ratio(float(n)) for n in ratios))
    evaluation = goal.evaluate(design.replace(actuators=motors))
    return evaluation.metrics.value(METRICS.energy_per_km) if goal.meets(evaluation) else math.inf


@functools.cache
def _brute_force() -> tuple[tuple[float, ...], float, float]:
    """A grid of 5 log-spaced ratios a joint over [40, 160], then three finer grids around
    the best (each half the step): (best ratios, best energy, the coarse grid's best)."""
    step = math.log(4.0) / 4
    centre = (math.log(100.0),) * 3
    axes = [np.exp(np.linspace(math.log(40.0), math.log(160.0), 5))] * 3
    coarse = None
    for _ in range(4):
        values = {ns: _energy(ns) for ns in itertools.product(*axes)}
        best = min(values, key=lambda ns: values[ns])
        coarse = values[best] if coarse is None else coarse
        centre = tuple(math.log(n) for n in best)
        axes = [
            np.exp(np.clip(np.linspace(c - step, c + step, 5), math.log(40.0), math.log(160.0)))
            for c in centre
        ]
        step /= 2
    return tuple(math.exp(c) for c in centre), values[best], coarse


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1])
def test_decide_finds_the_ratios_a_brute_force_search_does(seed):
    design = HexapodDesign()
    lengths = zip(("l1", "l2", "l3"), design.lengths, strict=True)
    pinned = [FreeVariable(name, value, value + 1e-4) for name, value in lengths]
    geared = [CATALOG.entry("geared")]
    with ProcessPoolExecutor(2) as pool:
        found = decide(
            design, GOAL_REQUIREMENTS, OBJECTIVE, free=pinned, free_posture=False,
            actuators=[e.actuator for e in geared],
            ratio_ranges=[e.gear_ratio_range for e in geared],
            settings=SearchSettings(seed=seed, evaluations=90 * 8), executor=pool,
            progress=False,
        )  # fmt: skip
    ratios, energy, coarse = _brute_force()
    assert found.feasible and found.best.design.actuators is not None
    found_energy = found.best.evaluation.metrics.value(METRICS.energy_per_km)
    assert found_energy <= coarse  # a continuous ratio does at least as well as the grid
    assert found_energy == pytest.approx(energy, rel=5e-3)
    chosen = [a.gear_ratio for a in found.best.design.actuators.joints]
    assert chosen == pytest.approx(ratios, rel=0.1)
