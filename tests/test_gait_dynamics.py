"""Gait inverse dynamics against independent oracles.

- The Lagrange equations of one 3-DOF leg, written out here from the paper's D-H kinematics
  and the link masses and inertias read from the leg's URDF (M(q) from the link Jacobians,
  Christoffel symbols and gravity from exact complex-step derivatives), equal the torques
  the gait computes for a swinging leg (the body moves at constant velocity without
  turning: an inertial frame) and Pinocchio's fixed-base RNEA, to 1e-9.
- The free-flyer rows balance at every sample, with Pinocchio's own foot Jacobians, the
  standing feet's forces are their least-norm balance (NumPy's lstsq) in every pattern, and
  the ZMP equals the one from Pinocchio's centroidal momentum rate: on each kind of robot
  (hexaleg's template, a robot file).
- The static limit equals the statics (``loads``) at the nominal stance.
- A payload's torques from its closed-form wrench equal RNEA with its mass on the body.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest
from robots import KINDS, robot_of

from hexaleg import HexapodDesign, HexapodModel, LegModel
from hexaleg.gait import Gait, Walker, analyze_gait
from hexaleg.gait.dynamics import carried_load, payload_wrench
from hexaleg.statics import GRAVITY, Payload, analyze_loads
from hexaleg.statics.ground import Ground

# -- the Lagrange oracle -------------------------------------------------------------------


def _rpy(r: float, p: float, y: float) -> np.ndarray:
    cr, sr, cp, sp, cy, sy = (f(a) for a in (r, p, y) for f in (math.cos, math.sin))
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def urdf_bodies(urdf: str, l3: float) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """(mass, centre of mass, inertia about it) of coxa, femur and tibia (+ its foot), each
    in its own link frame, read from the URDF's <inertial> elements."""
    root = ET.fromstring(urdf)
    bodies = {}
    for link in root.iter("link"):
        inertial = link.find("inertial")
        if inertial is None:
            continue
        origin = inertial.find("origin")
        xyz = np.zeros(3) if origin is None else np.array(origin.get("xyz").split(), float)
        rpy = (0.0, 0.0, 0.0) if origin is None else tuple(map(float, origin.get("rpy").split()))
        i = inertial.find("inertia").attrib
        tensor = np.array(
            [
                [i["ixx"], i["ixy"], i["ixz"]],
                [i["ixy"], i["iyy"], i["iyz"]],
                [i["ixz"], i["iyz"], i["izz"]],
            ],
            float,
        )
        rotation = _rpy(*rpy)
        bodies[link.get("name")] = (
            float(inertial.find("mass").get("value")),
            xyz,
            rotation @ tensor @ rotation.T,
        )
    coxa, femur, tibia, foot = (bodies[f"leg_{n}"] for n in ("coxa", "femur", "tibia", "foot"))
    # the foot rides on the tibia at (l3, 0, 0): combine the two rigid bodies
    m = tibia[0] + foot[0]
    foot_com = foot[1] + np.array([l3, 0.0, 0.0])
    com = (tibia[0] * tibia[1] + foot[0] * foot_com) / m
    inertia = np.zeros((3, 3))
    for mass, c, own in ((tibia[0], tibia[1], tibia[2]), (foot[0], foot_com, foot[2])):
        d = c - com
        inertia += own + mass * (d @ d * np.eye(3) - np.outer(d, d))
    return [coxa, femur, (m, com, inertia)]


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0 * c], [s, c, 0 * c], [0 * c, 0 * c, 1 + 0 * c]])


def _ry_down(a):
    """Rotation about −y by a: a positive hip or knee angle lifts the link (D-H, Table 1)."""
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0 * c, -s], [0 * c, 1 + 0 * c, 0 * c], [s, 0 * c, c]])


def _links(lengths, q):
    """Each link's frame (rotation, origin) in the leg-root frame, D-H chain (complex-safe)."""
    l1, l2, _ = lengths
    r1 = _rz(q[0])
    r2 = r1 @ _ry_down(q[1])
    r3 = r2 @ _ry_down(q[2])
    o1 = np.zeros(3) + 0 * q[0]
    o2 = o1 + r1 @ np.array([l1, 0.0, 0.0])
    o3 = o2 + r2 @ np.array([l2, 0.0, 0.0])
    return [(r1, o1), (r2, o2), (r3, o3)]


def _cross(a, b):
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )


