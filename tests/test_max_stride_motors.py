"""A design with actuators: its max stride keeps every joint within its every rating.

The oracle bisects the stride on :func:`~hexaleg.gait.analysis.analyze_gait`'s own verdict
(``feasible``, from its ``over_rating`` records), one gait period at a time.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from hexaleg import HexapodDesign
from hexaleg.actuators import Actuator, Actuators
from hexaleg.gait import Gait, analyze_gait

KEYS = dict(torque_constant=0.12, resistance=0.3, gearbox_efficiency=0.85, rotor_inertia=1e-4,
            mass=1.5, gear_ratio=100.0, peak_torque=500.0)  # fmt: skip
KIND = {"torque": "peak_torque", "continuous_torque": "continuous_torque",
        "voltage": "voltage", "speed": "speed"}  # fmt: skip
"""A cause's kind as the over-rating records name the quantity."""


def _over(design: HexapodDesign, gait: Gait, stride: float) -> list[tuple[str, str]]:
    walked = analyze_gait(design, dataclasses.replace(gait, stride=stride), limits=False)
    assert walked.walkable  # below the walkable max stride: only the ratings break
    return [(o.quantity, o.joint) for o in walked.over_rating]


def _oracle(design: HexapodDesign, gait: Gait, top: float) -> tuple[float, list[tuple[str, str]]]:
    """The first stride (from 1 mm, in 2 cm steps up to ``top``) over a rating, bisected."""
    low = 1e-3
    assert not _over(design, gait, low)
    for high in np.arange(0.02, top, 0.02):
        if _over(design, gait, float(high)):
            break
        low = float(high)
    else:
        pytest.fail("no stride breaks a rating")
    while high - low > 1e-7:
        middle = 0.5 * (low + high)
        low, high = (middle, high) if not _over(design, gait, middle) else (low, middle)
    return low, _over(design, gait, float(high))


@pytest.mark.slow
@pytest.mark.parametrize(
    ("hip", "voltage", "period", "binds"),
    [
        (145.0, 400.0, 0.8, ("continuous_torque", "hip")),  # the hips' RMS, at a high supply
        (300.0, 48.0, 1.0, ("voltage", "knee")),  # a low supply: the knees' back-EMF
    ],
)
def test_the_max_stride_is_where_the_period_first_exceeds_a_rating(hip, voltage, period, binds):
    strong = Actuator(continuous_torque=300.0, voltage=voltage, **KEYS)
    weak_hip = dataclasses.replace(strong, continuous_torque=hip)
    design = HexapodDesign().replace(actuators=Actuators(strong, weak_hip, strong))
    gait = Gait(period=period)
    found = analyze_gait(design, gait)
    walkable = analyze_gait(HexapodDesign(), gait).max_stride  # the same legs, no motors
    assert found.max_stride is not None and walkable is not None
    value, over = _oracle(design, gait, walkable.value)
    assert found.max_stride.value == pytest.approx(value, abs=2e-7)
    cause = found.max_stride.limited_by
    assert (KIND[cause.kind], cause.joint) == binds
    assert binds in over  # just beyond it, that rating is exceeded
    assert f"{binds[1]} {binds[0].replace('_', ' ')}" in str(cause).replace("motor's ", "")


def test_ratings_that_break_only_as_a_leg_straightens_leave_the_reach_named():
    bare = HexapodDesign()
    never = Actuator(continuous_torque=1e5, voltage=1e4, **(KEYS | {"peak_torque": 1e5}))
    motors = bare.replace(actuators=Actuators(never, never, never))
    gait = Gait()
    a, b = analyze_gait(bare, gait).max_stride, analyze_gait(motors, gait).max_stride
    assert a is not None and b is not None
    assert a.limited_by.kind == "reach" and b.limited_by == a.limited_by
    # a straight leg's torques are unbounded: even these ratings break just short of it
    assert a.value - 1e-4 * a.value <= b.value <= a.value
