"""The MuJoCo model of the URDF: the same masses, inertias and kinematics as Pinocchio's."""

from __future__ import annotations

import os

import numpy as np
import pinocchio as pin
import pytest
from robots import robot_of

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.exceptions import HexalegError
from hexaleg.statics.forces import Payload

if not os.environ.get("CI"):  # CI installs hexaleg[test], which includes the sim extra
    pytest.importorskip("mujoco")

import mujoco

from hexaleg.sim.model import (
    ServoGains,
    SimModel,
    contact_geom_name,
    reflected_inertia,
)

DESIGNS = [
    HexapodDesign(),
    HexapodDesign(l1=0.1, l2=0.5, l3=0.35, body_mass=30.0, layout="hexagon"),
]


@pytest.fixture(scope="module", params=[*DESIGNS, "kraby"], ids=["default", "hexagon", "kraby"])
def models(request):
    """Hexaleg's template at two designs, and a robot file: each model with its MuJoCo one."""
    if request.param == "kraby":
        model = robot_of("kraby").model
    else:
        model = HexapodModel(request.param)
    return model, SimModel(model)


def _random_configuration(model: HexapodModel, rng: np.random.Generator) -> np.ndarray:
    q = model.configuration(
        pin.SE3(pin.rpy.rpyToMatrix(*rng.uniform(-0.5, 0.5, 3)), rng.uniform(-1, 1, 3)),
        rng.uniform(-1.5, 1.5, size=(6, 3)),
    )
    return q


def _mujoco_at(sim: SimModel, q: np.ndarray):
    data = mujoco.MjData(sim.mj)
    data.qpos[:] = sim.qpos_of(q)
    mujoco.mj_forward(sim.mj, data)
    return data


def _velocity_map(model: HexapodModel, q: np.ndarray) -> np.ndarray:
    """T with v_mujoco = T v_pinocchio: MuJoCo's free joint moves in world axes, then turns
    in body axes; Pinocchio's does both in body axes."""
    t = np.eye(model.model.nv)
    t[:3, :3] = pin.XYZQUATToSE3(q[:7]).rotation
    return t


def test_mass_matrix_equals_pinocchios_at_random_configurations(models):
    model, sim = models
    rng = np.random.default_rng(7)
    for _ in range(5):
        q = _random_configuration(model, rng)
        data = _mujoco_at(sim, q)
        full = np.zeros((sim.mj.nv, sim.mj.nv))
        mujoco.mj_fullM(sim.mj, data, full)
        order = _dof_order(model, sim)
        t = _velocity_map(model, q)[np.ix_(order, order)]
        expected = pin.crba(model.model, model.data, q)
        expected = np.triu(expected) + np.triu(expected, 1).T
        np.testing.assert_allclose(
            t.T @ full[np.ix_(order, order)] @ t, expected, atol=1e-10 * np.abs(expected).max()
        )


def test_gravity_equals_pinocchios(models):
    model, sim = models
    q = _random_configuration(model, np.random.default_rng(3))
    data = _mujoco_at(sim, q)
    order = _dof_order(model, sim)
    mujoco_gravity = _velocity_map(model, q).T @ data.qfrc_bias[order]  # at rest: gravity only
    expected = pin.computeGeneralizedGravity(model.model, model.data, q)
    np.testing.assert_allclose(mujoco_gravity, expected, atol=1e-9 * np.abs(expected).max())


def _dof_order(model: HexapodModel, sim: SimModel) -> np.ndarray:
    """MuJoCo dof index of each Pinocchio velocity index."""
    order = np.arange(model.model.nv)
    for i, leg in enumerate(model.leg_names):
        order[model.leg_v_indices(leg)] = sim.dof[i]
    return order


def test_body_masses_are_the_urdfs_and_the_payload_is_a_point_mass_at_its_point():
    design = HexapodDesign()
    model = HexapodModel(design)
    payload = Payload(25.0, (0.1, -0.05, 0.08))
    sim = SimModel(model, payload)
    assert sim.mj.body_mass.sum() == pytest.approx(design.total_mass + 25.0, rel=1e-12)
    body = mujoco.mj_name2id(sim.mj, mujoco.mjtObj.mjOBJ_BODY, "payload")
    assert sim.mj.body_mass[body] == 25.0
    np.testing.assert_allclose(sim.mj.body_pos[body], payload.position)
    data = _mujoco_at(sim, model.nominal_configuration())
    base = data.xpos[sim.base]
    robot_com = pin.centerOfMass(model.model, model.data, model.nominal_configuration())
    total = design.total_mass + 25.0
    expected = (design.total_mass * robot_com + 25.0 * (base + payload.position)) / total
    np.testing.assert_allclose(data.subtree_com[sim.base], expected, atol=1e-12)


def test_feet_are_spheres_on_the_foot_frames_and_the_floor_lies_one_radius_down(models):
    model, sim = models
    q = model.nominal_configuration()
    data = _mujoco_at(sim, q)
    # the foot sphere the template's URDF draws; a robot file's documented 5 mm one
    radius = 0.005 if model.own_legs is not None else model.design.link_radius * 1.2
    feet = model.foot_positions(q)
    for leg, geom, foot in zip(model.leg_names, sim.contacts, feet, strict=True):
        assert mujoco.mj_id2name(sim.mj, mujoco.mjtObj.mjOBJ_GEOM, geom) == contact_geom_name(leg)
        assert sim.mj.geom_size[geom, 0] == pytest.approx(radius)
        np.testing.assert_allclose(data.geom_xpos[geom], foot, atol=1e-12)
    assert data.geom_xpos[sim.floor][2] == pytest.approx(-radius)
    mujoco.mj_forward(sim.mj, data)
    touching = {
        frozenset((int(c.geom1), int(c.geom2))) for c in data.contact[: data.ncon]
    }  # the nominal stance: every foot just touches the floor, nothing else does
    assert touching <= {frozenset((sim.floor, int(g))) for g in sim.contacts}