def mass_matrix(lengths, bodies, q):
    """M(q) = Σ m Jvᵀ Jv + Jωᵀ (R I Rᵀ) Jω, the link Jacobians written out (complex-safe)."""
    links = _links(lengths, q)
    axes = [np.array([0.0, 0.0, 1.0]) + 0 * q[0]]
    axes += [links[0][0] @ np.array([0.0, -1.0, 0.0]), links[1][0] @ np.array([0.0, -1.0, 0.0])]
    origins = [link[1] for link in links]
    m_total = np.zeros((3, 3), dtype=np.result_type(q, float))
    for n, ((rotation, origin), (mass, com, inertia)) in enumerate(zip(links, bodies, strict=True)):
        c = origin + rotation @ com
        jv = np.zeros((3, 3), dtype=m_total.dtype)
        jw = np.zeros((3, 3), dtype=m_total.dtype)
        for j in range(n + 1):
            jv[:, j] = _cross(axes[j], c - origins[j])
            jw[:, j] = axes[j]
        world_inertia = rotation @ inertia @ rotation.T
        m_total += mass * jv.T @ jv + jw.T @ world_inertia @ jw
    return m_total


def potential(lengths, bodies, q, g=GRAVITY):
    """V(q) = Σ m g z_c [J]."""
    return sum(
        mass * g * (origin + rotation @ com)[2]
        for (rotation, origin), (mass, com, _) in zip(_links(lengths, q), bodies, strict=True)
    )


def _d(f, q, k, h=1e-30):
    """∂f/∂q_k by the complex step: exact to round-off for analytic f."""
    shifted = np.array(q, dtype=complex)
    shifted[k] += 1j * h
    return np.imag(f(shifted)) / h


def lagrange_torques(lengths, bodies, q, qd, qdd):
    """τ = M(q)·q̈ + Σ Γ_kij q̇_i q̇_j + ∂V/∂q: the Euler–Lagrange equations of the leg."""
    m = mass_matrix(lengths, bodies, q)
    dm = [_d(lambda x: mass_matrix(lengths, bodies, x), q, k) for k in range(3)]
    coriolis = np.zeros(3)
    for k in range(3):
        for i in range(3):
            for j in range(3):
                gamma = 0.5 * (dm[i][k, j] + dm[j][k, i] - dm[k][i, j])
                coriolis[k] += gamma * qd[i] * qd[j]
    gravity = np.array([_d(lambda x: potential(lengths, bodies, x), q, k) for k in range(3)])
    return m @ qdd + coriolis + gravity


# -- tests ---------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def walked(hexapod_model):
    return analyze_gait(
        hexapod_model.design, Gait(period=1.2, samples=60), Payload(25.0, (0.1, -0.05, 0.1)),
        model=hexapod_model, limits=False,
    )  # fmt: skip


def test_the_lagrange_equations_give_the_swinging_legs_torques(walked, default_design):
    bodies = urdf_bodies(LegModel(default_design).urdf, default_design.l3)
    leg_model = LegModel(default_design)
    checked = 0
    for k in range(len(walked.times)):
        for leg in np.flatnonzero(~walked.stance[k]):
            q = walked.joint_angles[k, leg]
            qd = walked.joint_velocities[k, leg]
            qdd = walked.joint_accelerations[k, leg]
            expected = lagrange_torques(default_design.lengths, bodies, q, qd, qdd)
            np.testing.assert_allclose(walked.joint_torques[k, leg], expected, rtol=0, atol=1e-9)
            fixed = pin.rnea(leg_model.model, leg_model.data, q, qd, qdd)
            np.testing.assert_allclose(fixed, expected, rtol=0, atol=1e-9)
            checked += 1
    assert checked == 3 * len(walked.times)  # a tripod: three legs swing at every sample
    assert np.abs(walked.joint_velocities).max() > 0.5  # a real motion, not a pose


def test_the_lagrange_oracle_holds_on_random_motions(default_design):
    bodies = urdf_bodies(LegModel(default_design).urdf, default_design.l3)
    leg_model = LegModel(default_design)
    rng = np.random.default_rng(3)
    for _ in range(20):
        q, qd, qdd = rng.uniform(-2, 2, size=(3, 3))
        expected = lagrange_torques(default_design.lengths, bodies, q, qd, qdd)
        np.testing.assert_allclose(
            pin.rnea(leg_model.model, leg_model.data, q, qd, qdd), expected, atol=1e-9
        )


def _foot_jacobians(model: HexapodModel, q: np.ndarray) -> dict[str, np.ndarray]:
    pin.computeJointJacobians(model.model, model.data, q)
    pin.updateFramePlacements(model.model, model.data)
    return {
        leg: pin.getFrameJacobian(
            model.model, model.data, model.foot_frame_id(leg), pin.LOCAL_WORLD_ALIGNED
        )[:3]
        for leg in model.leg_names
    }


