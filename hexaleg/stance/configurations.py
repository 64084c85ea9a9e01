"""Configuration vectors q of the robot with its body displaced from the nominal stance.

One builder, :func:`configurations`, serves everything that poses the Pinocchio model
at a body pose: the statics at the extremes (:func:`extreme_configurations`, from the
angles an extreme reports), the viewer's animation and the self-collision checks
(:func:`stance_configurations`, the stance legs by the closed-form IK). Swing legs keep
their nominal angles.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._typing import ArrayF
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.constraints import displacement_poses, rpy_rotation
from hexaleg.stance.extremes import Extreme
from hexaleg.stance.geometry import StanceGeometry


def configurations(
    model: HexapodModel,
    rotation: npt.ArrayLike,
    translation: npt.ArrayLike,
    joint_angles: Mapping[str, npt.ArrayLike],
) -> ArrayF:
    """Configurations (P, nq) for body poses and some legs' joint angles.

    Args:
        model: The robot.
        rotation: Body orientations (P, 3, 3), world frame.
        translation: Body positions (P, 3), world frame [m].
        joint_angles: Leg name → (θ1, θ2, θ3) per pose (P, 3) [rad]; legs not named
            keep their nominal angles.

    """
    rotation = np.asarray(rotation, dtype=float).reshape(-1, 3, 3)
    q = np.tile(model.nominal_configuration(), (len(rotation), 1))
    q[:, :3] = np.asarray(translation, dtype=float).reshape(-1, 3)
    q[:, 3:7] = [pin.Quaternion(r).coeffs() for r in rotation]  # x, y, z, w
    for leg, angles in joint_angles.items():
        theta = np.asarray(angles, dtype=float).reshape(-1, 3)
        q[:, model.leg_q_indices(leg)] = model.joint_values(leg, theta)
    return q


def extreme_configurations(model: HexapodModel, extremes: Sequence[Extreme]) -> ArrayF:
    """The configurations (K, nq) at extremes, from their reported poses and joint angles."""
    poses = np.array([e.pose for e in extremes], dtype=float).reshape(-1, 6)
    translation = poses[:, :3] + model.nominal_base_pose().translation
    legs = extremes[0].joint_angles if extremes else {}
    angles = {leg: [e.joint_angles[leg] for e in extremes] for leg in legs}
    return configurations(model, rpy_rotation(poses[:, 3:]), translation, angles)


def stance_configurations(
    model: HexapodModel, geometry: StanceGeometry, displacements: npt.ArrayLike
) -> ArrayF:
    """Configurations (P, nq) at body displacements (P, 6), the stance legs by the IK."""
    rotation, translation = displacement_poses(geometry, np.reshape(displacements, (-1, 6)))
    return posed_configurations(model, geometry, rotation, translation)


def posed_configurations(
    model: HexapodModel, geometry: StanceGeometry, rotation: ArrayF, translation: ArrayF
) -> ArrayF:
    """Configurations (P, nq) at body poses (P, 3, 3), (P, 3), the stance legs by the IK.

    Each stance leg by its own geometry (:meth:`StanceGeometry.leg_solutions`): a robot
    file's general leg, or the paper's leg of the design's lengths.
    """
    rotation = np.asarray(rotation, dtype=float).reshape(-1, 3, 3)
    translation = np.asarray(translation, dtype=float).reshape(-1, 3)
    theta, _ = geometry.leg_solutions(geometry.feet_in_roots(rotation, translation))
    angles = {leg: theta[:, n] for n, leg in enumerate(geometry.legs)}
    return configurations(model, rotation, translation, angles)
