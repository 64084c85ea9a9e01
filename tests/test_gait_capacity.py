"""The walking payload capacity against a bisection on the gait analysis itself (and, for
each kind of robot, ``loads``' capacity against that analysis just under and over it).

With actuators, the bisection runs on the full :func:`analyze_gait` (its electrical
``over_rating``: peak and continuous torque, voltage, speed), never on the capacity's own
algebra.
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from conftest import run_cli
from robots import KINDS, KRABY, robot_argv, robot_json

from hexaleg import HexapodDesign, HexapodModel, analyze_gait
from hexaleg.actuator_catalog import actuators_from_table
from hexaleg.actuators import Actuator, Actuators
from hexaleg.battery import Battery
from hexaleg.cause import Cause
from hexaleg.design_file import load_design
from hexaleg.electrical.ratings import motor_loads
from hexaleg.evaluation.evaluate import evaluate
from hexaleg.evaluation.metrics import METRICS
from hexaleg.gait.capacity import (
    PROBE_MASS,
    _voltage_bound,
    _zmp_bound,
    walking_payload_capacity,
)
from hexaleg.gait.dynamics import payload_wrench
from hexaleg.gait.spec import Gait
from hexaleg.gait.walk import Walker
from hexaleg.grids import ratio_lengths
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.imported import import_robot
from hexaleg.robot.imported_model import ImportedHexapodModel
from hexaleg.statics.forces import Payload


def _walks(design, model, gait, mass, position) -> bool:
    """The oracle's predicate: the period is feasible, within every rating, the ZMP inside."""
    walked = analyze_gait(design, gait, Payload(mass, position), model=model, limits=False)
    return walked.feasible and not walked.over_rating and walked.min_zmp_margin >= 0


def _bisect(design, model, gait, position, upper) -> float:
    low, high = 0.0, upper
    while high - low > 1e-7:
        middle = (low + high) / 2
        low, high = (
            (middle, high) if _walks(design, model, gait, middle, position) else (low, middle)
        )
    return low


def _cases(count: int, seed: int):
    rng = np.random.default_rng(seed)
    for _ in range(count):
        ratings = tuple(rng.uniform([60, 180, 150], [120, 300, 250]))
        design = HexapodDesign.from_ratios(
            rng.uniform(0.08, 0.2), rng.uniform(0.35, 0.6), rated_torques=ratings
        )
        position = tuple(rng.uniform([-0.3, -0.2, 0.0], [0.3, 0.2, 0.2]))
        gait = Gait(period=rng.uniform(1.5, 3.0), stride=rng.uniform(0.15, 0.3))
        yield design, position, gait


@pytest.mark.parametrize(("design", "position", "gait"), list(_cases(4, seed=2)))
def test_the_capacity_equals_a_bisection_on_analyze_gait(design, position, gait):
    model = HexapodModel(design)
    found = walking_payload_capacity(model, gait, position)
    assert found.walks and found.limited_by.kind == "torque"
    oracle = _bisect(design, model, gait, position, 2 * found.mass + 1)
    assert found.mass == pytest.approx(oracle, abs=1e-6)


def test_a_payload_far_out_unloads_a_foot_until_it_cannot_grip():
    """As the ZMP nears the polygon's edge the far feet unload: their planned tangential
    force leaves the friction cone (or they would have to pull) just before it leaves."""
    design = HexapodDesign(rated_torques=(1e5, 1e5, 1e5))
    model, gait, position = HexapodModel(design), Gait(), (2.0, 0.0, 0.05)
    found = walking_payload_capacity(model, gait, position)
    assert found.limited_by.kind == "slide" and str(found.limited_by) == (
        f"{found.limited_by.leg} foot slides (friction cone)"
    )
    assert found.mass == pytest.approx(_bisect(design, model, gait, position, 100.0), abs=1e-6)
    above = analyze_gait(
        design, gait, Payload(found.mass * (1 + 1e-6), position), model=model, limits=False
    )
    assert above.walkable and above.tipping is None
    assert found.limited_by.leg in {slip.leg for slip in above.slips}


