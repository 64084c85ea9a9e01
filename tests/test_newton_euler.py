"""The walks' batched Newton–Euler against Pinocchio's own inverse dynamics.

:func:`hexaleg.gait.newton_euler.leg_forces` replaces, in every walk, one call of
Pinocchio's ``computeGeneralizedGravity`` and one of ``rnea`` (at zero gravity) per
sample. Its oracle is those calls, sample by sample, at random joint angles, rates and
accelerations, a random gravity, body velocity, rotor armatures and payload: on seeded
random designs of hexaleg's template, on a robot file (Kraby) and on random general
hexapods (hip heights, lateral offsets, legs written in turned and mirrored frames). A model with
a joint outside the legs gets no chains, and its walk takes Pinocchio's calls: the two
ways give the same walk. Designs derived from one body's model share its chains and walk
by their own bodies, as Pinocchio does on each.
"""

from __future__ import annotations

import warnings

import numpy as np
import pinocchio as pin
import pytest
from robot_files import draw_hexapod
from robots import KRABY

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.actuator_catalog import actuators_from_table
from hexaleg.exceptions import RobotImportWarning
from hexaleg.gait import Gait, Walker
from hexaleg.gait.newton_euler import leg_bodies, leg_chains, leg_forces
from hexaleg.robot.recipe import RobotSource
from hexaleg.robot.robot import Robot


def _leg_joints(model: HexapodModel) -> list[list[int]]:
    return [list(model.leg_joint_ids(leg)) for leg in model.leg_names]


def _pinocchio_parts(pin_model: pin.Model, q, v, a, gravity) -> tuple[np.ndarray, np.ndarray]:
    """Pinocchio at each sample: g(q) under ``gravity``, and rnea(q, v, a) without it."""
    pin_model = pin.Model(pin_model)
    data = pin_model.createData()
    pin_model.gravity.linear = gravity
    static = np.array([pin.computeGeneralizedGravity(pin_model, data, qk) for qk in q])
    pin_model.gravity.linear = np.zeros(3)
    inertial = np.array([pin.rnea(pin_model, data, *state) for state in zip(q, v, a, strict=True)])
    return static, inertial


def _assert_matches_pinocchio(model: HexapodModel, rng: np.random.Generator) -> None:
    pin_model = pin.Model(model.model)
    pin_model.armature[6:] = rng.uniform(0.0, 0.05, pin_model.nv - 6)  # the rotors
    payload = pin.Inertia(rng.uniform(0.5, 5.0), rng.normal(scale=0.1, size=3), np.zeros((3, 3)))
    pin_model.inertias[1] = pin_model.inertias[1] + payload  # a point mass on the body
    chains = leg_chains(pin_model, _leg_joints(model))
    assert chains is not None
    bodies = leg_bodies(pin_model, chains)
    count = 7
    q = np.tile(model.nominal_configuration(), (count, 1))
    q[:, :3] += rng.normal(size=(count, 3))  # where the body is does not matter
    q_index = np.array([model.leg_q_indices(leg) for leg in model.leg_names])
    v_index = np.array([model.leg_v_indices(leg) for leg in model.leg_names])
    q[:, q_index] = rng.uniform(-1.5, 1.5, (count, 6, 3))
    v = np.zeros((count, pin_model.nv))
    v[:, :3] = rng.normal(size=3)  # one velocity: the body neither turns nor accelerates
    v[:, v_index] = rng.normal(scale=3.0, size=(count, 6, 3))
    a = np.zeros_like(v)
    a[:, v_index] = rng.normal(scale=10.0, size=(count, 6, 3))
    gravity = rng.normal(size=3) + np.array([0.0, 0.0, -9.81])
    static, inertial = leg_forces(
        bodies, q[:, q_index], v[:, v_index], a[:, v_index], v[0, :3], gravity
    )
    expected_static, expected_inertial = _pinocchio_parts(pin_model, q, v, a, gravity)
    for part, expected in ((static, expected_static), (inertial, expected_inertial)):
        scale = np.abs(expected).max()
        np.testing.assert_allclose(part.torques, expected[:, v_index], atol=1e-10 * scale)
        np.testing.assert_allclose(part.base, expected[:, :6], atol=1e-10 * scale)


