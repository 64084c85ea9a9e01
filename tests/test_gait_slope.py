"""Walking on a slope against inverse dynamics written here from the definitions.

The oracle: the body stays parallel to the plane and the feet stand on it, so in the
plane's frame only gravity turns, g·(−sin α cos φ, −sin α sin φ, −cos α). Pinocchio's RNEA
on the design's own model with ``model.gravity`` set to that vector gives the generalized
forces of the motion; the standing feet's forces are the least-norm solution of the six
base rows, Jᵀ_base f = RNEA[0:6], solved here by least squares on Pinocchio's own foot
Jacobians; the joint torques are RNEA[6:] − Σ Jᵀ_joints f. None of hexaleg's walker code
(its split, its equilibrium rows, its Jacobians) is used. The zero-moment point is checked
as the centre of pressure of those forces on the plane, and the walk's physics as sums: the
average push of the ground is the weight's share along the plane, the positive work
uphill at least the potential energy gained.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest
from conftest import run_cli

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.gait import Gait, Walker, analyze_gait, max_speed
from hexaleg.gait.analysis import analyze_walker
from hexaleg.gait.capacity import walker_capacity, walking_payload_capacity
from hexaleg.statics import GRAVITY, Payload
from hexaleg.statics.ground import Ground

GAIT = Gait(samples=40)
"""A tripod period sampled coarsely: the oracle runs a Python loop per sample."""


def tilted(slope: float, heading: float) -> np.ndarray:
    """Gravity in the plane's frame [m/s²], from the definition (module docstring)."""
    return GRAVITY * np.array(
        [-math.sin(slope) * math.cos(heading), -math.sin(slope) * math.sin(heading),
         -math.cos(slope)]
    )  # fmt: skip


