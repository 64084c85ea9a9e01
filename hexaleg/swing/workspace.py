"""Swing-phase workspace of one leg (paper §4): Monte Carlo cloud, planar and improved areas.

The planar workspace (θ1 = 0, eq 14) is the image of a joint domain in
(θ2, θ3) under the 2R map. On a single knee branch (θ3 ∈ [−π, 0]) that map is
one-to-one, so the image's boundary is the image of the domain's boundary and
its area follows exactly from Green's theorem, A = ½∮(x dz − z dx), integrated
along the boundary with adaptive Gauss–Kronrod quadrature (no pixel counting).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from typing import TypeVar

import numpy as np
import numpy.typing as npt
from scipy import integrate

from hexaleg._checks import require_instance, require_int
from hexaleg._typing import ArrayF, Lengths
from hexaleg.design import HexapodDesign, l3_ratio_grid, require_design
from hexaleg.exceptions import HexalegError
from hexaleg.kinematics import foot_position, planar_foot_position
from hexaleg.leg_geometry import LegGeometry
from hexaleg.limits import JointLimits
from hexaleg.robot.model import HexapodModel

Length = TypeVar("Length", float, ArrayF)

MAX_SAMPLES = 5_000_000
"""Most Monte Carlo samples: it bounds the arrays held at the peak (about 1 GB)."""

MAX_SEED = 2**32 - 1
"""Largest seed accepted (NumPy takes any non-negative integer; 32 bits is plenty)."""


@dataclass(frozen=True)
class MonteCarloWorkspace:
    """Foot positions of random joint samples (Fig 5).

    Attributes:
        theta: Joint samples (N, 3), uniform in the limits [rad].
        points: Foot positions (N, 3) in the leg-root frame [m].
        seed: Seed of the random generator.
        limits: The joint limits sampled.

    """

    theta: ArrayF
    points: ArrayF
    seed: int
    limits: JointLimits

    @property
    def lower_bound(self) -> ArrayF:
        """Smallest x, y, z of the cloud in the leg-root frame [m]."""
        return self.points.min(axis=0)

    @property
    def upper_bound(self) -> ArrayF:
        """Largest x, y, z of the cloud in the leg-root frame [m]."""
        return self.points.max(axis=0)


def monte_carlo_workspace(
    design: HexapodDesign,
    samples: int = 20_000,
    seed: int = 0,
    limits: JointLimits | None = None,
    leg: LegGeometry | None = None,
) -> MonteCarloWorkspace:
    """Sample joint angles uniformly within limits and map them to foot positions (eq 7).

    Args:
        design: The design whose leg is sampled.
        samples: Number of random configurations N.
        seed: Seed of NumPy's default generator, for reproducible clouds.
        limits: Joint limits to sample; the design's Table 2 ``workspace_limits`` by default.
        leg: A general leg (an imported robot's) to map them with; the design's by default.

    """
    design = require_design(design)
    samples = require_int("samples", samples, 1, MAX_SAMPLES)
    seed = require_int("seed", seed, 0, MAX_SEED)
    limits = design.workspace_limits if limits is None else limits
    require_instance("limits", limits, JointLimits, "a JointLimits or None")
    rng = np.random.default_rng(seed)
    theta = rng.uniform(limits.lower, limits.upper, size=(samples, 3))
    if limits.coupled_knee:  # resample the knee within its coupled bound
        knee_lower = limits.knee_lower(theta[:, 1])
        theta[:, 2] = knee_lower + rng.random(samples) * (limits.theta3[1] - knee_lower)
    shape = design.lengths if leg is None else leg
    return MonteCarloWorkspace(theta, foot_position(shape, theta), seed, limits)


def standing_reach(
    model: HexapodModel, samples: int = 20_000, seed: int = 0
) -> dict[str, MonteCarloWorkspace]:
    """Each leg's reach while it stands, in its leg-root frame: a Monte Carlo cloud by leg.

    Each leg's own general leg within the limits that hold it standing: the model's
    stance limits, else (a robot file's) the leg's own joint limits. Legs alike (every
    leg of hexaleg's template) share one cloud.
    """
    clouds: dict[str, MonteCarloWorkspace] = {}
    made: dict[tuple[object, ...], MonteCarloWorkspace] = {}
    for leg in model.leg_names:
        limits = model.stance_limits
        if limits is None:
            lower, upper = model.joint_limits(leg)
            root, hip, knee = ((float(a), float(b)) for a, b in zip(lower, upper, strict=True))
            limits = JointLimits(root, hip, knee, name=f"{leg}'s own limits")
        shape = model.leg_geometry(leg)
        key = (limits.lower.tobytes(), limits.upper.tobytes(), limits.coupled_knee, shape.lengths,
               shape.hip_height, shape.foot_lateral)  # fmt: skip
        if key not in made:
            made[key] = monte_carlo_workspace(model.design, samples, seed, limits, shape)
        clouds[leg] = made[key]
    return clouds


@dataclass(frozen=True)
class PlanarWorkspace:
    """Planar foot workspace at θ1 = 0 (eq 14) of one joint domain.

    Attributes:
        lengths: Segment lengths (l1, l2, l3) [m].
        limits: The (θ2, θ3) domain; ``coupled_knee`` selects the improved domain.
        boundary: Closed boundary polygon (M, 2) of (x, z) in the leg plane [m],
            counter-clockwise, first point not repeated.
        area: Area enclosed by the boundary [m²], by exact boundary integration.

    """

    lengths: Lengths
    limits: JointLimits
    boundary: ArrayF
    area: float


def planar_workspace(
    lengths: Lengths, limits: JointLimits, points_per_edge: int = 200
) -> PlanarWorkspace:
    """Boundary and area of the planar workspace of ``limits`` (θ2, θ3 part).

    Args:
        lengths: Segment lengths (l1, l2, l3) [m].
        limits: Joint domain; with ``coupled_knee`` the improved domain of Table 4.
        points_per_edge: Samples along each of the four boundary edges of the polygon.

    """
    _require_single_knee_branch(limits)
    edges = _boundary_edges(limits)
    area = abs(sum(_green_integral(lengths, edge) for edge in edges))
    polygon = np.concatenate(
        [
            planar_foot_position(
                lengths, *edge.angles(np.linspace(edge.start, edge.stop, points_per_edge)[:-1])
            )
            for edge in edges
        ]
    )
    if _shoelace(polygon) < 0:
        polygon = polygon[::-1]
    return PlanarWorkspace(tuple(lengths), limits, polygon, float(area))  # type: ignore[arg-type]


def improved_area_closed_form(l2: Length, l3: Length) -> Length:
    """Improved-workspace area S_W = 2π·l2·l3/3 [m²] (eq 16), of one design or an array."""
    return 2 * math.pi * l2 * l3 / 3


def _require_single_knee_branch(limits: JointLimits) -> None:
    lower, upper = limits.theta3
    if lower < -math.pi or upper > 0:
        raise HexalegError(
            f"{limits.name}.theta3 = ({lower:.6g}, {upper:.6g}) spans both knee branches: "
            "planar areas need θ3 within [-π, 0] [rad]"
        )
    if limits.theta2[1] - limits.theta2[0] > 2 * math.pi:
        raise HexalegError(f"{limits.name}.theta2 spans more than a full turn")
    if np.any(limits.knee_lower(np.array(limits.theta2)) >= upper):
        raise HexalegError(f"{limits.name}: the coupled knee bound leaves an empty domain")


@dataclass(frozen=True)
class _Edge:
    """One boundary edge of a (θ2, θ3) domain: θ(t) = (θ2, θ3) for t from start to stop."""

    hip: Callable[[ArrayF], ArrayF]
    knee: Callable[[ArrayF], ArrayF]
    hip_rate: Callable[[ArrayF], ArrayF]  # dθ2/dt
    knee_rate: Callable[[ArrayF], ArrayF]  # dθ3/dt
    start: float
    stop: float
    kinks: tuple[float, ...] = ()

    def angles(self, t: ArrayF) -> tuple[ArrayF, ArrayF]:
        return self.hip(t), self.knee(t)


def _boundary_edges(limits: JointLimits) -> list[_Edge]:
    """The domain boundary in (θ2, θ3) as four parametrized edges, counter-clockwise in θ."""
    (h_lo, h_hi), (k_lo, k_hi) = limits.theta2, limits.theta3

    def const(value: float) -> Callable[[ArrayF], ArrayF]:
        return lambda t: np.full_like(np.asarray(t, dtype=float), value)

    def ident(t: ArrayF) -> ArrayF:
        return np.asarray(t, dtype=float)

    def coupled_rate(t: ArrayF) -> ArrayF:  # d/dθ2 of max(k_lo, -θ2 - π/2)
        return np.where(limits.knee_lower(t) > k_lo, -1.0, 0.0)

    kinks: tuple[float, ...] = ()
    if limits.coupled_knee and h_lo < -k_lo - math.pi / 2 < h_hi:
        kinks = (-k_lo - math.pi / 2,)
    return [
        _Edge(ident, limits.knee_lower, const(1.0), coupled_rate, h_lo, h_hi, kinks),
        _Edge(const(h_hi), ident, const(0.0), const(1.0), float(limits.knee_lower(h_hi)), k_hi),
        _Edge(ident, const(k_hi), const(1.0), const(0.0), h_hi, h_lo),
        _Edge(const(h_lo), ident, const(0.0), const(1.0), k_hi, float(limits.knee_lower(h_lo))),
    ]


def _green_integral(lengths: Lengths, edge: _Edge) -> float:
    """½∫(x dz − z dx) along one boundary edge, by adaptive Gauss–Kronrod quadrature."""
    if edge.start == edge.stop:
        return 0.0
    _, l2, l3 = lengths

    def integrand(t: float) -> float:
        hip, knee = edge.angles(np.asarray(t))
        x, z = planar_foot_position(lengths, hip, knee)
        s2, c2 = math.sin(hip), math.cos(hip)
        s23, c23 = math.sin(hip + knee), math.cos(hip + knee)
        rate2, rate3 = float(edge.hip_rate(np.asarray(t))), float(edge.knee_rate(np.asarray(t)))
        dx = (-l2 * s2 - l3 * s23) * rate2 - l3 * s23 * rate3
        dz = (l2 * c2 + l3 * c23) * rate2 + l3 * c23 * rate3
        return 0.5 * (x * dz - z * dx)

    lo, hi = sorted((edge.start, edge.stop))
    with warnings.catch_warnings():
        # asked for at round-off level, quad says so when it gets there (extreme length
        # ratios); its own error estimate decides instead
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        value, error = integrate.quad(
            integrand, lo, hi, epsabs=1e-15, epsrel=1e-13, limit=200, points=edge.kinks or None
        )
    if error > 1e-9 * max(abs(value), (l2 + l3) ** 2):
        warnings.warn(
            f"workspace area: boundary integral accurate only to {error:.2g} m²",
            RuntimeWarning,
            stacklevel=2,
        )
    return float(value if edge.start < edge.stop else -value)


def _shoelace(polygon: ArrayF) -> float:
    x, z = polygon[:, 0], polygon[:, 1]
    return float(0.5 * np.sum(x * np.roll(z, -1) - np.roll(x, -1) * z))


def improved_area_by_l3_ratio(
    l1_ratio: float, l3_ratios: npt.ArrayLike, total: float, limits: JointLimits
) -> ArrayF:
    """Numerical improved-workspace area for each tibia ratio at a fixed coxa ratio [m²].

    Used to show the paper's claim after eq 16: for fixed l1 the area peaks at l2 = l3.
    """
    l1 = l1_ratio * total
    return np.array(
        [
            planar_workspace((l1, total - l1 - r3 * total, r3 * total), limits).area
            for r3 in np.asarray(l3_ratios, dtype=float)
        ]
    )


@dataclass(frozen=True)
class CoxaSeries:
    """Fig 8: the improved workspace per coxa ratio, and its area against tibia ratio.

    Attributes:
        l1_ratios: Coxa ratios of the series [-] (each with l2 = l3).
        workspaces: The improved planar workspace at each of them.
        fixed_l1_ratio: The design's own coxa ratio [-].
        l3_ratios: Tibia ratios at that coxa ratio (R3,) [-].
        areas: Numerical improved area at each (R3,) [m²].

    """

    l1_ratios: tuple[float, ...]
    workspaces: tuple[PlanarWorkspace, ...]
    fixed_l1_ratio: float
    l3_ratios: ArrayF
    areas: ArrayF


def coxa_series(design: HexapodDesign, l1_ratios: tuple[float, ...]) -> CoxaSeries:
    """Fig 8's data at ``design``'s leg length and improved limits.

    Args:
        design: The design (its leg length, coxa ratio and improved limits).
        l1_ratios: Coxa ratios of the series, each with equal femur and tibia [-].

    """
    total = design.leg_length
    fixed = design.l1 / total
    l3_ratios = l3_ratio_grid()
    l3_ratios = l3_ratios[l3_ratios < 1 - fixed - 0.02]
    return CoxaSeries(
        l1_ratios=l1_ratios,
        workspaces=tuple(
            planar_workspace(
                (r * total, (1 - r) * total / 2, (1 - r) * total / 2), design.improved_limits
            )
            for r in l1_ratios
        ),
        fixed_l1_ratio=fixed,
        l3_ratios=l3_ratios,
        areas=improved_area_by_l3_ratio(fixed, l3_ratios, total, design.improved_limits),
    )


@dataclass(frozen=True)
class WorkspaceAnalysis:
    """Everything §4 tells about one design's swing-phase workspace.

    Attributes:
        design: The design analysed.
        monte_carlo: The Monte Carlo cloud (Table 2 limits).
        rectangular: Planar workspace on the rectangular domain (Table 3).
        improved: Planar workspace on the improved domain (Table 4).
        improved_closed_form: Eq 16's S_W = 2π·l2·l3/3 [m²].

    """

    design: HexapodDesign
    monte_carlo: MonteCarloWorkspace
    rectangular: PlanarWorkspace
    improved: PlanarWorkspace
    improved_closed_form: float

    def to_dict(self, design: bool = True) -> dict:
        """JSON-ready summary (SI units: m, m², rad), with the design unless ``design`` is off."""
        out = {
            "area": {
                "improved": self.improved.area,
                "improved_closed_form": self.improved_closed_form,
                "rectangular": self.rectangular.area,
            },
            "monte_carlo": {
                "samples": len(self.monte_carlo.points),
                "seed": self.monte_carlo.seed,
                "lower_bound": self.monte_carlo.lower_bound.tolist(),
                "upper_bound": self.monte_carlo.upper_bound.tolist(),
            },
            "units": {"area": "m^2", "bound": "m, leg-root frame"},
        }
        return {**out, "design": self.design.as_dict()} if design else out


def analyze_workspace(
    design: HexapodDesign, samples: int = 20_000, seed: int = 0, leg: LegGeometry | None = None
) -> WorkspaceAnalysis:
    """Monte Carlo cloud, planar and improved workspaces of ``design``'s leg.

    A general ``leg`` (an imported robot's) gives the cloud and the segments; its planar
    workspace is the paper leg's of its (a1, l2, l3) lifted by the hip height h (the
    lateral offset e lies off that plane), so the areas are those of (a1, l2, l3).
    """
    design = require_design(design)
    lengths = design.lengths if leg is None else leg.lengths
    return WorkspaceAnalysis(
        design=design,
        monte_carlo=monte_carlo_workspace(design, samples, seed, leg=leg),
        rectangular=planar_workspace(lengths, design.workspace_limits),
        improved=planar_workspace(lengths, design.improved_limits),
        improved_closed_form=improved_area_closed_form(lengths[1], lengths[2]),
    )
