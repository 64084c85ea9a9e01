"""Running a :class:`~hexaleg.sim.model.SimModel`: its start, its feet, whether it diverged.

What the feet feel is the floor's contact force on each; a run has diverged when its
state no longer means anything (:func:`divergence`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.sim._mujoco import require_mujoco
from hexaleg.sim.model import SimModel


def start(sim: SimModel, q: npt.ArrayLike) -> Any:
    """A fresh ``mujoco.MjData`` at Pinocchio configuration ``q``, at rest, forward computed."""
    mujoco = require_mujoco()
    data = mujoco.MjData(sim.mj)
    data.qpos[:] = sim.qpos_of(q)
    mujoco.mj_forward(sim.mj, data)
    return data


DIVERGED_SPEED = 100.0
"""A body or joint faster than this [m/s or rad/s] is a simulation blowing up, not a walk."""


def divergence(sim: SimModel, data: Any, floor: float) -> str:
    """Why the run has diverged (empty if it has not): its state no longer means anything.

    MuJoCo found NaN, infinite or huge accelerations (it then resets the state, and every
    measure after is of another run); a coordinate's speed not finite or beyond
    :data:`DIVERGED_SPEED`; or the body below ``floor`` [m], far through the ground.
    """
    mujoco = require_mujoco()
    if data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number:
        return "MuJoCo's accelerations became NaN, infinite or huge (the simulation is unstable)"
    fastest = float(np.abs(data.qvel).max())
    if not fastest <= DIVERGED_SPEED:
        return f"a speed of {fastest:.3g} (m/s or rad/s) beyond {DIVERGED_SPEED:g}: it blew up"
    height = float(data.xpos[sim.base][2])
    if not height >= floor:
        return f"the body fell through the ground to z = {height:.3g} m"
    return ""


def foot_forces(sim: SimModel, data: Any) -> ArrayF:
    """Force of the floor on each foot (legs, 3), world frame [N]; zero for a foot in the air."""
    mujoco = require_mujoco()
    forces = np.zeros((len(sim.contacts), 3))
    wrench = np.zeros(6)
    foot_of_geom = {int(g): i for i, g in enumerate(sim.contacts)}
    for k in range(data.ncon):
        contact = data.contact[k]
        pair = (int(contact.geom1), int(contact.geom2))
        if sim.floor not in pair:
            continue
        other = pair[1] if pair[0] == sim.floor else pair[0]
        if other not in foot_of_geom:
            continue
        mujoco.mj_contactForce(sim.mj, data, k, wrench)
        # Contact frame rows: normal (from geom1 to geom2), then two tangents; the force
        # acts on geom2, so it is the foot's when the floor is geom1.
        force = contact.frame.reshape(3, 3).T @ wrench[:3]
        forces[foot_of_geom[other]] += force if pair[0] == sim.floor else -force
    return forces
