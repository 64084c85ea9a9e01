"""The legs' stresses and deflection, each against an independent computation written here.

Stresses: the foot forces are the statics', everything else is summed by hand from the D-H
closed forms (eq 7), the tubes' masses and centres and the actuators' points, and turned
into σ, τ and von Mises with the formulas of the brief. Deflection: cantilever and bent
two-segment chains in closed form. Walking: the tibia's wrench against its mass times its
centre's acceleration, by finite differences of its position along the period.
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin
import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.actuators import Actuator, Actuators
from hexaleg.design import FOOT_MASS
from hexaleg.gait.analysis import analyze_gait
from hexaleg.gait.spec import Gait
from hexaleg.gravity import GRAVITY, slope_gravity
from hexaleg.leg_structure import Structure, Tube
from hexaleg.materials import shipped_materials
from hexaleg.statics.forces import Payload
from hexaleg.statics.ground import Ground
from hexaleg.statics.loads import analyze_loads
from hexaleg.statics.slopes import SLOPE_HEADINGS
from hexaleg.structure.deflection import deflection_integrals, foot_deflections
from hexaleg.structure.wrenches import leg_states

CATALOG = shipped_materials()


def actuators(rng):
    def one():
        return Actuator(
            gear_ratio=100.0,
            torque_constant=0.1,
            resistance=0.5,
            gearbox_efficiency=0.8,
            peak_torque=500.0,
            continuous_torque=300.0,
            mass=float(rng.uniform(0.2, 2.0)),
            voltage=48.0,
        )

    return Actuators(one(), one(), one())


def seeded_design(seed):
    """A design of random lengths, posture, tubes, material and actuators."""
    rng = np.random.default_rng(seed)
    while True:
        tubes = []
        for _ in range(3):
            outer = rng.uniform(0.015, 0.06)
            tubes.append(Tube(outer, rng.uniform(0.001, outer / 2)))
        material = CATALOG.entries[rng.integers(len(CATALOG))]
        try:
            return HexapodDesign(
                l1=rng.uniform(0.05, 0.3),
                l2=rng.uniform(0.2, 0.6),
                l3=rng.uniform(0.2, 0.6),
                body_mass=rng.uniform(10, 80),
                nominal_angles=(0.0, rng.uniform(-0.4, 0.4), rng.uniform(-2.2, -0.6)),
                structure=Structure(material, *tubes, safety_factor=rng.uniform(1, 3)),
                actuators=actuators(rng) if seed % 2 else None,
            )
        except ValueError:
            continue


def rotation_z(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rotation_y(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def leg_chain(design, mount, body_rotation, body_position, angles):
    """The joints, foot and segment frames of one leg, world frame, by the D-H forms."""
    t1, t2, t3 = angles
    turn = body_rotation @ rotation_z(mount.yaw + t1)
    root = body_position + body_rotation @ np.array(mount.position)
    frames = [turn, turn @ rotation_y(-t2), turn @ rotation_y(-(t2 + t3))]
    hip = root + design.l1 * frames[0][:, 0]
    knee = hip + design.l2 * frames[1][:, 0]
    foot = knee + design.l3 * frames[2][:, 0]
    return [root, hip, knee], foot, frames


def point_masses(design, joints, foot, frames):
    """(mass, position) beyond each segment's proximal joint, by hand."""
    structure = design.structure
    tubes = [
        (structure.material.density * tube.area * length, origin + length / 2 * frame[:, 0])
        for tube, length, origin, frame in zip(
            structure.tubes, design.lengths, joints, frames, strict=True
        )
    ]
    hip, knee = (0.0, 0.0) if design.actuators is None else design.actuators.masses[1:]
    foot_point = (FOOT_MASS, foot)
    return [
        [tubes[0], (hip, joints[1]), tubes[1], (knee, joints[2]), tubes[2], foot_point],
        [tubes[1], (knee, joints[2]), tubes[2], foot_point],
        [tubes[2], foot_point],
    ]


def hand_loads(design, body_rotation, body_position, angles, foot_forces, gravity):
    """(N, M_b, T) (6, 3, 3) at each segment's proximal joint: the distal wrench by hand."""
    out = np.zeros((6, 3, 3))
    for i, mount in enumerate(design.legs):
        joints, foot, frames = leg_chain(design, mount, body_rotation, body_position, angles[i])
        for s, distal in enumerate(point_masses(design, joints, foot, frames)):
            origin, axis = joints[s], frames[s][:, 0]
            force = -(foot_forces[i] + sum(m * gravity for m, _ in distal))
            moment = -(
                np.cross(foot - origin, foot_forces[i])
                + sum(np.cross(c - origin, m * gravity) for m, c in distal)
            )
            torsion = moment @ axis
            out[i, s] = (force @ axis, np.linalg.norm(moment - torsion * axis), torsion)
    return out


