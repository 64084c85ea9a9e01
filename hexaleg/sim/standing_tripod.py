"""The standing check: a tripod holds the robot and its payload in MuJoCo, as the statics say.

The robot stands on one tripod (``--stance tripod``'s legs: lf, rm, lr on the built-in
layouts) with the other legs' feet lifted :data:`LIFT` straight up, payload on, body
level at its nominal height. The servos hold that pose with the statics' torques as
feed-forward for :data:`DURATION`; the floor's vertical force on each standing foot,
averaged over the last :data:`AVERAGE_WINDOW`, is set beside the statics' (the nominal
stance of ``hexaleg loads --stance tripod``). Three feet on the ground are statically
determinate in their vertical forces: the two must agree to a few per cent.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg._typing import ArrayF
from hexaleg.kinematics import foot_position, inverse_kinematics
from hexaleg.robot.model import HexapodModel
from hexaleg.sim._mujoco import mujoco_warnings, pass_on, require_mujoco
from hexaleg.sim.engine import divergence, foot_forces, start
from hexaleg.sim.model import ServoGains, SimModel
from hexaleg.stance.geometry import stance_legs
from hexaleg.statics.forces import DEFAULT_FRICTION, Payload, Statics

DURATION = 2.0
"""How long the robot stands [s]."""
LIFT = 0.02
"""How far the other legs' feet are lifted [m]."""
AVERAGE_WINDOW = 0.5
"""The final stretch over which the foot forces are averaged [s]."""


@dataclass(frozen=True)
class StandingCheck:
    """Vertical foot forces standing on a tripod: simulated and from the statics.

    Attributes:
        legs: The standing legs.
        foot_forces_z: Floor's vertical force on each standing foot in MuJoCo [N].
        statics_foot_forces_z: The same from the statics at the nominal stance [N].
        duration: How long the robot stood [s].
        diverged: When and why the simulation diverged (``at t = 0.038 s: …``), stopping it
            (:func:`~hexaleg.sim.engine.divergence`): its forces then mean nothing; empty
            if it did not.

    """

    legs: tuple[str, ...]
    foot_forces_z: dict[str, float]
    statics_foot_forces_z: dict[str, float]
    duration: float
    diverged: str = ""

    @property
    def worst_relative_error(self) -> float:
        """Largest |simulated − statics| / statics over the standing feet [-]."""
        return max(
            abs(self.foot_forces_z[leg] - self.statics_foot_forces_z[leg])
            / abs(self.statics_foot_forces_z[leg])
            for leg in self.legs
        )

    def to_dict(self) -> dict[str, dict[str, float]]:
        """JSON-ready: ``foot_forces_z`` and ``statics_foot_forces_z`` per leg [N]."""
        return {
            "foot_forces_z": dict(self.foot_forces_z),
            "statics_foot_forces_z": dict(self.statics_foot_forces_z),
        }


def lifted_configuration(model: HexapodModel, standing: tuple[str, ...], lift: float) -> ArrayF:
    """The nominal stance with every leg not in ``standing`` lifting its foot by ``lift`` [m].

    Each leg from its own nominal posture, by its own general leg (an imported robot's).
    """
    angles = {}
    for leg in model.leg_names:
        nominal = model.nominal_angles(leg)
        if leg in standing:
            angles[leg] = np.asarray(nominal)
            continue
        geometry = model.leg_geometry(leg)
        foot = foot_position(geometry, nominal) + np.array([0.0, 0.0, lift])
        angles[leg] = inverse_kinematics(geometry, foot).theta
    return model.configuration(model.nominal_base_pose(), angles)


def standing_check(
    model: HexapodModel,
    payload: Payload | None = None,
    friction: float = DEFAULT_FRICTION,
    gains: ServoGains | None = None,
    sim: SimModel | None = None,
) -> StandingCheck:
    """Stand on the first tripod for :data:`DURATION` in MuJoCo; compare with the statics.

    Args:
        model: The hexapod's Pinocchio model.
        payload: A point mass on the body.
        friction: Coefficient of friction μ between feet and floor [-].
        gains: Joint servo gains (default: :meth:`ServoGains.from_bandwidth`).
        sim: The MuJoCo model, if already built with this payload and friction.

    """
    mujoco = require_mujoco()
    payload = payload or Payload()
    sim = SimModel(model, payload, friction, gains) if sim is None else sim
    legs = stance_legs(model, "tripod")
    statics = Statics(model, legs, payload, friction)
    q = lifted_configuration(model, legs, LIFT)
    data = start(sim, q)
    data.ctrl[:] = sim.command(
        model.joint_angles(q),
        np.zeros((len(model.leg_names), 3)),
        _holding_torques(model, statics, q),
    )
    steps = round(DURATION / sim.timestep)
    window = round(AVERAGE_WINDOW / sim.timestep)
    total = np.zeros((len(model.leg_names), 3))
    floor, diverged = -float(model.nominal_base_pose().translation[2]), ""
    with mujoco_warnings() as caught:  # no log file is written
        for k in range(steps):
            mujoco.mj_step(sim.mj, data)
            if k >= steps - window:
                total += foot_forces(sim, data)
            why = divergence(sim, data, floor)
            if why:
                diverged = f"at t = {k * sim.timestep:.3f} s: {why}"
                break
    if not diverged:  # a divergence says what they meant
        pass_on(caught)
    measured = total[:, 2] / window
    expected = statics.state(model.nominal_configuration()).foot_forces[:, 2]
    index = {leg: i for i, leg in enumerate(model.leg_names)}
    return StandingCheck(
        legs=legs,
        foot_forces_z={leg: float(measured[index[leg]]) for leg in legs},
        statics_foot_forces_z={leg: float(f) for leg, f in zip(legs, expected, strict=True)},
        duration=steps * sim.timestep,
        diverged=diverged,
    )


def _holding_torques(model: HexapodModel, statics: Statics, q: ArrayF) -> ArrayF:
    """Joint torques on θ (legs, 3) [N·m] holding ``q``.

    The statics' on the standing legs; each lifted leg holds its own weight.
    """
    gravity: Any = pin.computeGeneralizedGravity(model.model, model.data, q)
    torques = np.array(
        [model.joint_signs(leg) * gravity[model.leg_v_indices(leg)] for leg in model.leg_names]
    )
    state = statics.state(q)
    for leg, tau in zip(state.legs, state.joint_torques, strict=True):
        torques[model.leg_names.index(leg)] = tau
    return torques