def test_a_design_that_cannot_walk_unloaded_carries_nothing_and_says_why():
    slow = HexapodDesign(rated_speeds=(0.2, 0.2, 0.2))  # the gait's joints turn faster
    found = walking_payload_capacity(HexapodModel(slow))
    assert not found.walks and found.mass == 0.0 and found.limited_by.kind == "speed"
    weak = HexapodDesign(rated_torques=(60.0, 40.0, 120.0))  # the hips cannot hold the body
    found = walking_payload_capacity(HexapodModel(weak))
    assert not found.walks and found.mass == 0.0
    assert str(found.limited_by).endswith("hip torque at its rating")
    assert not _walks(weak, HexapodModel(weak), Gait(), 0.0, None)


# With actuators: the continuous torque (RMS over the period) and the motor's voltage bind too.

SMALL_LEG = dict(l1=0.1, l2=0.25, l3=0.3, body_mass=20.0)
"""A leg short and a body light enough for the shipped harmonic drives to walk the gait."""

QUANTITY = {"torque": "peak_torque", "continuous_torque": "continuous_torque", "voltage": "voltage"}
"""A cause's kind as the gait analysis's over_rating names the quantity."""


def _first_over(design, model, gait, mass, position) -> set[tuple[str, str, str]]:
    """(leg, joint, quantity) of every rating analyze_gait finds broken at ``mass``."""
    walked = analyze_gait(design, gait, Payload(mass, position), model=model, limits=False)
    return {(o.leg, o.joint, o.quantity) for o in walked.over_rating}


def _check_against_bisection(design, gait, position, kind):
    model = HexapodModel(design)
    found = walking_payload_capacity(model, gait, position)
    assert found.walks and found.limited_by.kind == kind, found
    oracle = _bisect(design, model, gait, position, 2 * found.mass + 1)
    assert found.mass == pytest.approx(oracle, rel=1e-6)
    # just past it, the gait analysis itself reports the named joint over the named rating
    over = _first_over(design, model, gait, oracle * (1 + 1e-5) + 1e-6, position)
    cause = found.limited_by
    assert (cause.leg, cause.joint, QUANTITY[kind]) in over
    assert not _first_over(design, model, gait, oracle * (1 - 1e-5), position)
    return found


@pytest.mark.parametrize(
    ("knee", "kind", "text"),
    [
        ("hd_cha_17a_e_100", "continuous_torque", "hip continuous torque at its rating"),
        ("hd_cha_20a_100", "torque", "hip torque at its rating"),
    ],
)
def test_catalog_actuators_bind_on_the_rating_the_gait_analysis_breaks_first(knee, kind, text):
    catalog = {"root": "hd_cha_17a_e_100", "hip": "hd_cha_25a_100", "knee": knee}
    actuators = actuators_from_table({j: {"catalog": name} for j, name in catalog.items()})
    design = HexapodDesign(actuators=actuators, battery=BUS_680, **SMALL_LEG)
    found = _check_against_bisection(design, Gait(stride=0.2), None, kind)
    assert str(found.limited_by).endswith(text)


BUS_680 = Battery(capacity=500.0, specific_energy=200.0, voltage=680.0)
"""One bus for the catalog's 48 V and 680 V drives: the 680 V ones' supply."""


def _random_actuator(rng, **keys) -> Actuator:
    """A plausible geared motor with generous ratings unless ``keys`` lower them."""
    values = dict(
        gear_ratio=rng.uniform(50, 150),
        torque_constant=rng.uniform(0.05, 0.3),
        resistance=rng.uniform(0.2, 3.0),
        gearbox_efficiency=rng.uniform(0.6, 0.95),
        peak_torque=1e4,
        continuous_torque=1e4,
        mass=rng.uniform(0.3, 1.5),
        voltage=1e4,
        rotor_inertia=rng.uniform(0, 5e-5),
        max_speed=100.0,
    )
    return Actuator(**(values | keys))