def hand_stresses(structure, loads):
    """σ, τ, von Mises and the ratio (6, 3) of the brief's formulas."""
    result = np.zeros((4, *loads.shape[:2]))
    for s, tube in enumerate(structure.tubes):
        outer, inner = tube.outer_diameter, tube.outer_diameter - 2 * tube.wall
        area = math.pi / 4 * (outer**2 - inner**2)
        moment = math.pi / 64 * (outer**4 - inner**4)
        axial, bending, torsion = (np.abs(loads[:, s, k]) for k in range(3))
        sigma = axial / area + bending * (outer / 2) / moment
        tau = torsion * (outer / 2) / (2 * moment)
        von_mises = np.sqrt(sigma**2 + 3 * tau**2)
        ratio = von_mises / (structure.material.yield_strength / structure.safety_factor)
        if structure.material.shear_strength is not None:
            shear = tau / (structure.material.shear_strength / structure.safety_factor)
            ratio = np.maximum(ratio, shear)
        result[:, :, s] = sigma, tau, von_mises, ratio
    return result


@pytest.mark.parametrize("seed", [1, 2, *(pytest.param(s, marks=pytest.mark.slow) for s in (3, 4))])
def test_standing_stresses_equal_the_distal_wrench_summed_by_hand(seed):
    design = seeded_design(seed)
    slope = math.radians(8.0)
    analysis = analyze_loads(design, Payload(15.0), slope=slope)
    check = analysis.structure
    nominal = np.array([design.nominal_angles] * 6)
    level = np.array([0.0, 0.0, design.nominal_height])
    down = np.array([0.0, 0.0, -GRAVITY])
    cases = [("nominal", np.eye(3), level, nominal, analysis.nominal.foot_forces, down)]
    for loads in analysis.extremes[::3]:  # body moved and turned: x+, y-, roll+, yaw-
        extreme = loads.extreme
        angles = np.array([extreme.joint_angles[leg] for leg in design.leg_names])
        rotation = pin.rpy.rpyToMatrix(*extreme.pose[3:])
        place = level + np.array(extreme.pose[:3])
        cases.append((extreme.name, rotation, place, angles, loads.state.foot_forces, down))
    for name, rotation, place, angles, forces, gravity in cases:
        k = check.cases.index(name)
        expected = hand_loads(design, rotation, place, angles, forces, gravity)
        np.testing.assert_allclose(check.loads[k], expected, rtol=1e-9, atol=1e-9)
        sigma, tau, von_mises, ratio = hand_stresses(design.structure, expected)
        got_sigma, got_tau, got_vm = (stress[k] for stress in check.stresses)
        np.testing.assert_allclose(got_vm, von_mises, rtol=1e-9)
        np.testing.assert_allclose(got_sigma, sigma, rtol=1e-9)
        np.testing.assert_allclose(got_tau, tau, rtol=1e-9, atol=1e-6)
        np.testing.assert_allclose(check.ratios[k], ratio, rtol=1e-9)
    assert len(check.cases) == 1 + 12 + len(SLOPE_HEADINGS)
    assert check.worst_ratio == pytest.approx(check.ratios.max())


def test_slope_cases_tilt_gravity_in_every_heading():
    design = seeded_design(5)
    slope = math.radians(12.0)
    check = analyze_loads(design, slope=slope).structure
    from hexaleg.statics.forces import Statics

    model = HexapodModel(design)
    statics = Statics(model, model.leg_names)
    for heading in SLOPE_HEADINGS:
        gravity = slope_gravity(slope, heading)
        state = statics.state(model.nominal_configuration(), gravity=gravity)
        name = next(c for c in check.cases if f"{math.degrees(heading):+.0f}°" in c)
        nominal = np.array([design.nominal_angles] * 6)
        level = np.array([0.0, 0.0, design.nominal_height])
        expected = hand_loads(design, np.eye(3), level, nominal, state.foot_forces, gravity)
        np.testing.assert_allclose(check.loads[check.cases.index(name)], expected, atol=1e-9)


ALUMINIUM = CATALOG.material("aluminium_6061_t6")


def straight_states(design, angles):
    """Every leg at ``angles``, the body at the origin, level: the legs' joints and feet."""
    model = HexapodModel(design)
    q = model.configuration(pin.SE3.Identity(), np.array([angles] * 6))
    return leg_states(model, [q], np.zeros(3))


