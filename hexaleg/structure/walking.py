"""The legs' tubes through a walking period: the wrenches with the links' inertial forces.

At each sample of a gait period the wrench at each segment's proximal joint holds the
foot's force from the ground (zero while it swings) and the weights and inertial forces
of everything beyond the joint (:func:`~.wrenches.leg_states` with the period's joint
velocities and accelerations). The deflection is checked standing only.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from hexaleg.robot.model import HexapodModel
from hexaleg.statics.ratings import at_times
from hexaleg.structure.check import StructureCheck
from hexaleg.structure.wrenches import leg_states, require_template, segment_wrenches


def check_walking(
    model: HexapodModel,
    times: npt.ArrayLike,
    configurations: npt.ArrayLike,
    velocities: npt.ArrayLike,
    accelerations: npt.ArrayLike,
    foot_forces: npt.ArrayLike,
    gravity: npt.ArrayLike,
) -> StructureCheck | None:
    """The model's tubes at every sample of a period; ``None`` without them all given.

    Args:
        model: The robot (hexaleg's template).
        times: t_k (N,) [s].
        configurations: q (N, nq).
        velocities: v (N, nv) [m/s, rad/s].
        accelerations: a (N, nv) [m/s², rad/s²].
        foot_forces: Each foot's force from the ground (N, 6, 3), world frame [N].
        gravity: Gravitational acceleration (3,) in the body (ground) frame [m/s²]: −g·z
            on level ground, tilted on a slope (:class:`~hexaleg.statics.ground.Ground`).

    """
    design = model.design
    structure = design.structure
    if structure is None or any(tube is None for tube in structure.tubes):
        return None
    require_template(model)
    with np.errstate(invalid="ignore"):  # a straight leg's unbounded rates: NaN, as the walk's
        states = leg_states(
            model, configurations, np.asarray(gravity, dtype=float), velocities, accelerations
        )
        wrenches = segment_wrenches(states, foot_forces)
    return StructureCheck(
        structure,
        design.lengths,
        model.leg_names,
        tuple(at_times(times)),
        wrenches,
        None,
        structure.limit(design.leg_length),
    )
