"""A required range frees the battery's capacity: the least capacity that walks that far."""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import pytest

from hexaleg import HexapodDesign
from hexaleg.actuators import Actuator, Actuators
from hexaleg.battery import Battery
from hexaleg.evaluation.evaluate import evaluate
from hexaleg.evaluation.goal import Objective
from hexaleg.evaluation.metrics import METRICS
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import ParameterError
from hexaleg.study.decide import decide
from hexaleg.study.optimize import SearchSettings
from hexaleg.study.search_space import FreeVariable, search_space

KEYS = dict(torque_constant=0.12, resistance=0.3, gearbox_efficiency=0.85, voltage=48.0)
MOTORS = Actuators(
    Actuator(60.0, peak_torque=80.0, continuous_torque=50.0, mass=0.8, **KEYS),
    Actuator(100.0, peak_torque=250.0, continuous_torque=150.0, mass=2.0, **KEYS),
    Actuator(80.0, peak_torque=150.0, continuous_torque=90.0, mass=1.2, **KEYS),
)
DESIGN = HexapodDesign(actuators=MOTORS, battery=Battery(100.0, 150.0))


def walked_range(capacity: float) -> float:
    """The range [km] of the design with a battery of ``capacity`` [Wh]."""
    design = DESIGN.replace(battery=Battery(capacity, 150.0))
    return evaluate(design, (METRICS.battery_range,)).metrics.value(METRICS.battery_range)


@pytest.mark.slow  # a bisection of whole evaluations and a 400-design search: a minute
def test_the_least_capacity_for_a_range_is_found():
    required = 5.0
    low, high = 1.0, 5e4  # bisection on the capacity: range grows with it here
    assert walked_range(low) < required < walked_range(high)
    while high - low > 1e-2 * high:
        middle = 0.5 * (low + high)
        low, high = (middle, high) if walked_range(middle) < required else (low, middle)
    lengths = zip(("l1", "l2", "l3"), DESIGN.lengths, strict=True)
    pinned = [FreeVariable(name, value, value + 1e-4) for name, value in lengths]
    with ThreadPoolExecutor(1) as here:
        found = decide(
            DESIGN, Requirements(range_km=required, leg_length=1.001),
            Objective("robot_mass", "minimize"), free=pinned, free_posture=False,
            settings=SearchSettings(seed=1, evaluations=400), executor=here, progress=False,
        )  # fmt: skip
    battery = found.best.design.battery
    assert found.feasible and battery is not None
    assert found.best.evaluation.metrics.value(METRICS.battery_range) >= required
    assert battery.capacity == pytest.approx(high, rel=0.05)


def test_a_range_without_a_battery_keeps_the_capacity_bound():
    space = search_space(HexapodDesign(), 1.0, battery=True)
    assert "battery_capacity" not in space.names
    with pytest.raises(ParameterError, match="battery"):
        search_space(HexapodDesign(), 1.0, free=[FreeVariable("battery_capacity", 10.0, 100.0)])