@pytest.mark.parametrize("seed", range(4))
def test_the_template_at_random_designs_matches_pinocchio(seed):
    rng = np.random.default_rng(seed)
    l1, l2, l3 = rng.uniform(0.05, 0.6, 3)
    design = HexapodDesign(l1=l1, l2=l2, l3=l3, body_radius=rng.uniform(0.2, 0.6))
    _assert_matches_pinocchio(HexapodModel(design), rng)


def _file_model(path: str) -> HexapodModel:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        return Robot.build(RobotSource.of(path)).model


def test_a_robot_file_matches_pinocchio():
    _assert_matches_pinocchio(_file_model(KRABY), np.random.default_rng(10))


@pytest.mark.parametrize("seed", [1, 4, 7])
def test_random_general_hexapods_match_pinocchio(tmp_path, seed):
    path = tmp_path / "drawn.urdf"
    path.write_text(draw_hexapod(seed, same_legs=True)[0])
    _assert_matches_pinocchio(_file_model(str(path)), np.random.default_rng(seed))


def _with_joint_beyond_the_legs(model: HexapodModel) -> HexapodModel:
    """``model`` with a massless revolute joint on the body besides its legs (appended)."""
    extended = pin.Model(model.model)
    extended.addJoint(1, pin.JointModelRX(), pin.SE3.Identity(), "beyond_the_legs")
    return HexapodModel(model.design, _model=extended)


def test_what_is_not_six_chains_on_the_body_gets_no_chains():
    model = HexapodModel(HexapodDesign())
    joints = _leg_joints(model)
    assert leg_chains(model.model, joints[:5]) is None  # a sixth leg's joints unaccounted for
    shuffled = [[leg[1], leg[0], leg[2]] for leg in joints]
    assert leg_chains(model.model, shuffled) is None  # not a chain from the body
    assert leg_chains(_with_joint_beyond_the_legs(model).model, joints) is None


def test_a_model_with_a_joint_beyond_its_legs_walks_by_pinocchio():
    """Its walk takes Pinocchio's calls, and is the legs' walk by their chains.

    The joint beyond the legs is massless and still: the generalized forces of the legs
    and the body are those of the model without it (walked by the chains, themselves held
    to Pinocchio above), and its own row is zero.
    """
    drives = {joint: {"catalog": "hd_cha_17a_e_100"} for joint in ("root", "hip", "knee")}
    plain = HexapodModel(HexapodDesign(actuators=actuators_from_table(drives)))
    assert np.any(plain.model.armature[6:] > 0)  # the rotors' inertia is in the walk
    gait = Gait(samples=40)
    walks, chains = [], []
    for model in (plain, _with_joint_beyond_the_legs(plain)):
        walker = Walker(model, gait)
        walks.append(walker.generalized_forces(gait.stride, walker.stride(gait.stride)))
        chains.append(walker.robot.bodies)
    assert chains[0] is not None and chains[1] is None
    chained, called = walks
    nv = plain.model.nv
    for part in ("static", "inertial"):
        expected, found = getattr(chained, part), getattr(called, part)
        scale = np.abs(expected).max()
        np.testing.assert_allclose(found[:, :nv], expected, atol=1e-10 * scale)
        np.testing.assert_array_equal(found[:, nv:], 0.0)


def test_designs_derived_from_one_body_share_its_chains_and_walk_by_their_own_bodies():
    """A study's designs derive from one body's model (``with_design``): the legs' chains
    are found once for all, and each design walks by its own lengths and masses. Oracle:
    Pinocchio's calls on each derived model."""
    base = HexapodModel(HexapodDesign())
    assert Walker(base, Gait()).robot.bodies is not None  # the body's chains, found
    gait = Gait(samples=20)
    for l2, l3 in ((0.35, 0.5), (0.5, 0.35)):
        model = base.with_design(HexapodDesign(l2=l2, l3=l3))
        model.structural("leg chains", lambda: pytest.fail("the chains are found again"))
        walker = Walker(model, gait)
        walked = walker.generalized_forces(gait.stride, walker.stride(gait.stride))
        expected = _pinocchio_parts(
            model.model,
            walked.configurations,
            walked.velocities,
            walked.accelerations,
            walker.gravity_vector,
        )
        for found, oracle in zip((walked.static, walked.inertial), expected, strict=True):
            np.testing.assert_allclose(found, oracle, atol=1e-10 * np.abs(oracle).max())
