"""The feet in MuJoCo: each foot's contact sphere, how big, on which body; the model's names.

Each foot touches the floor with a sphere the model gives
(:meth:`~hexaleg.robot.model.HexapodModel.contact_radius`: the URDF's own foot sphere, or a
small one at a robot file's foot point). The sphere is centred on the foot frame and
carried by the first body up from it with a mass or a joint (:func:`contact_body`):
hexaleg's feet on a robot file are massless links, and MuJoCo scales a contact's impedance
by its body's weight, so on a massless body the floor would be far softer than its contact
parameters say. The bodies and joints are named as the Pinocchio model names them
(:func:`frame_name`, :func:`leg_joint_names`): the same URDF.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.robot.model import HexapodModel
from hexaleg.sim._mujoco import require_mujoco


def contact_geom_name(leg: str) -> str:
    """Name of the contact sphere of ``leg``'s foot."""
    return f"{leg}_foot_contact"


def contact_body(body: Any) -> tuple[Any, ArrayF]:
    """The ``MjSpec`` body that carries ``body``'s origin, and where that origin lies in it [m].

    ``body`` itself if it has a mass or a joint; else (a massless link fixed to its parent)
    the first such body up the tree.
    """
    mujoco = require_mujoco()
    point = np.zeros(3)
    while body.mass <= 0 and not body.joints and body.parent is not None:
        rotation = np.zeros(9)
        mujoco.mju_quat2Mat(rotation, np.asarray(body.quat, dtype=float))
        point = np.asarray(body.pos, dtype=float) + rotation.reshape(3, 3) @ point
        body = body.parent
    return body, point


def frame_name(model: HexapodModel, frame_id: int) -> str:
    """The name of Pinocchio frame ``frame_id``: a link's frame is named as the link."""
    return str(model.model.frames[frame_id].name)


def leg_joint_names(model: HexapodModel, leg: str) -> list[str]:
    """The model's names of ``leg``'s (root, hip, knee) joints (a robot file's own)."""
    pinocchio = model.model
    by_v = {pinocchio.idx_vs[j]: pinocchio.names[j] for j in range(1, pinocchio.njoints)}
    return [str(by_v[int(v)]) for v in model.leg_v_indices(leg)]