def _random_motor_case(seed: int):
    rng = np.random.default_rng(seed)
    actuators = Actuators(*(_random_actuator(rng) for _ in LEG_JOINTS))
    design = HexapodDesign.from_ratios(
        rng.uniform(0.08, 0.2), rng.uniform(0.35, 0.6), actuators=actuators,
        body_mass=rng.uniform(30, 60),
    )  # fmt: skip
    position = tuple(rng.uniform([-0.2, -0.1, 0.0], [0.2, 0.1, 0.1]))
    gait = Gait(period=rng.uniform(1.5, 3.0), stride=rng.uniform(0.15, 0.3))
    return rng, design, position, gait


def _lowered(design, joint: str, **keys) -> HexapodDesign:
    actuators = dataclasses.replace(
        design.actuators, **{joint: dataclasses.replace(getattr(design.actuators, joint), **keys)}
    )
    return dataclasses.replace(design, actuators=actuators)


@pytest.mark.parametrize("seed", [3, 4])
def test_a_lower_continuous_torque_binds_exactly(seed):
    rng, design, position, gait = _random_motor_case(seed)
    unloaded = analyze_gait(design, gait, Payload(0.0, position), limits=False)
    joint = LEG_JOINTS[int(rng.integers(1, 3))]  # hip or knee
    rms = unloaded.electrical.per_joint[joint].rms_torque  # its worst leg's, unloaded
    design = _lowered(design, joint, continuous_torque=rms * rng.uniform(1.1, 1.4))
    found = _check_against_bisection(design, gait, position, "continuous_torque")
    assert found.limited_by.joint == joint


@pytest.mark.parametrize("seed", [5, 6])
def test_a_lower_bus_voltage_binds_exactly_on_the_voltage(seed):
    rng, design, position, gait = _random_motor_case(seed)
    unloaded = analyze_gait(design, gait, Payload(0.0, position), limits=False)
    volts = max(figures.peak_voltage for figures in unloaded.electrical.per_joint.values())
    bus = Battery(capacity=1e3, specific_energy=1e4, voltage=volts * rng.uniform(1.1, 1.4))
    design = dataclasses.replace(design, battery=bus)  # one bus for every motor
    found = _check_against_bisection(design, gait, position, "voltage")
    assert found.limited_by.joint in LEG_JOINTS


@pytest.mark.parametrize("turning", [1.0, -1.0])
def test_the_voltage_bound_is_exact_where_the_torque_changes_sign(turning):
    """τ(m) = a + m·b crosses zero at every sample before the supply binds: motoring turns
    to braking (ω > 0) or braking to motoring (ω < 0), so a bound kept on the unloaded
    branch, or on one branch for both signs, is wrong. The oracle bisects on motor_loads."""
    rng = np.random.default_rng(7)
    actuators = Actuators(*(_random_actuator(rng, voltage=30.0) for _ in LEG_JOINTS))
    shape = (40, 6, 3)
    speeds = turning * rng.uniform(0.05, 0.5, shape)  # back-EMF well within the supply
    base = rng.uniform(1, 10, shape)  # τ₀ > 0 ...
    slope = -rng.uniform(1.0, 2.0, shape)  # ... falling through zero by m = 10
    legs = tuple(f"leg{i}" for i in range(6))
    mass, cause = _voltage_bound(legs, base, slope, speeds, actuators, 30.0)

    def within(m: float) -> bool:
        loads = motor_loads(base + m * slope, speeds, actuators, legs, supply=30.0)
        return bool((loads.ratios[2] <= 1).all())

    low, high = 0.0, 1e6
    assert within(low) and not within(high)
    while high - low > 1e-10 * high:
        middle = (low + high) / 2
        low, high = (middle, high) if within(middle) else (low, middle)
    assert mass == pytest.approx(low, rel=1e-8)
    assert (base + mass * slope < 0).all()  # every torque changed sign on the way
    assert cause.kind == "voltage"
    broke = motor_loads(base + high * (1 + 1e-6) * slope, speeds, actuators, legs).ratios[2] > 1
    assert broke[legs.index(cause.leg), LEG_JOINTS.index(cause.joint)]