def test_reflected_inertia_equals_the_default_legs_hand_computed():
    design = HexapodDesign()
    l1, l2, l3 = design.lengths
    r, rho, foot = design.link_radius, design.link_linear_density, 1e-3
    m1, m2, m3 = rho * l1, rho * l2, rho * l3
    rt = 0.8 * r  # the tibia is thinner
    # nominal stance: coxa and femur horizontal, tibia hanging straight down
    root = (
        m1 * (3 * r**2 + l1**2) / 12 + m1 * (l1 / 2) ** 2
        + m2 * (3 * r**2 + l2**2) / 12 + m2 * (l1 + l2 / 2) ** 2
        + m3 * rt**2 / 2 + m3 * (l1 + l2) ** 2
        + 0.4 * foot * r**2 + foot * (l1 + l2) ** 2
    )  # fmt: skip
    hip = (
        m2 * (3 * r**2 + l2**2) / 12 + m2 * (l2 / 2) ** 2
        + m3 * (3 * rt**2 + l3**2) / 12 + m3 * (l2**2 + (l3 / 2) ** 2)
        + 0.4 * foot * r**2 + foot * (l2**2 + l3**2)
    )  # fmt: skip
    knee = m3 * (3 * rt**2 + l3**2) / 12 + m3 * (l3 / 2) ** 2 + 0.4 * foot * r**2 + foot * l3**2
    own = np.array([root, hip, knee])
    np.testing.assert_allclose(reflected_inertia(HexapodModel(design), 0.0), own, rtol=1e-12)
    # a standing foot carrying m: the foot moves at (l1 + l2)·θ̇1 (the root turns the whole
    # leg), √(l2² + l3²)·θ̇2 (hip to foot) and l3·θ̇3 (knee to foot)
    lever = np.array([(l1 + l2) ** 2, l2**2 + l3**2, l3**2])
    np.testing.assert_allclose(
        reflected_inertia(HexapodModel(design), 20.0), own + 20.0 * lever, rtol=1e-12
    )
    third = design.total_mass / 3  # the default: a tripod foot's share
    inertia = reflected_inertia(HexapodModel(design))
    np.testing.assert_allclose(inertia, own + third * lever, rtol=1e-12)
    gains = ServoGains.from_bandwidth(HexapodModel(design), bandwidth=5.0, damping_ratio=0.7)
    omega = 2 * np.pi * 5.0
    np.testing.assert_allclose(gains.stiffness, inertia * omega**2, rtol=1e-12)
    np.testing.assert_allclose(gains.damping, 2 * 0.7 * inertia * omega, rtol=1e-12)


def test_servo_applies_feed_forward_plus_pd_on_the_tracking_error(models):
    model, sim = models
    rng = np.random.default_rng(11)
    q = model.nominal_configuration()
    data = _mujoco_at(sim, q)
    data.qvel[sim.dof.ravel()] = rng.uniform(-1, 1, 18)
    q_ref = model.joint_angles(q) + rng.uniform(-0.1, 0.1, (6, 3))
    v_ref, feed = rng.uniform(-1, 1, (6, 3)), rng.uniform(-20, 20, (6, 3))
    data.ctrl[:] = sim.command(q_ref, v_ref, feed)
    mujoco.mj_forward(sim.mj, data)
    kp, kd = np.array(sim.gains.stiffness), np.array(sim.gains.damping)
    q_now, v_now = data.qpos[sim.qpos], data.qvel[sim.dof]
    # on the model's joints: q = s·θ + o (the identity on the template's), q̇ = s·θ̇, s·τ
    signs = np.array([model.joint_signs(leg) for leg in model.leg_names])
    legs = zip(model.leg_names, q_ref, strict=True)
    q_set = np.array([model.joint_values(leg, theta) for leg, theta in legs])
    expected = signs * feed + kp * (q_set - q_now) + kd * (signs * v_ref - v_now)
    np.testing.assert_allclose(data.actuator_force[sim.actuators], expected, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(data.qfrc_actuator[sim.dof], expected, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize(
    ("gains", "field"),
    [
        (((-1.0, 1.0, 1.0), (1.0, 1.0, 1.0)), "stiffness.root"),
        (((1.0, 0.0, 1.0), (1.0, 1.0, 1.0)), "stiffness.hip"),
        (((1, 1, 1), (1, float("nan"), 1)), "damping.hip"),
    ],
)
def test_invalid_gains_are_refused_naming_the_field(gains, field):
    with pytest.raises(HexalegError, match=field):
        ServoGains(*gains)


def test_missing_mujoco_is_one_line_naming_the_extra(monkeypatch):
    import builtins

    from hexaleg.sim._mujoco import require_mujoco

    real_import = builtins.__import__

    def no_mujoco(name, *args, **kwargs):
        if name == "mujoco":
            raise ImportError("No module named 'mujoco'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_mujoco)
    with pytest.raises(HexalegError, match=r"pip install 'hexaleg\[sim\]'") as error:
        require_mujoco()
    assert "\n" not in str(error.value)
