"""Running a :class:`~hexaleg.sim.model.SimModel`: its start state, and what the feet feel."""

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