def test_without_actuators_neither_continuous_torque_nor_voltage_bounds():
    design = HexapodDesign.from_ratios(0.1, 0.45)
    found = walking_payload_capacity(HexapodModel(design))
    assert found.limited_by.kind in ("torque", "zmp")


MOTOR_FILE = """l1 = 0.1
l2 = 0.25
l3 = 0.3
body_mass = 20.0
[actuators.root]
catalog = "hd_cha_17a_e_100"
[actuators.hip]
catalog = "hd_cha_25a_100"
continuous_torque = 80.0
[actuators.knee]
catalog = "hd_cha_17a_e_100"
[battery]
capacity = 500
specific_energy = 200
voltage = 680
"""
"""A design whose hips' continuous torque, lowered below the catalog's, binds walking (one
680 V bus for its 48 V and 680 V drives)."""


def test_loads_json_and_the_study_see_the_continuous_torque_bind(tmp_path, capsys):
    path = tmp_path / "robot.toml"
    path.write_text(MOTOR_FILE)
    design = load_design(path)
    model = HexapodModel(design)
    oracle = _bisect(design, model, Gait(), None, 100.0)
    assert run_cli(["loads", "--design", str(path), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)["walking_payload_capacity"]
    assert printed["mass"] == pytest.approx(oracle, rel=1e-6)
    assert printed["limited_by"]["kind"] == "continuous_torque"
    assert printed["limited_by"]["joint"] == "hip"
    specs = [METRICS.walking_payload_capacity]
    measured = evaluate(design, specs, model=model)  # studies, decide
    assert measured.metrics.walking_payload_capacity == pytest.approx(oracle, rel=1e-6)
    cause = measured.causes.walking_payload_capacity
    assert cause is not None and cause.kind == "continuous_torque"


def test_the_capacity_is_where_the_gait_turns_infeasible():
    """The capacity and ``feasible`` agree: just under it feasible, just over it a foot slides."""
    design = HexapodDesign(rated_torques=(1e5, 1e5, 1e5))
    model, gait, position = HexapodModel(design), Gait(samples=60), (1.0, 0.3, 0.05)
    found = walking_payload_capacity(model, gait, position)
    assert found.walks and found.limited_by.kind == "slide" and found.mass > 0
    below, above = (
        analyze_gait(design, gait, Payload(found.mass * f, position), model=model, limits=False)
        for f in (1 - 1e-6, 1 + 1e-6)
    )
    assert below.feasible and not below.slips
    assert not above.feasible and above.walkable and above.tipping is None
    assert [slip.cause for slip in above.slips] == [found.limited_by]


def test_the_zmp_bound_is_where_the_gaits_zmp_reaches_the_polygons_edge():
    """The capacity's ZMP bound alone, against a bisection on the gait's own ZMP margin."""
    design = HexapodDesign(rated_torques=(1e5, 1e5, 1e5))
    model, gait, position = HexapodModel(design), Gait(samples=60), (1.0, 0.3, 0.05)
    walker = Walker(model, gait, Payload(0.0, position))
    walk = walker.stride(gait.stride)
    probe = payload_wrench(walker.payload.point(model), PROBE_MASS, walker.gravity_vector)
    rnea = walker.loads(gait.stride, walk, gait.period).rnea
    mass, cause = _zmp_bound(walker, walk, rnea, probe)

    def margin(m: float) -> float:
        walked = analyze_gait(design, gait, Payload(m, position), model=model, limits=False)
        return walked.min_zmp_margin

    low, high = 0.0, 2 * mass + 1
    assert margin(low) > 0 > margin(high)
    while high - low > 1e-7:
        middle = (low + high) / 2
        low, high = (middle, high) if margin(middle) >= 0 else (low, middle)
    assert cause.kind == "zmp" and mass == pytest.approx(low, abs=1e-6)


WALKED = "[gait]\nstride = 0.03\nstep_height = 0.02\nperiod = 0.6\nsamples = 48\n"
"""A gait table both kinds of robot walk (Kraby's legs are 20 cm long)."""


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_loads_walking_capacity_is_where_the_design_files_gait_breaks(tmp_path, capsys, kind):
    """The oracle: the gait analysis of the model built here from what the design file names
    (the template's design, the robot file imported), at the capacity ± 1e-6 of it."""
    target = tmp_path / "robot.toml"
    if kind == "template":
        target.write_text(WALKED)
        model = HexapodModel(load_design(target))
    else:
        assert run_cli(["design", "import", KRABY, "-o", str(target)]) == 0
        with target.open("a") as file:
            file.write("\n" + WALKED)
        model = ImportedHexapodModel(import_robot(KRABY))
    loads = robot_json(capsys, ["loads", "--design", str(target), "--json"])
    capacity = loads["walking_payload_capacity"]
    assert capacity["walks"] and capacity["mass"] > 0.1
    gait = Gait(stride=0.03, step_height=0.02, period=0.6, samples=48)

    def holds(mass):
        walked = analyze_gait(model.design, gait, Payload(mass), model=model, limits=False)
        return walked.walkable and walked.tipping is None and not walked.over_rating

    for factor, expected in ((1 - 1e-6, True), (1 + 1e-6, False)):
        mass = capacity["mass"] * factor
        assert holds(mass) is expected
        assert _walks(model.design, model, gait, mass, None) is expected
    if kind == "kraby":  # without a [gait] table a robot file walks its own gait, sized to it
        plain = robot_json(capsys, ["loads", *robot_argv(kind), "--json"])
        assert plain["walking_payload_capacity"]["walks"]


@pytest.mark.parametrize(("l1_ratio", "l3_ratio"), [(0.2, 0.435), (0.2, 0.205)])
def test_mirror_legs_that_bind_together_are_named_in_leg_order(l1_ratio, l3_ratio):
    """Mirror-image legs bind at the same payload: the first in leg order is named.

    Round-off never chooses between them (as the statics' capacity and the max speed do).
    Oracle: each joint's bound from the gait analysis itself, unloaded and with 1 kg (every
    torque affine in the payload), or its unloaded peak speed when one is over its rating.
    """
    l1, l2, l3 = ratio_lengths(l1_ratio, l3_ratio, 1.0)
    design = HexapodDesign(l1=l1, l2=l2, l3=l3)
    model, gait = HexapodModel(design), Gait()
    found = walking_payload_capacity(model, gait)
    unloaded = analyze_gait(design, gait, model=model, limits=False)
    speeds = np.abs(unloaded.joint_velocities).max(axis=0)  # (6, 3)
    rated = np.array(design.rated_torques)
    if (speeds > np.array(design.rated_speeds)).any():
        kind, bound = "speed", -speeds  # the fastest stops the walk
    else:
        loaded = analyze_gait(design, gait, Payload(1.0), model=model, limits=False)
        base, slope = unloaded.joint_torques, loaded.joint_torques - unloaded.joint_torques
        with np.errstate(divide="ignore", invalid="ignore"):
            up, down = (rated - base) / slope, (-rated - base) / slope
        bound = np.where(slope > 0, up, np.where(slope < 0, down, np.inf)).min(axis=0)
        kind = "torque"
    least = bound.min()
    tied = np.argwhere(bound <= least + 1e-9 * max(1.0, abs(least)))
    assert len({leg for leg, _ in tied}) >= 2  # the case: two legs tie
    leg, joint = tied[0]
    assert found is not None
    assert found.limited_by == Cause(kind, design.leg_names[leg], LEG_JOINTS[joint])