def _generalized(model, payload, q, v, a):
    """RNEA of the robot plus the payload's weight through the body Jacobian (as the statics)."""
    tau = pin.rnea(model.model, model.data, q, v, a).copy()
    pin.computeJointJacobians(model.model, model.data, q)
    pin.updateFramePlacements(model.model, model.data)
    frame = pin.getFrameJacobian(model.model, model.data, model.base_frame, pin.LOCAL_WORLD_ALIGNED)
    body = model.data.oMf[model.base_frame]
    offset = body.rotation @ np.array(payload.position)
    point = frame[:3] - pin.skew(offset) @ frame[3:]
    return tau - point.T @ (payload.mass * np.array([0.0, 0.0, -GRAVITY]))


@pytest.fixture(scope="module", params=KINDS)
def robot_walked(request):
    """Each kind of robot walking a period: the template as ``walked``, Kraby a small gait."""
    robot = robot_of(request.param)
    small = request.param != "template"
    gait = (
        Gait(stride=0.03, step_height=0.02, period=0.8, samples=60)
        if small
        else Gait(period=1.2, samples=60)
    )
    payload = Payload(0.4, (0.01, -0.005, 0.01)) if small else Payload(25.0, (0.1, -0.05, 0.1))
    walked = analyze_gait(robot.design, gait, payload, model=robot.model, limits=False)
    return robot.model, walked


def test_free_flyer_rows_balance_at_every_sample(robot_walked):
    model, walked = robot_walked
    for k in range(len(walked.times)):
        q = walked.configurations[k]
        v, a = walked.generalized_velocities[k], walked.generalized_accelerations[k]
        tau = _generalized(model, walked.payload, q, v, a)
        jacobians = _foot_jacobians(model, q)
        for i, leg in enumerate(model.leg_names):
            tau -= jacobians[leg].T @ walked.foot_forces[k, i]
        np.testing.assert_allclose(tau[:6], 0.0, atol=1e-9)
        for i, leg in enumerate(model.leg_names):  # on θ: s·τ of the model's joints
            on_theta = model.joint_signs(leg) * tau[model.leg_v_indices(leg)]
            np.testing.assert_allclose(on_theta, walked.joint_torques[k, i], atol=1e-9)
    assert np.all(walked.foot_forces[~walked.stance] == 0.0)


@pytest.mark.parametrize("pattern", ["tripod", "tetrapod", "wave"])
def test_the_standing_feet_carry_each_sample_at_least_norm(hexapod_model, pattern):
    """The min-norm split: at each sample, the least-norm forces on the standing feet that
    balance the free-flyer rows. Oracle: NumPy's least-squares minimum-norm solution of
    those rows, written with Pinocchio's foot Jacobians and RNEA (a payload on the body)."""
    gait = Gait(pattern=pattern, period=1.2, samples=30)
    payload = Payload(25.0, (0.1, -0.05, 0.1))
    model = hexapod_model
    walked = analyze_gait(model.design, gait, payload, model=model, limits=False)
    for k in range(gait.samples):
        q = walked.configurations[k]
        v, a = walked.generalized_velocities[k], walked.generalized_accelerations[k]
        base = _generalized(model, payload, q, v, a)[:6]
        jacobians = _foot_jacobians(model, q)
        legs = np.flatnonzero(walked.stance[k])
        rows = np.hstack([jacobians[model.leg_names[i]][:, :6].T for i in legs])  # (6, 3n)
        least = np.linalg.lstsq(rows, base, rcond=None)[0].reshape(-1, 3)
        np.testing.assert_allclose(walked.foot_forces[k, legs], least, atol=1e-9)


def test_the_static_limit_equals_the_statics_at_the_nominal_stance(hexapod_model):
    payload = Payload(40.0, (0.2, 0.1, 0.05))
    walker = Walker(hexapod_model, Gait(step_height=0.0, samples=20), payload)
    walk = walker.stride(0.0)  # v = 0: every foot at its nominal foothold
    split = walker.loads(0.0, walk, math.inf).split
    standing_b = ("rf", "lm", "rr")  # a tripod stands on B while A swings, t < T/2
    loads = analyze_loads(hexapod_model.design, payload, stance=standing_b).nominal
    index = [hexapod_model.leg_names.index(leg) for leg in standing_b]
    for k in range(10):
        np.testing.assert_allclose(split.static_torques[k, index], loads.joint_torques, atol=1e-9)
        np.testing.assert_allclose(split.static_forces[k, index], loads.foot_forces, atol=1e-9)
    # and the slow walk tends to it: torques differ by O(S) + O(1/T²)
    slow = analyze_gait(
        hexapod_model.design, Gait(stride=1e-4, step_height=0.0, period=1000.0, samples=20),
        payload, model=hexapod_model, limits=False,
    )  # fmt: skip
    np.testing.assert_allclose(slow.joint_torques[0, index], loads.joint_torques, atol=0.05)
    # standing still, the ZMP is the centre of mass's footprint: its margin is the statics'
    assert slow.zmp_margin[0] == pytest.approx(loads.stability_margin, abs=1e-3)
    assert slow.min_zmp_margin == slow.zmp_margin.min()


