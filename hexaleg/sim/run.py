"""Running a plan in MuJoCo: the servos follow it from rest; every step is recorded.

The robot starts at rest in the plan's first pose: body level at its nominal height
above the world origin, axes on the world's, each foot where the plan has it at t = 0
(all on the ground for a gait). At each step of ``timestep`` the servos get the plan's
reference at that step's time (:meth:`~hexaleg.sim.plan.Plan.reference`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg._checks import require_in_range
from hexaleg._typing import ArrayF
from hexaleg.sim._mujoco import require_mujoco
from hexaleg.sim.engine import start
from hexaleg.sim.measure import Trace
from hexaleg.sim.model import SimModel
from hexaleg.sim.plan import Plan

FRAME_RATE = 25.0
"""Frames per second [1/s] kept for animations."""


@dataclass(frozen=True)
class Run:
    """A simulated run: every step, and the frames of its animation.

    Attributes:
        trace: Every step's state, reference and torques.
        frames: Pinocchio configurations (F, nq) at ``frame_rate``.
        frame_torques: The servos' torques (F, legs, 3) at those frames [N·m].
        frame_rate: Frames per second [1/s].

    """

    trace: Trace
    frames: ArrayF
    frame_torques: ArrayF
    frame_rate: float


MAX_DURATION = 3600.0
"""Longest simulated time [s]: an hour of walking."""


def run_plan(sim: SimModel, plan: Plan, duration: float, frame_rate: float = FRAME_RATE) -> Run:
    """Follow ``plan`` for ``duration`` [s] from rest at its first pose.

    Args:
        sim: The MuJoCo model.
        plan: The motion to follow (repeated every period).
        duration: Simulated time [s], in (0, :data:`MAX_DURATION`].
        frame_rate: Animation frames per second [1/s], in (0, 1000].

    """
    mujoco = require_mujoco()
    require_in_range("duration", duration, 1e-6, MAX_DURATION, "s")
    require_in_range("frame_rate", frame_rate, 1e-3, 1000.0, "1/s")
    model = sim.hexapod
    steps = round(duration / sim.timestep)
    times = np.arange(steps, dtype=float) * sim.timestep
    reference, rates, torques, standing = plan.reference(times)
    controls = sim.command(reference, rates, torques)
    data = start(sim, model.configuration(model.nominal_base_pose(), plan.angles[0]))
    qpos = np.empty((steps, sim.mj.nq))
    feet = np.empty((steps, *sim.feet.shape, 3))
    applied = np.empty((steps, *sim.actuators.shape))
    for k in range(steps):
        data.ctrl[:] = controls[k]
        qpos[k] = data.qpos
        mujoco.mj_step(sim.mj, data)
        # after a step, the positions and forces are still those computed at its start
        feet[k] = data.xpos[sim.feet]
        applied[k] = data.actuator_force[sim.actuators]
    trace = Trace(
        time=times,
        base_position=qpos[:, :3],
        base_quaternion=qpos[:, 3:7],
        joint_angles=qpos[:, sim.qpos],
        reference=reference,
        joint_torques=applied,
        foot_positions=feet,
        standing=standing,
    )
    every = max(1, round(1.0 / (frame_rate * sim.timestep)))
    frames = np.array([sim.configuration_of(row) for row in qpos[::every]])
    return Run(trace, frames, applied[::every], 1.0 / (every * sim.timestep))
