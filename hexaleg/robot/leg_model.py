"""One leg on a fixed base, as Pinocchio sees it: the world frame is the leg-root frame of eq 7."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._typing import ArrayF
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import ModelError
from hexaleg.robot.inertia import set_armature
from hexaleg.robot.model import _LegIndex
from hexaleg.robot.urdf import SINGLE_LEG_NAME, render_leg

__all__ = ["LegModel"]


class LegModel:
    """One leg on a fixed base, as Pinocchio sees it.

    Attributes:
        design: The design the model was built from.
        urdf: The rendered URDF text.
        model: The Pinocchio model (nq = nv = 3, q = (θ1, θ2, θ3) [rad]).
        data: Pinocchio workspace for ``model``.

    """

    def __init__(self, design: HexapodDesign) -> None:
        self.design = design
        self.urdf = render_leg(design)
        self.model = pin.buildModelFromXML(self.urdf)
        self._leg = _LegIndex(self.model, SINGLE_LEG_NAME)
        set_armature(self.model, [self._leg.v], design)
        self.data = self.model.createData()
        if self.model.nq != 3 or list(self._leg.q) != [0, 1, 2]:
            raise ModelError(f"single-leg model has nq = {self.model.nq}, expected 3 in leg order")

    @property
    def joint_lower(self) -> ArrayF:
        """Joint lower limits read from the URDF (θ1, θ2, θ3) [rad]."""
        return self._leg.lower

    @property
    def joint_upper(self) -> ArrayF:
        """Joint upper limits read from the URDF (θ1, θ2, θ3) [rad]."""
        return self._leg.upper

    def foot_position(self, theta: npt.ArrayLike) -> ArrayF:
        """Foot position in the leg-root frame [m] at joint angles θ (3,) [rad]."""
        q = np.asarray(theta, dtype=float)
        pin.framesForwardKinematics(self.model, self.data, q)
        return self.data.oMf[self._leg.foot_frame].translation.copy()

    def foot_jacobian(self, theta: npt.ArrayLike) -> ArrayF:
        """Foot linear-velocity Jacobian dp/dθ (3, 3) in the leg-root frame [m/rad]."""
        q = np.asarray(theta, dtype=float)
        jac = pin.computeFrameJacobian(
            self.model, self.data, q, self._leg.foot_frame, pin.LOCAL_WORLD_ALIGNED
        )
        return jac[:3].copy()

    def foot_positions(self, thetas: npt.ArrayLike) -> ArrayF:
        """Foot positions (N, 3) [m] for joint angles (N, 3) [rad], one Pinocchio call each."""
        thetas = np.asarray(thetas, dtype=float).reshape(-1, 3)
        return np.array([self.foot_position(t) for t in thetas])