def test_the_zmp_is_the_centroidal_momentum_rates(robot_walked):
    hexapod_model, walked = robot_walked
    model = pin.Model(hexapod_model.model)
    base = model.getJointId("root_joint")
    point = pin.Inertia(walked.payload.mass, np.array(walked.payload.position), np.zeros((3, 3)))
    model.inertias[base] = model.inertias[base] + point
    data = model.createData()
    mass = pin.computeTotalMass(model)
    assert mass == pytest.approx(walked.mass, abs=1e-12)
    for k in range(0, len(walked.times), 7):
        q = walked.configurations[k]
        v, a = walked.generalized_velocities[k], walked.generalized_accelerations[k]
        pin.computeCentroidalMomentumTimeVariation(model, data, q, v, a)
        com = data.com[0]
        rate = data.dhg  # about the centre of mass, world axes
        force = rate.linear + mass * np.array([0.0, 0.0, GRAVITY])
        x = com[0] - (rate.angular[1] + com[2] * force[0]) / force[2]
        y = com[1] + (rate.angular[0] - com[2] * force[1]) / force[2]
        np.testing.assert_allclose(walked.zmp[k], [x, y], atol=1e-9)


def test_a_random_design_balances_too():
    design = HexapodDesign(
        l1=0.15, l2=0.45, l3=0.5, body_length=0.8, nominal_angles=(0.1, 0.2, -1.7)
    )
    model = HexapodModel(design)
    walked = analyze_gait(
        design, Gait(pattern="wave", stride=0.15, heading=0.7, samples=24), model=model,
        limits=False,
    )  # fmt: skip
    for k in range(len(walked.times)):
        q = walked.configurations[k]
        v, a = walked.generalized_velocities[k], walked.generalized_accelerations[k]
        tau = pin.rnea(model.model, model.data, q, v, a).copy()
        for i, jac in enumerate(_foot_jacobians(model, q).values()):
            tau -= jac.T @ walked.foot_forces[k, i]
        np.testing.assert_allclose(tau[:6], 0.0, atol=1e-9)


@pytest.mark.parametrize(
    ("seed", "slope", "heading"), [(0, 0.0, None), (1, 0.0, None), (2, 0.2, 0.9), (3, -0.3, None)]
)
def test_a_payloads_loads_are_what_pinocchio_gives_with_its_mass_on_the_body(seed, slope, heading):
    # oracle: Pinocchio's RNEA on a copy of the model whose body inertia holds the point
    # mass (gravity tilted on a slope), split min-norm as any gait; against the closed-form
    # wrench the capacity uses, under the same gravity
    rng = np.random.default_rng(seed)
    design = HexapodDesign.from_ratios(rng.uniform(0.08, 0.2), rng.uniform(0.35, 0.6))
    model, gait = HexapodModel(design), Gait(stride=rng.uniform(0.1, 0.25))
    point, mass = tuple(rng.uniform([-0.3, -0.2, 0.0], [0.3, 0.2, 0.2])), rng.uniform(1, 20)
    ground = Ground(slope, heading)
    empty, loaded = (Walker(model, gait, Payload(m, point), ground=ground) for m in (0.0, mass))
    walk = empty.stride(gait.stride)
    with_mass = loaded.loads(gait.stride, walk, gait.period).split
    without = empty.loads(gait.stride, walk, gait.period).split
    gravity = GRAVITY * np.array(  # the plane's frame, from its definition
        [-math.sin(slope) * math.cos(gait.heading if heading is None else heading),
         -math.sin(slope) * math.sin(gait.heading if heading is None else heading),
         -math.cos(slope)]
    )  # fmt: skip
    wrench = payload_wrench(np.array(point), mass, gravity)
    found = carried_load(empty.frames, empty.phases, walk.paths.position, walk.motion, wrench)
    torques = with_mass.torques(gait.period) - without.torques(gait.period)
    forces = with_mass.forces(gait.period) - without.forces(gait.period)
    np.testing.assert_allclose(found.torques, torques, atol=1e-9 * np.abs(torques).max())
    np.testing.assert_allclose(found.forces, forces, atol=1e-9 * np.abs(forces).max())
