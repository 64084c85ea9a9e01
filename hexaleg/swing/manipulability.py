"""Manipulability of one leg (paper §5): indices, optimum pose, average manipulability.

w = |det J| [m³] of the 3×3 foot-velocity Jacobian (eq 23). Single poses are
evaluated on the Pinocchio model; grids and design sweeps use the vectorized
closed form of :mod:`hexaleg.kinematics`, which the tests prove equal to it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import numpy.typing as npt
from scipy import optimize

from hexaleg._checks import require_instance
from hexaleg._typing import ArrayF, Lengths
from hexaleg.design import DEFAULT_LEG_LENGTH, HexapodDesign, require_design
from hexaleg.kinematics import foot_jacobian, manipulability
from hexaleg.leg_geometry import LegGeometry
from hexaleg.limits import JointLimits
from hexaleg.robot.leg_model import LegModel

GRID_STEP = math.radians(1.0)
"""Spacing of the w_A grid (eq 27): one characteristic value per degree [rad]."""


@dataclass(frozen=True)
class ManipulabilityIndices:
    """Dexterity indices of one pose, from the foot-velocity Jacobian.

    Attributes:
        w: Manipulability |det J| [m³] (eq 23).
        condition_number: σ_max / σ_min of J [-] (∞ at a singularity).
        min_singular_value: σ_min of J [m/rad]: the slowest foot speed per unit joint speed.

    """

    w: float
    condition_number: float
    min_singular_value: float


def indices_from_jacobian(jacobian: npt.ArrayLike) -> ManipulabilityIndices:
    """Manipulability indices of a square Jacobian."""
    jac = np.asarray(jacobian, dtype=float)
    singular = np.linalg.svd(jac, compute_uv=False)
    smallest = float(singular[-1])
    condition = float(singular[0] / smallest) if smallest > 0 else math.inf
    return ManipulabilityIndices(abs(float(np.linalg.det(jac))), condition, smallest)


def pose_indices(leg: LegModel, theta: npt.ArrayLike) -> ManipulabilityIndices:
    """Indices at joint angles θ (3,) [rad], from the Pinocchio Jacobian of ``leg``."""
    return indices_from_jacobian(leg.foot_jacobian(theta))


# -- optimum pose (eq 25–26) ------------------------------------------------------------


@dataclass(frozen=True)
class OptimumPose:
    """Pose of maximum manipulability within limits (Table 6).

    Attributes:
        theta2: Hip angle [rad].
        theta3: Knee angle [rad].
        w: Manipulability there [m³].
        converged: Whether the local refinement reported success.

    """

    theta2: float
    theta3: float
    w: float
    converged: bool


def optimum_pose(lengths: Lengths, limits: JointLimits, starts: int = 8) -> OptimumPose:
    """Maximize w over (θ2, θ3) within ``limits`` (eq 25–26), robust to local optima.

    A 1° grid locates the basins; the ``starts`` best grid points that are local
    maxima of the grid are refined with bounded L-BFGS-B on the analytic gradient,
    and the best refined point wins.

    Args:
        lengths: Segment lengths (l1, l2, l3) [m].
        limits: Hip and knee intervals (θ1 does not affect w; coupling is honoured
            by the grid only, the paper's eq 26 has none).
        starts: Number of grid local maxima to refine.

    """
    hip, knee = joint_grid(limits)
    values = manipulability(lengths, hip[:, None], knee[None, :])
    order = np.argsort(values, axis=None)[::-1]
    candidates = [np.unravel_index(i, values.shape) for i in order[: max(starts * 20, 1)]]
    seeds = _distinct_local_maxima(values, candidates, starts)
    bounds = [limits.theta2, limits.theta3]

    def refine(i: int, j: int) -> OptimumPose:
        result = optimize.minimize(
            _negative_w_and_gradient,
            x0=[hip[i], knee[j]],
            args=(lengths,),
            jac=True,
            method="L-BFGS-B",
            bounds=bounds,
            options={"ftol": 1e-15, "gtol": 1e-12, "maxiter": 500},
        )
        return OptimumPose(
            float(result.x[0]), float(result.x[1]), -float(result.fun), result.success
        )

    return max((refine(i, j) for i, j in seeds), key=lambda pose: pose.w)


def _distinct_local_maxima(values: ArrayF, candidates: list, count: int) -> list:
    """Grid points among ``candidates`` that beat their 8 neighbours, best first."""
    padded = np.pad(values, 1, constant_values=-np.inf)
    seeds = []
    for i, j in candidates:
        window = padded[i : i + 3, j : j + 3]
        if values[i, j] >= window.max():
            seeds.append((i, j))
        if len(seeds) == count:
            break
    return seeds or candidates[:1]


def _negative_w_and_gradient(x: ArrayF, lengths: Lengths) -> tuple[float, ArrayF]:
    l1, l2, l3 = lengths
    t2, t3 = x
    reach = l1 + l2 * math.cos(t2) + l3 * math.cos(t2 + t3)
    signed = l2 * l3 * math.sin(t3) * reach
    d_reach_2 = -l2 * math.sin(t2) - l3 * math.sin(t2 + t3)
    d_reach_3 = -l3 * math.sin(t2 + t3)
    grad = (
        l2
        * l3
        * np.array([math.sin(t3) * d_reach_2, math.cos(t3) * reach + math.sin(t3) * d_reach_3])
    )
    sign = 1.0 if signed >= 0 else -1.0
    return -abs(signed), -sign * grad


# -- average manipulability (eq 27) ----------------------------------------------------


def joint_grid(limits: JointLimits, step: float = GRID_STEP) -> tuple[ArrayF, ArrayF]:
    """Characteristic values of θ2 and θ3 every ``step`` across the limits [rad] (eq 27)."""
    return _grid_axis(limits.theta2, step), _grid_axis(limits.theta3, step)


@dataclass(frozen=True)
class ManipulabilitySurface:
    """w over the joint grid of one leg (Fig 10).

    Attributes:
        lengths: Segment lengths (l1, l2, l3) [m].
        theta2: Hip angles (M,) [rad].
        theta3: Knee angles (N,) [rad].
        w: |det J| at each (θ2, θ3) (M, N) [m³].

    """

    lengths: Lengths
    theta2: ArrayF
    theta3: ArrayF
    w: ArrayF


def manipulability_surface(lengths: Lengths, limits: JointLimits) -> ManipulabilitySurface:
    """Manipulability w on eq 27's grid of ``limits`` (one per degree), leg ``lengths`` [m]."""
    hip, knee = joint_grid(limits)
    t2, t3 = np.meshgrid(hip, knee, indexing="ij")
    return ManipulabilitySurface(lengths, hip, knee, manipulability(lengths, t2, t3))


def _grid_axis(bounds: tuple[float, float], step: float) -> ArrayF:
    lower, upper = bounds
    count = round((upper - lower) / step) + 1
    return np.linspace(lower, upper, count)


def average_manipulability(
    lengths: npt.ArrayLike, limits: JointLimits, step: float = GRID_STEP
) -> ArrayF:
    """Average manipulability w_A [m³] (eq 27) of one or many designs.

    The mean of w over the grid of :func:`joint_grid`; with ``limits.coupled_knee``
    only the grid points inside the coupled (improved) domain count.

    Args:
        lengths: Segment lengths (3,) or (D, 3) for D designs at once [m].
        limits: The joint domain (eq 26's rectangle, or it coupled as in Table 4).
        step: Grid spacing [rad].

    Returns:
        w_A as a scalar array () or (D,) [m³].

    """
    lengths = np.asarray(lengths, dtype=float)
    hip, knee = joint_grid(limits, step)
    t2, t3 = np.meshgrid(hip, knee, indexing="ij")
    mask = limits.contains(np.stack([np.zeros_like(t2), t2, t3], axis=-1), tol=1e-12)
    # Trigonometry depends only on the grid: evaluate it once for every design. The
    # reach l1 + l2·cos θ2 + l3·cos(θ2+θ3) is linear in the lengths: one matrix product.
    hip_m, knee_m = t2[mask], t3[mask]
    basis = np.stack([np.ones_like(hip_m), np.cos(hip_m), np.cos(hip_m + knee_m)])
    sin3 = np.abs(np.sin(knee_m))
    flat = lengths.reshape(-1, 3)
    reach = flat @ basis
    np.abs(reach, out=reach)
    w_mean = flat[:, 1] * flat[:, 2] * (reach @ sin3) / sin3.size
    return w_mean.reshape(lengths.shape[:-1])


@dataclass(frozen=True)
class AverageManipulabilityMap:
    """w_A over a grid of designs of fixed total length (Fig 11).

    Attributes:
        l1_ratios: Coxa ratios (R1,) [-].
        l3_ratios: Tibia ratios (R3,) [-].
        total: Total leg length [m].
        rectangular: w_A on eq 26's rectangular domain (R1, R3) [m³].
        improved: w_A on the same grid restricted to the improved domain (R1, R3) [m³].
        peak_rectangular: For each l1 ratio, the l3 ratio maximizing w_A (R1,) [-].
        peak_improved: The same on the improved domain (R1,) [-].

    """

    l1_ratios: ArrayF
    l3_ratios: ArrayF
    total: float
    rectangular: ArrayF
    improved: ArrayF
    peak_rectangular: ArrayF
    peak_improved: ArrayF


def average_manipulability_map(
    l1_ratios: npt.ArrayLike,
    l3_ratios: npt.ArrayLike,
    total: float = DEFAULT_LEG_LENGTH,
    limits: JointLimits | None = None,
) -> AverageManipulabilityMap:
    """w_A for every (l1 ratio, l3 ratio) pair, on both domains, with the peaks refined.

    Args:
        l1_ratios: Coxa ratios [-].
        l3_ratios: Tibia ratios [-]; pairs leaving no femur give NaN.
        total: Total leg length [m].
        limits: Rectangular domain; the default design's eq 26 limits if omitted.

    """
    rect, improved = rectangular_and_improved(
        HexapodDesign().manipulability_limits if limits is None else limits
    )
    r1 = np.asarray(l1_ratios, dtype=float)
    r3 = np.asarray(l3_ratios, dtype=float)
    lengths = _ratio_lengths(r1[:, None], r3[None, :], total)
    valid = lengths[..., 1] > 0
    maps = []
    peaks = []
    for domain in (rect, improved):
        values = np.full(valid.shape, np.nan)
        values[valid] = average_manipulability(lengths[valid], domain)
        maps.append(values)
        peaks.append(
            np.array(
                [_refine_peak(r, r3, row, total, domain) for r, row in zip(r1, values, strict=True)]
            )
        )
    return AverageManipulabilityMap(r1, r3, total, maps[0], maps[1], peaks[0], peaks[1])


def _ratio_lengths(l1_ratio: ArrayF, l3_ratio: ArrayF, total: float) -> ArrayF:
    l1, l3 = np.broadcast_arrays(l1_ratio * total, l3_ratio * total)
    return np.stack([l1, total - l1 - l3, l3], axis=-1)


def _refine_peak(
    l1_ratio: float, l3_ratios: ArrayF, values: ArrayF, total: float, domain: JointLimits
) -> float:
    """The l3 ratio of maximum w_A, refined between the grid neighbours of the best point."""
    if np.all(np.isnan(values)):
        return math.nan
    k = int(np.nanargmax(values))
    lo = l3_ratios[max(k - 1, 0)]
    hi = l3_ratios[min(k + 1, len(l3_ratios) - 1)]
    if lo == hi:
        return float(l3_ratios[k])

    def negative(r3: float) -> float:
        return -float(
            average_manipulability(_ratio_lengths(np.array(l1_ratio), np.array(r3), total), domain)
        )

    result = optimize.minimize_scalar(
        negative, bounds=(lo, hi), method="bounded", options={"xatol": 1e-7}
    )
    return float(result.x)


@dataclass(frozen=True)
class ManipulabilityAnalysis:
    """Everything §5 tells about one design's leg.

    Attributes:
        design: The design analysed.
        optimum: Pose of maximum w within the eq 26 limits.
        optimum_indices: Indices at the optimum, from the Pinocchio Jacobian.
        average_rectangular: w_A on eq 26's rectangular grid [m³].
        average_improved: w_A on the grid points inside the improved domain [m³].

    """

    design: HexapodDesign
    optimum: OptimumPose
    optimum_indices: ManipulabilityIndices
    average_rectangular: float
    average_improved: float

    def to_dict(self, design: bool = True) -> dict:
        """JSON-ready summary (SI units: rad, m³); the design's fields unless ``design`` is off."""
        out = {
            "optimum": {
                "theta2": self.optimum.theta2,
                "theta3": self.optimum.theta3,
                "w": self.optimum.w,
                "converged": self.optimum.converged,
                "condition_number": self.optimum_indices.condition_number,
                "min_singular_value": self.optimum_indices.min_singular_value,
            },
            "average": {
                "rectangular": self.average_rectangular,
                "improved": self.average_improved,
            },
            "units": {"angle": "rad", "w": "m^3", "min_singular_value": "m/rad"},
        }
        return {**out, "design": self.design.as_dict()} if design else out


def analyze_manipulability(
    design: HexapodDesign, leg: LegModel | None = None, general: LegGeometry | None = None
) -> ManipulabilityAnalysis:
    """Optimum pose, indices there and w_A on both domains.

    The indices come from the Pinocchio model of ``design``'s leg, or, for a ``general``
    leg (an imported robot's), from its closed-form Jacobian (proven equal to Pinocchio's
    on the robot's file). w = |det J| depends on (a1, l2, l3) alone, not on the offsets.
    """
    design = require_design(design)
    limits = design.manipulability_limits
    lengths = design.lengths if general is None else general.lengths
    optimum = optimum_pose(lengths, limits)
    pose = [0.0, optimum.theta2, optimum.theta3]
    if general is None:
        model = (
            LegModel(design)
            if leg is None
            else require_instance("leg", leg, LegModel, "a LegModel")
        )
        indices = pose_indices(model, pose)
    else:
        indices = indices_from_jacobian(foot_jacobian(general, pose))
    rect, improved = rectangular_and_improved(limits)
    return ManipulabilityAnalysis(
        design=design,
        optimum=optimum,
        optimum_indices=indices,
        average_rectangular=float(average_manipulability(lengths, rect)),
        average_improved=float(average_manipulability(lengths, improved)),
    )


def rectangular_and_improved(limits: JointLimits) -> tuple[JointLimits, JointLimits]:
    """Eq 26's rectangle and the same restricted by Table 4's coupled knee bound."""
    rect = replace(limits, coupled_knee=False)
    return rect, replace(limits, coupled_knee=True, name=f"{limits.name}+improved")