def bent(design, foot_force):
    """lf's foot deflection vector [m] under a force at its foot alone (no weight)."""
    states = straight_states(design, design.nominal_angles)
    forces = np.zeros((1, 6, 3))
    forces[0, 0] = foot_force
    integrals = deflection_integrals(design, states, forces, np.zeros(3))
    return foot_deflections(integrals, design.structure)[0, 0]


def leg_axes(design):
    """lf's outward direction (the coxa's, at θ1 = 0) and up, world frame."""
    yaw = design.legs[0].yaw
    return np.array([math.cos(yaw), math.sin(yaw), 0.0]), np.array([0.0, 0.0, 1.0])


def test_a_straight_leg_bends_as_a_cantilever():
    tube = Tube(0.03, 0.002)
    design = HexapodDesign(
        l1=0.2, l2=0.35, l3=0.3, nominal_angles=(0.0, 0.0, -0.3),
        structure=Structure(ALUMINIUM, tube, tube, tube),
    )  # fmt: skip
    states = straight_states(design, (0.0, 0.0, 0.0))
    forces = np.zeros((1, 6, 3))
    forces[0, 0, 2] = -120.0
    integrals = deflection_integrals(design, states, forces, np.zeros(3))
    deflection = foot_deflections(integrals, design.structure)[0, 0]
    length, stiffness = design.leg_length, ALUMINIUM.youngs_modulus * tube.second_moment
    np.testing.assert_allclose(deflection, [0, 0, -120.0 * length**3 / (3 * stiffness)], atol=1e-12)


def test_a_straight_chain_of_three_stiffnesses_sums_their_shares():
    tubes = [Tube(0.05, 0.003), Tube(0.035, 0.002), Tube(0.02, 0.01)]
    design = HexapodDesign(
        l1=0.15, l2=0.4, l3=0.35, nominal_angles=(0.0, 0.0, -0.3),
        structure=Structure(ALUMINIUM, *tubes),
    )  # fmt: skip
    states = straight_states(design, (0.0, 0.0, 0.0))
    forces = np.zeros((1, 6, 3))
    forces[0, 0, 2] = 80.0
    integrals = deflection_integrals(design, states, forces, np.zeros(3))
    deflection = foot_deflections(integrals, design.structure)[0, 0]
    # segment k spans distances a_k .. b_k from the foot: ∫ F x² / EI dx = F (a³ − b³) / 3EI
    far = np.cumsum(design.lengths[::-1])[::-1]
    near = far - np.array(design.lengths)
    shares = [
        80.0 * (a**3 - b**3) / (3 * ALUMINIUM.youngs_modulus * tube.second_moment)
        for a, b, tube in zip(far, near, tubes, strict=True)
    ]
    np.testing.assert_allclose(deflection, [0, 0, sum(shares)], atol=1e-12)


@pytest.mark.parametrize("load", ["down", "out"])
def test_an_l_shaped_leg_bends_as_its_closed_form(load):
    """Coxa and femur level (one tube, length a), tibia hanging (length b), loaded at the foot."""
    arm, post = Tube(0.04, 0.002), Tube(0.025, 0.0015)
    design = HexapodDesign(
        l1=0.2,
        l2=0.4,
        l3=0.45,
        structure=Structure(ALUMINIUM, arm, arm, post),
    )  # the default posture: femur level, tibia vertical
    a, b = design.l1 + design.l2, design.l3
    ei_arm = ALUMINIUM.youngs_modulus * arm.second_moment
    ei_post = ALUMINIUM.youngs_modulus * post.second_moment
    out, up = leg_axes(design)
    if load == "down":  # the post only carries it along its axis; the arm bends and turns
        deflection = bent(design, -150.0 * up)
        expected = -150.0 * a**3 / (3 * ei_arm) * up - 150.0 * a**2 * b / (2 * ei_arm) * out
    else:  # the post bends as a cantilever, the arm under the constant moment H·b
        deflection = bent(design, 90.0 * out)
        along = 90.0 * b**3 / (3 * ei_post) + 90.0 * b**2 * a / ei_arm
        expected = along * out + 90.0 * b * a**2 / (2 * ei_arm) * up
    np.testing.assert_allclose(deflection, expected, rtol=1e-10, atol=1e-14)


def test_the_standing_deflection_is_the_worst_over_cases_and_legs():
    design = seeded_design(6)
    check = analyze_loads(design).structure
    assert check.deflections.shape == (13, 6)
    assert check.deflection == pytest.approx(check.deflections.max())
    assert check.limit == pytest.approx(0.01 * design.leg_length)
    assert check.feasible == (check.worst_ratio <= 1 and check.deflection <= check.limit)


