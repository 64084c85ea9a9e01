"""Free-coupled body flexibility: each coordinate pushed as far as the mechanism allows.

The other five body coordinates are free to help: a constrained nonlinear program
(SLSQP) on the Pinocchio model's configuration, with the foot-anchor constraints and
their Jacobians from Pinocchio, started from the axis-locked extreme so its range is
never smaller.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence

import numpy as np
import pinocchio as pin
from scipy import optimize

from hexaleg._typing import ArrayF, StanceSet
from hexaleg.design import HexapodDesign
from hexaleg.kinematics import inverse_kinematics
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.axis_locked import axis_locked_extremes
from hexaleg.stance.constraints import (
    AXES,
    Cause,
    constraint_labels,
    direction_poses,
    stance_margins,
)
from hexaleg.stance.extremes import Extreme, FlexibilityResult, FlexibilityWarning
from hexaleg.stance.geometry import (
    StanceGeometry,
    constraint_jacobian,
    constraint_residual,
    mechanism_columns,
)


def free_flexibility(
    design: HexapodDesign,
    stance: StanceSet | Sequence[str] = "all",
    model: HexapodModel | None = None,
) -> FlexibilityResult:
    """Free-coupled flexibility: each coordinate's extreme with the other five free."""
    model = HexapodModel(design) if model is None else model
    geometry = StanceGeometry.from_model(model, stance)
    locked = axis_locked_extremes(geometry)
    problem = _FreeProblem(model, geometry)
    extremes = []
    converged = True
    iterations = 0
    for extreme in locked:
        solved, ok, nit = problem.solve(extreme)
        converged &= ok
        iterations += nit
        extremes.append(solved)
    if not converged:
        warnings.warn(
            "free-coupled flexibility: SLSQP did not converge for some directions; "
            "their axis-locked values are kept",
            FlexibilityWarning,
            stacklevel=2,
        )
    return FlexibilityResult(design, geometry.legs, "free", tuple(extremes), converged, iterations)


class _FreeProblem:
    """max ±coordinate s.t. feet on footholds, joints within limits, body above ground.

    Variables x = (ν, θ): ν ∈ R⁶ the body displacement, pose = nominal·exp6(ν);
    θ the stance legs' joint angles. Constraint Jacobians come from Pinocchio.
    """

    def __init__(self, model: HexapodModel, geometry: StanceGeometry) -> None:
        self.model = model
        self.geometry = geometry
        self.columns = mechanism_columns(model, geometry.legs)
        self.q_index = np.concatenate([model.leg_q_indices(leg) for leg in geometry.legs])
        self.q_swing = model.nominal_configuration()
        self.nominal = geometry.nominal_pose
        self.labels = constraint_labels(geometry.legs)
        self.corners = geometry.body_corners(np.eye(3), np.zeros(3))
        limits = geometry.limits
        n = len(geometry.legs)
        self.bounds = [(None, None)] * 6 + [
            (float(limits.lower[j]), float(limits.upper[j])) for _ in range(n) for j in range(3)
        ]

    def pose(self, x: ArrayF) -> pin.SE3:
        return self.nominal * pin.exp6(x[:6])

    def configuration(self, x: ArrayF) -> ArrayF:
        q = self.q_swing.copy()
        q[:7] = pin.SE3ToXYZQUAT(self.pose(x))
        q[self.q_index] = x[6:]
        return q

    def coordinate(self, x: ArrayF, axis: int) -> float:
        pose = self.pose(x)
        if axis < 3:
            return float(pose.translation[axis])
        return float(pin.rpy.matrixToRpy(pose.rotation)[axis - 3])

    def equality(self, x: ArrayF) -> ArrayF:
        return constraint_residual(self.model, self.geometry, self.configuration(x))

    def equality_jacobian(self, x: ArrayF) -> ArrayF:
        jac = constraint_jacobian(self.model, self.geometry, self.configuration(x))[:, self.columns]
        jac[:, :6] = jac[:, :6] @ pin.Jexp6(x[:6])
        return jac

    def ground(self, x: ArrayF) -> ArrayF:
        pose = self.pose(x)
        return (self.corners @ pose.rotation.T + pose.translation)[:, 2]

    def ground_jacobian(self, x: ArrayF) -> ArrayF:
        pose = self.pose(x)
        jac = np.zeros((len(self.corners), len(x)))
        for k, corner in enumerate(self.corners):
            # d(corner z)/dν_local = e_z·R·[I, −[c]×]
            local = np.hstack([np.eye(3), -pin.skew(corner)])
            jac[k, :6] = (pose.rotation @ local)[2] @ pin.Jexp6(x[:6])
        return jac

    def knee_coupling(self, x: ArrayF) -> ArrayF:
        theta = x[6:].reshape(-1, 3)
        return theta[:, 2] - self.geometry.limits.knee_lower(theta[:, 1])

    def start(self, extreme: Extreme) -> ArrayF:
        """A feasible start: the axis-locked extreme pulled back by a hair."""
        axis = AXES.index(extreme.axis)
        back = extreme.value - extreme.sign * 1e-9
        rotation, translation = direction_poses(self.geometry, axis, back)
        body = pin.SE3(rotation, translation)
        nu = pin.log6(self.nominal.inverse() * body).vector
        targets = self.geometry.feet_in_roots(body.rotation, body.translation)
        theta = inverse_kinematics(self.geometry.lengths, targets).theta
        return np.concatenate([nu, theta.ravel()])

    def solve(self, extreme: Extreme) -> tuple[Extreme, bool, int]:
        axis = AXES.index(extreme.axis)
        sign = extreme.sign
        x0 = self.start(extreme)
        nominal_value = self.coordinate(np.zeros_like(x0), axis)
        step = 1e-7

        def objective(x: ArrayF) -> tuple[float, ArrayF]:
            value = self.coordinate(x, axis)
            grad = np.zeros_like(x)
            for k in range(6):  # the pose depends on ν only
                dx = np.zeros_like(x)
                dx[k] = step
                grad[k] = (self.coordinate(x + dx, axis) - self.coordinate(x - dx, axis)) / (
                    2 * step
                )
            return -sign * value, -sign * grad

        constraints = [
            {"type": "eq", "fun": self.equality, "jac": self.equality_jacobian},
            {"type": "ineq", "fun": self.ground, "jac": self.ground_jacobian},
        ]
        if self.geometry.limits.coupled_knee:
            constraints.append({"type": "ineq", "fun": self.knee_coupling})
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            result = optimize.minimize(
                objective,
                x0,
                jac=True,
                method="SLSQP",
                bounds=self.bounds,
                constraints=constraints,
                options={"maxiter": 200, "ftol": 1e-10},
            )
        value = self.coordinate(result.x, axis) - nominal_value
        feasible, cause = self._check(result.x)
        converged = bool(result.success) and feasible
        if feasible and sign * value > sign * extreme.value:
            return Extreme(extreme.axis, sign, float(value), cause), converged, int(result.nit)
        return extreme, converged, int(result.nit)  # axis-locked is feasible: never less

    def _check(self, x: ArrayF) -> tuple[bool, Cause]:
        """Feasibility of the NLP's answer, re-derived by stance IK from its body pose."""
        pose = self.pose(x)
        margins = stance_margins(self.geometry, pose.rotation, pose.translation)
        residual = np.abs(self.equality(x)).max()
        feasible = bool(margins.min() >= -1e-7 and residual <= 1e-7)
        return feasible, self.labels[int(np.argmin(margins))]