def oracle(model: HexapodModel, walked, gravity: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Joint torques (N, 6, 3) and foot forces (N, 6, 3) of the walk's motion under ``gravity``."""
    pinocchio = pin.Model(model.model)
    pinocchio.gravity.linear = gravity
    data = pinocchio.createData()
    feet = [model.foot_frame_id(leg) for leg in walked.legs]
    columns = np.array([model.leg_v_indices(leg) for leg in walked.legs])  # (6, 3)
    torques, forces = np.zeros((len(walked.times), 6, 3)), np.zeros((len(walked.times), 6, 3))
    for k in range(len(walked.times)):
        q = walked.configurations[k]
        v, a = walked.generalized_velocities[k], walked.generalized_accelerations[k]
        generalized = pin.rnea(pinocchio, data, q, v, a)
        standing = np.flatnonzero(walked.stance[k])
        jacobian = np.vstack(  # (3·n, nv): each standing foot's point, world axes
            [
                pin.computeFrameJacobian(pinocchio, data, q, feet[i], pin.LOCAL_WORLD_ALIGNED)[:3]
                for i in standing
            ]
        )
        solved = np.linalg.lstsq(jacobian[:, :6].T, generalized[:6], rcond=None)[0]
        pushed = generalized - jacobian.T @ solved
        np.testing.assert_allclose(pushed[:6], 0.0, atol=1e-8)  # the body balances
        forces[k, standing] = solved.reshape(-1, 3)
        torques[k] = pushed[columns]
    return torques, forces


@pytest.fixture(scope="module")
def model() -> HexapodModel:
    return HexapodModel(HexapodDesign(nominal_angles=(0.0, -0.2, -1.7)))


@pytest.mark.parametrize(
    ("degrees", "heading", "walking"),
    [(12.0, None, 0.0), (-12.0, None, 0.0), (15.0, math.pi / 2, 0.0), (8.0, 0.7, 0.3),
     (0.0, None, 0.0)],
)  # fmt: skip
def test_slope_torques_and_forces_equal_rnea_with_tilted_gravity(model, degrees, heading, walking):
    """Uphill, downhill, across, off the fall line with the gait turned, and level."""
    gait = GAIT.replace(heading=walking)
    ground = Ground(math.radians(degrees), heading)
    walked = analyze_gait(model.design, gait, model=model, ground=ground, limits=False)
    rises = walking if heading is None else heading
    torques, forces = oracle(model, walked, tilted(math.radians(degrees), rises))
    np.testing.assert_allclose(walked.joint_torques, torques, atol=1e-8, rtol=1e-9)
    np.testing.assert_allclose(walked.foot_forces, forces, atol=1e-8, rtol=1e-9)
    level = analyze_gait(model.design, gait, model=model, limits=False)
    np.testing.assert_array_equal(walked.joint_angles, level.joint_angles)  # feet on the plane


def test_a_walkers_shared_walk_and_loads_are_its_own_grounds(model):
    """Walkers of one model, level and on a slope, each analysed after the other: each one's
    cached walk and loads hold its own gravity (the RNEA oracle), and another payload's
    walker (the capacity's unloaded one) keeps the ground and the safety factor."""
    ground = Ground(math.radians(12.0), math.pi / 2)
    level, sloped = Walker(model, GAIT), Walker(model, GAIT, ground=ground, safety_factor=1.5)
    for walker in (level, sloped, level, sloped):  # each served from its cache the 2nd time
        walked = analyze_walker(walker, limits=False)
        gravity = walker.ground.gravity(GAIT.heading)
        torques, forces = oracle(model, walked, gravity)
        np.testing.assert_allclose(walked.joint_torques, torques, atol=1e-8, rtol=1e-9)
        np.testing.assert_allclose(walked.foot_forces, forces, atol=1e-8, rtol=1e-9)
    assert walker_capacity(sloped) == walking_payload_capacity(
        model, GAIT, ground=ground, safety_factor=1.5
    )
    carried = sloped.carrying(Payload(3.0))
    assert (carried.ground, carried.safety_factor, carried.payload.mass) == (ground, 1.5, 3.0)
    with pytest.raises(AttributeError):
        level.ground = ground  # type: ignore[misc]  # a cached walk's ground never changes


def test_the_zmp_is_the_centre_of_pressure_on_the_plane(model):
    ground = Ground(math.radians(10.0), math.pi / 4)
    walked = analyze_gait(model.design, GAIT, model=model, ground=ground, limits=False)
    _, forces = oracle(model, walked, ground.gravity(GAIT.heading))
    feet = walked.feet + walked.configurations[:, None, :3]  # the plane's frame
    np.testing.assert_allclose(feet[walked.stance][:, 2], 0.0, atol=1e-12)  # on the plane
    normal = forces[..., 2]
    pressure = (normal[..., None] * feet[..., :2]).sum(axis=1) / normal.sum(axis=1)[:, None]
    np.testing.assert_allclose(walked.zmp, pressure, atol=1e-9)


def test_the_ground_pushes_the_weights_share_along_the_plane(model):
    """Over a period the momentum returns: the feet's mean push is −M·g, tilted."""
    for degrees, heading in ((10.0, None), (-10.0, None), (10.0, math.pi / 2)):
        ground = Ground(math.radians(degrees), heading)
        walked = analyze_gait(model.design, Gait(samples=200), model=model, ground=ground,
                              limits=False)  # fmt: skip
        mean = walked.foot_forces.sum(axis=1).mean(axis=0)
        weight = walked.mass * ground.gravity(0.0)
        np.testing.assert_allclose(mean, -weight, atol=1e-5 * walked.mass * GRAVITY)


def test_uphill_costs_the_potential_energy_and_downhill_less(model):
    slope = math.radians(10.0)
    works = {}
    for name, degrees in (("up", 10.0), ("level", 0.0), ("down", -10.0)):
        walked = analyze_gait(model.design, Gait(), model=model,
                              ground=Ground(math.radians(degrees)), limits=False)  # fmt: skip
        works[name] = walked.metrics.positive_work
    climbed = Gait().stride / Gait().duty_factor * math.sin(slope)  # per period [m]
    assert works["up"] >= walked.mass * GRAVITY * climbed
    assert works["up"] > works["level"] > works["down"]


def test_the_level_ground_is_the_same_whatever_its_heading(model):
    plain = analyze_gait(model.design, GAIT, model=model, limits=False)
    turned = analyze_gait(model.design, GAIT, model=model, ground=Ground(0.0, 1.0), limits=False)
    np.testing.assert_array_equal(plain.joint_torques, turned.joint_torques)
    assert plain.max_speed == turned.max_speed


def test_a_steep_slope_slides_the_feet_and_names_them():
    """tan 35° = 0.70 > μ = 0.6: some foot needs more than the average ratio, hence > μ."""
    strong = HexapodDesign(nominal_angles=(0.0, -0.2, -1.7), rated_torques=(1e4, 1e4, 1e4))
    model, ground = HexapodModel(strong), Ground(math.radians(35.0), friction=0.6)
    walked = analyze_gait(model.design, GAIT, model=model, ground=ground, limits=False)
    assert not walked.feasible and walked.slips
    forces = walked.foot_forces
    share = np.hypot(*forces.sum(axis=1)[:, :2].T) / forces.sum(axis=1)[:, 2]
    assert walked.friction_needed >= share.max() - 1e-12  # |Σ f_t| ≤ Σ|f_t| ≤ r·Σ f_n
    slip = walked.slips[0]
    with np.errstate(divide="ignore", invalid="ignore"):  # swinging feet push nothing
        ratios = np.hypot(forces[..., 0], forces[..., 1]) / forces[..., 2]
    k, i = int(np.argmin(np.abs(walked.times - slip.time))), walked.legs.index(slip.leg)
    assert ratios[k, i] == pytest.approx(slip.ratio, rel=1e-12) and slip.ratio > 0.6
    assert walked.infeasible_because.startswith(f"{slip.leg} foot slides at t = ")
    capacity = walking_payload_capacity(model, GAIT, ground=ground)
    assert not capacity.walks and capacity.limited_by.kind == "slide"


def _feasible(model, gait, ground, mass=0.0) -> bool:
    walked = analyze_gait(model.design, gait, Payload(mass), model=model, ground=ground,
                          limits=False)  # fmt: skip
    return walked.feasible


@pytest.mark.parametrize("degrees", [8.0, -8.0])
def test_the_walking_capacity_on_a_slope_equals_a_bisection(model, degrees):
    ground = Ground(math.radians(degrees))
    found = walking_payload_capacity(model, GAIT, ground=ground)
    assert found.walks and found.mass > 0
    low, high = 0.0, 2 * found.mass + 1
    while high - low > 1e-7:
        middle = (low + high) / 2
        low, high = (middle, high) if _feasible(model, GAIT, ground, middle) else (low, middle)
    assert found.mass == pytest.approx(low, abs=1e-6)
    level = walking_payload_capacity(model, GAIT)
    assert found.mass != pytest.approx(level.mass, rel=1e-3)  # the slope changes it


def test_the_max_speed_on_a_slope_equals_a_bisection(model):
    ground = Ground(math.radians(6.0), math.pi / 2)
    limit = max_speed(Walker(model, GAIT, ground=ground))
    assert 0 < limit.value and limit.stride == GAIT.stride
    low, high = 0.2, 50.0  # periods [s]
    assert not _feasible(model, GAIT.replace(period=low), ground)
    while high - low > 1e-9 * high:
        middle = (low + high) / 2
        low, high = (low, middle) if _feasible(model, GAIT.replace(period=middle), ground) else (
            middle, high)  # fmt: skip
    assert limit.period == pytest.approx(high, rel=1e-7)


@pytest.mark.parametrize(
    ("argv", "fragment"),
    [
        (["--slope-deg", "61"], "--slope-deg = 61 is not valid: must lie in [-60, 60] [°]"),
        (["--slope-deg", "-70"], "--slope-deg"),
        (["--slope-heading", "9"], "--slope-heading"),
        (
            ["--motor-safety-factor", "0.9"],
            "--motor-safety-factor = 0.9 is not valid: must lie in [1, 100]",
        ),
        (["--friction", "0"], "friction"),
    ],
)
def test_bad_ground_and_margin_options_are_one_line_and_exit_2(capsys, argv, fragment):
    assert run_cli(["gait", "--samples", "20", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err and fragment in err


def test_gait_json_states_the_ground_and_the_table_names_it(capsys):
    argv = ["gait", "--samples", "40", "--slope-deg", "-10", "--slope-heading", "3.1416"]
    assert run_cli([*argv, "--json"]) == 0
    walked = __import__("json").loads(capsys.readouterr().out)
    assert walked["ground"]["slope_deg"] == pytest.approx(-10.0)
    assert walked["ground"]["heading"] == 3.1416 and walked["ground"]["friction"] == 0.6
    assert walked["friction_needed"] > 0 and walked["slips"] == []
    assert run_cli(argv) == 0
    out = capsys.readouterr().out
    assert "-10° slope rising along 3.142 rad, walked uphill, μ = 0.6" in out