@pytest.mark.parametrize(
    ("seed", "slope_deg", "heading"),
    [(7, 0.0, None), (7, 12.0, 0.5), pytest.param(8, 0.0, None, marks=pytest.mark.slow)],
)
def test_walking_wrenches_carry_the_links_inertial_forces(seed, slope_deg, heading):
    """The knee's force on the tibia, in the world: m·(a − g) − f_foot, a by finite differences.

    On a slope the body stays parallel to the ground and gravity turns in its frame:
    g·(−sin α cos φ, −sin α sin φ, −cos α), written here from the definition.
    """
    design = seeded_design(seed)
    gait = Gait(samples=400, period=1.2, stride=0.1)
    alpha = math.radians(slope_deg)
    phi = gait.heading if heading is None else heading
    walk = analyze_gait(design, gait, limits=False, ground=Ground(alpha, heading))
    gravity = GRAVITY * np.array(
        [-math.sin(alpha) * math.cos(phi), -math.sin(alpha) * math.sin(phi), -math.cos(alpha)]
    )
    check = walk.structure
    tube = design.structure.tibia
    tube_mass = design.structure.material.density * tube.area * design.l3
    period, count = walk.gait.period, len(walk.times)
    step = period / count
    body = walk.configurations[:, :3]
    for i, mount in enumerate(design.legs):
        centres, frames = [], []
        for k in range(count):
            joints, foot, leg_frames = leg_chain(
                design, mount, np.eye(3), body[k], walk.joint_angles[k, i]
            )
            tube_centre = joints[2] + design.l3 / 2 * leg_frames[2][:, 0]
            centres.append((tube_mass * tube_centre + FOOT_MASS * foot) / (tube_mass + FOOT_MASS))
            frames.append(leg_frames[2])
        centres = np.array(centres)
        # the period repeats, the body moving on by one stride's travel
        travel = body[1] - body[0]
        ahead = np.roll(centres, -1, axis=0)
        ahead[-1] += count * travel
        behind = np.roll(centres, 1, axis=0)
        behind[0] -= count * travel
        acceleration = (ahead - 2 * centres + behind) / step**2
        expected = (tube_mass + FOOT_MASS) * (acceleration - gravity)
        expected -= walk.foot_forces[:, i]
        got = np.einsum("kij,kj->ki", np.array(frames), _knee_forces(check, i))
        # where the foot lands or lifts the acceleration jumps: differences span the jump
        stance = walk.stance[:, i]
        smooth = (stance == np.roll(stance, 1)) & (stance == np.roll(stance, -1))
        scale = np.abs(expected).max()
        np.testing.assert_allclose(got[smooth], expected[smooth], atol=2e-3 * scale)
        assert smooth.sum() > 0.9 * count


def _knee_forces(check, leg):
    """The tibia's axial and shear forces in its frame, rebuilt from the stress record."""
    return check.wrenches[:, leg, 2, :3]


@pytest.mark.parametrize("seed", [9, 10])
def test_the_vectorized_legs_are_pinocchio_s_frames_and_rnea_forces(seed):
    """Random body poses, velocities and accelerations: oMi, the feet and RNEA's data.f."""
    design = seeded_design(seed)
    model = HexapodModel(design)
    pm, data = model.model, model.data
    rng = np.random.default_rng(seed)
    q = np.array([pin.randomConfiguration(pm, -np.ones(pm.nq), np.ones(pm.nq)) for _ in range(4)])
    v, a = rng.normal(size=(2, 4, pm.nv))
    gravity = np.array([0.5, -0.3, -GRAVITY])
    states = leg_states(model, q, gravity, v, a)
    saved = pm.gravity.linear.copy()
    pm.gravity.linear = gravity
    try:
        for k in range(4):
            pin.framesForwardKinematics(pm, data, q[k])
            pin.rnea(pm, data, q[k], v[k], a[k])
            for i, leg in enumerate(model.leg_names):
                for s, joint in enumerate(model.leg_joint_ids(leg)):
                    placement = data.oMi[joint]
                    np.testing.assert_allclose(
                        states.rotations[k, i, s], placement.rotation, atol=1e-14
                    )
                    np.testing.assert_allclose(
                        states.origins[k, i, s], placement.translation, atol=1e-14
                    )
                    np.testing.assert_allclose(
                        states.own[k, i, s], data.f[joint].vector, atol=1e-11
                    )
                foot = data.oMf[model.foot_frame_id(leg)].translation
                np.testing.assert_allclose(states.feet[k, i], foot, atol=1e-14)
    finally:
        pm.gravity.linear = saved
