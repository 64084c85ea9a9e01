"""Running a plan in MuJoCo: the joints follow it; every step is recorded as it goes.

The robot starts in the plan's first pose: body level at its nominal height above the
world origin, axes on the world's, each foot where the plan has it at t = 0 (all on the
ground for a gait), at rest or (``moving``) at the plan's velocities there. At each step
of ``timestep`` the joints get the plan's reference at that step's time
(:meth:`~hexaleg.sim.plan.Plan.reference`). A run that diverges
(:func:`~hexaleg.sim.engine.divergence`) stops at that step and says why.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg._checks import require_in_range
from hexaleg._typing import ArrayF
from hexaleg.sim._mujoco import mujoco_warnings, pass_on, require_mujoco
from hexaleg.sim.engine import divergence, foot_forces, start
from hexaleg.sim.measure import Trace
from hexaleg.sim.model import SimModel
from hexaleg.sim.plan import Plan

FRAME_RATE = 25.0
"""Frames per second [1/s] kept for animations."""


@dataclass(frozen=True)
class Run:
    """A simulated run's animation frames (its steps went to the ``record`` of :func:`run_plan`).

    Attributes:
        frames: Pinocchio configurations (F, nq) at ``frame_rate``.
        frame_torques: The servos' torques (F, legs, 3) at those frames [N·m].
        frame_rate: Frames per second [1/s].
        diverged: When and why the run stopped early (``at t = 0.038 s: …``); empty if it
            ran to its end.

    """

    frames: ArrayF
    frame_torques: ArrayF
    frame_rate: float
    diverged: str = ""


CHECK_EVERY = 10
"""Steps between two checks for divergence: a run that diverges stops within them."""
MAX_DURATION = 3600.0
"""Longest simulated time [s]: an hour of walking."""
PART_DURATION = 10.0
"""Simulated time [s] of each part of the trace handed to ``record`` at once: what a run
holds of its steps, whatever its length (the frames, 25 a second, are all kept)."""


def run_plan(
    sim: SimModel,
    plan: Plan,
    duration: float,
    frame_rate: float = FRAME_RATE,
    *,
    record: Callable[[Trace], object],
    moving: bool = False,
) -> Run:
    """Follow ``plan`` for ``duration`` [s] from its first pose.

    Every step's state is handed to ``record`` as it is simulated, a :class:`Trace` of at
    most :data:`PART_DURATION` at a time, in time order (a
    :class:`~hexaleg.sim.measure.WalkMeter`'s ``add`` measures it): the run itself keeps
    only the frames, so its memory does not grow with the steps. A run that diverges
    stops at the step it does, that step recorded last.

    Args:
        sim: The MuJoCo model.
        plan: The motion to follow (repeated every period).
        duration: Simulated time [s], in (0, :data:`MAX_DURATION`].
        frame_rate: Animation frames per second [1/s], in (0, 1000].
        record: Called with each part of the trace.
        moving: Start at the plan's velocities (the body's and the joints'), not at rest.

    """
    require_mujoco()
    require_in_range("duration", duration, 1e-6, MAX_DURATION, "s")
    require_in_range("frame_rate", frame_rate, 1e-3, 1000.0, "1/s")
    model = sim.hexapod
    steps = round(duration / sim.timestep)
    every = max(1, round(1.0 / (frame_rate * sim.timestep)))
    part = max(every, round(PART_DURATION / sim.timestep) // every * every)  # whole frames
    data = start(sim, model.configuration(model.nominal_base_pose(), plan.angles[0]))
    if moving:
        _set_moving(sim, data, plan)
    floor = -float(model.nominal_base_pose().translation[2])  # its height below the ground
    frames: list[ArrayF] = []
    frame_torques: list[ArrayF] = []
    diverged = ""
    with mujoco_warnings() as caught:  # no log file is written
        for first in range(0, steps, part):
            times = np.arange(first, min(first + part, steps), dtype=float) * sim.timestep
            trace, qpos, diverged = _steps(sim, data, plan, times, floor)
            record(trace)
            frames += [sim.configuration_of(row) for row in qpos[::every]]
            frame_torques.append(trace.joint_torques[::every].copy())  # not a view of the part
            if diverged:
                break
    if not diverged:  # a divergence says what they meant
        pass_on(caught)
    rate = 1.0 / (every * sim.timestep)
    return Run(np.array(frames), np.concatenate(frame_torques), rate, diverged)


def _set_moving(sim: SimModel, data: Any, plan: Plan) -> None:
    """Give ``data`` the plan's velocities at t = 0: the body's (world) and the joints'."""
    mujoco = require_mujoco()
    data.qvel[: len(plan.velocity)] = plan.velocity
    data.qvel[sim.dof] = sim.signs * plan.rates[0]
    mujoco.mj_forward(sim.mj, data)


def _steps(
    sim: SimModel, data: Any, plan: Plan, times: ArrayF, floor: float
) -> tuple[Trace, ArrayF, str]:
    """Step ``data`` through ``times`` [s]: their trace, their ``qpos``, why they stopped early.

    Empty: they did not stop. ``floor``: the height [m] below which the body has diverged.
    """
    mujoco = require_mujoco()
    reference, rates, torques, standing = plan.reference(times)
    controls = sim.command(reference, rates, torques)
    steps = len(times)
    qpos = np.empty((steps, sim.mj.nq))
    feet = np.empty((steps, *sim.feet.shape, 3))
    forces = np.empty((steps, *sim.feet.shape, 3))
    applied = np.empty((steps, *sim.actuators.shape))
    diverged = ""
    for k in range(steps):
        data.ctrl[:] = controls[k]
        qpos[k] = data.qpos
        mujoco.mj_step(sim.mj, data)
        # after a step, the positions and forces are still those computed at its start
        feet[k] = data.xpos[sim.feet]
        forces[k] = foot_forces(sim, data)
        applied[k] = data.actuator_force[sim.actuators]
        why = divergence(sim, data, floor) if k % CHECK_EVERY == 0 or k == steps - 1 else ""
        if why:
            diverged, steps = f"at t = {times[k]:.3f} s: {why}", k + 1
            break
    trace = Trace(
        time=times[:steps],
        base_position=qpos[:steps, :3],
        base_quaternion=qpos[:steps, 3:7],
        joint_angles=sim.angles_of(qpos[:steps, sim.qpos]),
        reference=reference[:steps],
        joint_torques=sim.signs * applied[:steps],  # on θ
        foot_positions=feet[:steps],
        standing=standing[:steps],
        foot_forces=forces[:steps],
    )
    return trace, qpos[:steps], diverged
