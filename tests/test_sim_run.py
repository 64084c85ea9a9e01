"""Following a plan in MuJoCo: a plan that stands still stands still; states convert both ways."""

from __future__ import annotations

import os

import numpy as np
import pinocchio as pin
import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.statics.forces import Statics

if not os.environ.get("CI"):  # CI installs hexaleg[test], which includes the sim extra
    pytest.importorskip("mujoco")

from hexaleg.sim.measure import Trace, measure_walk
from hexaleg.sim.model import SimModel
from hexaleg.sim.plan import Plan
from hexaleg.sim.run import run_plan


@pytest.fixture(scope="module")
def sim():
    return SimModel(HexapodModel(HexapodDesign()))


def test_qpos_and_configuration_convert_both_ways(sim):
    model = sim.hexapod
    rng = np.random.default_rng(4)
    for _ in range(5):
        base = pin.SE3(pin.rpy.rpyToMatrix(*rng.uniform(-1, 1, 3)), rng.uniform(-1, 1, 3))
        q = model.configuration(base, rng.uniform(-1, 1, (6, 3)))
        back = sim.configuration_of(sim.qpos_of(q))
        np.testing.assert_allclose(back, q, atol=1e-12)


def test_a_plan_that_stands_still_keeps_the_robot_where_it_is(sim):
    model = sim.hexapod
    q = model.nominal_configuration()
    state = Statics(model, model.leg_names).state(q)
    samples = 10
    plan = Plan(
        period=1.0,
        angles=np.tile(model.joint_angles(q), (samples, 1, 1)),
        rates=np.zeros((samples, 6, 3)),
        torques=np.tile(state.joint_torques, (samples, 1, 1)),
        standing=np.ones((samples, 6), dtype=bool),
        velocity=np.zeros(2),
    )
    parts: list[Trace] = []
    run = run_plan(sim, plan, duration=2.0, frame_rate=10.0, record=parts.append)
    trace = Trace(
        *(np.concatenate([getattr(p, f) for p in parts]) for f in Trace.__dataclass_fields__)
    )
    assert trace.time.shape == (2000,)
    np.testing.assert_allclose(trace.time, np.arange(2000) * 1e-3, atol=1e-12)
    assert run.frames.shape == (20, model.model.nq)
    assert run.frame_rate == pytest.approx(10.0)
    design = model.design
    metrics = measure_walk(
        trace,
        1.0,
        2,
        plan.velocity,
        design.nominal_height,
        legs=model.leg_names,
        rated_torques=design.rated_torques,
    )
    assert not metrics.fell
    assert abs(metrics.distance) < 1e-3
    assert metrics.max_tilt < 1e-3
    assert metrics.slip < 1e-3
    assert metrics.tracking_rms < 1e-3
    # the soft contact lets the feet sink a little, never more than a centimetre
    assert model.design.nominal_height - 0.01 < metrics.min_height <= model.design.nominal_height
    peaks = state.peak_torques()
    for joint in ("hip", "knee"):
        assert metrics.peak_torque[joint] == pytest.approx(peaks[joint], rel=0.05, abs=0.5)


def test_a_run_that_diverges_says_when_and_why_and_stops(sim):
    """Each sign of divergence on a state built to show it (the oracle: the state itself),
    and a run fed an absurd feed-forward stopping at once, saying so."""
    import mujoco

    from hexaleg.sim.engine import DIVERGED_SPEED, divergence, start

    model = sim.hexapod
    floor = -model.design.nominal_height
    calm = start(sim, model.nominal_configuration())
    assert divergence(sim, calm, floor) == ""
    fast = start(sim, model.nominal_configuration())
    fast.qvel[sim.dof[0, 2]] = 2 * DIVERGED_SPEED
    assert "beyond 100" in divergence(sim, fast, floor)
    sunk = model.nominal_configuration()
    sunk[2] = 2 * floor
    assert "through the ground" in divergence(sim, start(sim, sunk), floor)
    bad = start(sim, model.nominal_configuration())
    bad.warning[mujoco.mjtWarning.mjWARN_BADQACC].number = 1
    assert "NaN, infinite or huge" in divergence(sim, bad, floor)
    q = model.nominal_configuration()
    plan = Plan(1.0, np.tile(model.joint_angles(q), (10, 1, 1)), np.zeros((10, 6, 3)),
                np.full((10, 6, 3), 1e9), np.ones((10, 6), dtype=bool), np.zeros(2))  # fmt: skip
    parts: list[Trace] = []
    run = run_plan(sim, plan, duration=2.0, record=parts.append)
    assert run.diverged.startswith("at t = ") and len(parts) == 1
    assert len(parts[0].time) < 100  # stopped within a tenth of a second
    assert run.frames.shape[0] == len(run.frame_torques) <= 3


def test_mujocos_warnings_are_collected_never_logged_in_the_working_folder(tmp_path, monkeypatch):
    import warnings

    import mujoco

    from hexaleg.sim._mujoco import mujoco_warnings, pass_on

    monkeypatch.chdir(tmp_path)
    xml = '<mujoco><worldbody><body><freejoint/><geom size="0.1"/></body></worldbody></mujoco>'
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    data.qfrc_applied[0] = float("nan")  # MuJoCo warns of a bad acceleration
    before = mujoco.get_mju_user_warning()
    with mujoco_warnings() as caught:
        mujoco.mj_step(model, data)
    assert mujoco.get_mju_user_warning() is before
    assert len(caught) == 1 and "QACC" in caught[0]
    assert list(tmp_path.iterdir()) == []  # no MUJOCO_LOG.TXT
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")
        pass_on(caught * 3)
        pass_on([])
    assert [str(w.message) for w in said] == [
        f"MuJoCo warned 3 times in the simulation: {caught[0]}"
    ]
