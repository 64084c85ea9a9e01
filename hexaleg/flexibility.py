"""Body flexibility with the feet planted (paper §6, eq 28–29), replacing the ADAMS study.

Axis-locked (the ADAMS semantics, see DESIGN.md): the body moves along one of
x, y, z, roll, pitch, yaw from the nominal stance, the other five held, until
the first constraint breaks — a foot out of reach, a joint past its stance
limit, or the body touching the ground. All twelve directions are searched at
once: a vectorized coarse scan finds the first infeasible sample (so a pose
that is feasible again beyond the first failure never counts), nested scans
shrink that bracket to ~1e-7 of the range, and the breaking constraint's own
margin is refined by regula falsi inside it.

Free-coupled: each coordinate is pushed as far as the mechanism allows with the
other five free, a constrained nonlinear program (SLSQP) on the Pinocchio
model's configuration, started from the axis-locked extreme so its range is
never smaller.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
import pinocchio as pin
from scipy import optimize

from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.kinematics import inverse_kinematics, leg_solution
from hexaleg.model import LEG_JOINTS, HexapodModel
from hexaleg.stance import (
    StanceGeometry,
    constraint_jacobian,
    constraint_residual,
    mechanism_columns,
)

ArrayF = npt.NDArray[np.float64]

AXES: tuple[str, ...] = ("x", "y", "z", "roll", "pitch", "yaw")
"""Body coordinates, translations [m] then rotations about the world axes [rad]."""
TRANSLATIONS = AXES[:3]
DIRECTIONS: tuple[tuple[str, int], ...] = tuple((a, s) for a in AXES for s in (1, -1))
"""The twelve (axis, sign) directions of the flexibility study."""

SCAN_STEPS = 256
"""Resolution of the first-failure scan: t_max / 256 (≈ 8 mm or 0.7° for a 1 m leg)."""
SCAN_CHUNKS = 8
REFINE_ITERATIONS = 60
MARGIN_ROUNDOFF = 1e-15
"""A margin this small [m or rad] is zero to round-off: its end of the bracket is the root."""
BRACKET_TOLERANCE = 1e-12
"""Final bracket width relative to the searched distance (at least 1 m or 1 rad)."""


class FlexibilityWarning(UserWarning):
    """An optimizer did not converge; the result keeps the best feasible value found."""


@dataclass(frozen=True)
class Cause:
    """The constraint that stops the body.

    Attributes:
        kind: ``"joint"`` (a joint limit), ``"reach"`` (foothold out of the leg's
            reach), ``"ground"`` (the body touches the ground) or ``"range"`` (nothing
            broke within the searched range).
        leg: Leg name, for joint and reach causes.
        joint: ``"root"``, ``"hip"`` or ``"knee"``, for joint causes.
        bound: ``"lower"``/``"upper"`` for joints, ``"outer"``/``"inner"`` for reach.

    """

    kind: str
    leg: str | None = None
    joint: str | None = None
    bound: str | None = None

    def __str__(self) -> str:
        if self.kind == "joint":
            return f"{self.leg} {self.joint} joint at its {self.bound} limit"
        if self.kind == "reach":
            edge = "too far" if self.bound == "outer" else "too close"
            return f"{self.leg} foothold out of reach ({edge})"
        if self.kind == "ground":
            return "body touches the ground"
        return "end of the searched range"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {"kind": self.kind, "leg": self.leg, "joint": self.joint, "bound": self.bound}


@dataclass(frozen=True)
class Extreme:
    """How far the body goes in one direction.

    Attributes:
        axis: One of :data:`AXES`.
        sign: +1 or −1.
        value: Signed displacement from the nominal pose at the extreme [m or rad].
        limited_by: The constraint that stops it.

    """

    axis: str
    sign: int
    value: float
    limited_by: Cause

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (value in m or rad)."""
        return {
            "axis": self.axis,
            "sign": self.sign,
            "value": self.value,
            "limited_by": self.limited_by.to_dict(),
            "description": str(self.limited_by),
        }


@dataclass(frozen=True)
class FlexibilityResult:
    """The twelve extremes, the six ranges (eq 28) and FB (eq 29) of one design.

    Attributes:
        design: The design analysed.
        legs: Stance legs.
        mode: ``"axis"`` (axis-locked) or ``"free"`` (free-coupled).
        extremes: One per direction of :data:`DIRECTIONS`.
        converged: False if an optimizer (free mode) failed somewhere.
        iterations: Optimizer iterations summed over the twelve directions (0 for axis mode).

    """

    design: HexapodDesign
    legs: tuple[str, ...]
    mode: str
    extremes: tuple[Extreme, ...]
    converged: bool = True
    iterations: int = 0

    def extreme(self, axis: str, sign: int) -> Extreme:
        """The extreme in direction (axis, sign)."""
        return next(e for e in self.extremes if e.axis == axis and e.sign == sign)

    @property
    def ranges(self) -> dict[str, float]:
        """S_x, S_y, S_z [m] and φ_x, φ_y, φ_z [rad] (eq 28), keyed x y z roll pitch yaw."""
        return {a: self.extreme(a, 1).value - self.extreme(a, -1).value for a in AXES}

    @property
    def fb(self) -> float:
        """Flexibility index FB (eq 29), angles in degrees as the paper defines it [-]."""
        return flexibility_index(self.ranges, self.design.leg_length)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary: fb, ranges, extremes and every design field used."""
        return {
            "fb": self.fb,
            "mode": self.mode,
            "stance": list(self.legs),
            "converged": self.converged,
            "ranges": self.ranges,
            "extremes": [e.to_dict() for e in self.extremes],
            "units": {"x y z": "m", "roll pitch yaw": "rad", "fb": "1"},
            "design": self.design.as_dict(),
        }


def flexibility_index(ranges: dict[str, float], leg_length: float) -> float:
    """FB = (1/6)·[(S_x+S_y+S_z)/(2L) + (φ_x+φ_y+φ_z)/180°] (eq 29).

    Args:
        ranges: S_x, S_y, S_z [m] and φ_x, φ_y, φ_z [rad], keyed as :data:`AXES`.
        leg_length: L = l1 + l2 + l3 [m].

    """
    translation = sum(ranges[a] for a in TRANSLATIONS) / (2 * leg_length)
    rotation = sum(math.degrees(ranges[a]) for a in AXES[3:]) / 180.0
    return (translation + rotation) / 6.0


# -- poses along the twelve directions -------------------------------------------------


def direction_poses(
    geometry: StanceGeometry, axis_index: npt.ArrayLike, value: npt.ArrayLike
) -> tuple[ArrayF, ArrayF]:
    """Body rotations (..., 3, 3) and translations (..., 3) displaced along one coordinate.

    Args:
        geometry: Provides the nominal pose.
        axis_index: Index into :data:`AXES` per sample.
        value: Signed displacement per sample [m or rad].

    """
    axis_index = np.asarray(axis_index)
    value = np.asarray(value, dtype=float)
    axis_index, value = np.broadcast_arrays(axis_index, value)
    translation = np.zeros((*value.shape, 3))
    translation[..., 2] = geometry.nominal_height
    is_translation = axis_index < 3
    for k in range(3):
        translation[..., k] += np.where(is_translation & (axis_index == k), value, 0.0)
    rotation = np.broadcast_to(np.eye(3), (*value.shape, 3, 3)).copy()
    c, s = np.cos(value), np.sin(value)
    for k, (i, j) in enumerate(((1, 2), (2, 0), (0, 1))):  # about x, y, z
        sel = axis_index == 3 + k
        rotation[sel, i, i] = c[sel]
        rotation[sel, j, j] = c[sel]
        rotation[sel, i, j] = -s[sel]
        rotation[sel, j, i] = s[sel]
    return rotation, translation


# -- constraint margins ------------------------------------------------------------------


def constraint_labels(legs: Sequence[str]) -> list[Cause]:
    """Causes in the column order of :func:`stance_margins`."""
    labels = []
    for leg in legs:
        labels += [Cause("reach", leg, bound="outer"), Cause("reach", leg, bound="inner")]
    for leg in legs:
        for joint in LEG_JOINTS:
            labels += [Cause("joint", leg, joint, "lower"), Cause("joint", leg, joint, "upper")]
    return [*labels, Cause("ground")]


def stance_margins(geometry: StanceGeometry, rotation: ArrayF, translation: ArrayF) -> ArrayF:
    """Every constraint's margin (..., 8N + 1) for body poses: ≥ 0 feasible, < 0 broken.

    Columns (see :func:`constraint_labels`): per leg the outer and inner reach [m];
    per leg and joint the lower and upper limit [rad]; last the lowest body corner's
    height above the ground [m].
    """
    _, l2, l3 = geometry.lengths
    targets = geometry.feet_in_roots(rotation, translation)  # (..., N, 3)
    theta, r = leg_solution(geometry.lengths, targets)  # knee-down IK (..., N, 3), (..., N)
    reach = np.stack([l2 + l3 - r, r - abs(l2 - l3)], axis=-1)  # (..., N, 2)
    limits = geometry.limits
    lower = np.broadcast_to(limits.lower, theta.shape).copy()
    lower[..., 2] = limits.knee_lower(theta[..., 1])
    joints = np.stack([theta - lower, limits.upper - theta], axis=-1)  # (..., N, 3, 2)
    ground = geometry.lowest_corner_height(rotation, translation)
    shape = theta.shape[:-2]
    return np.concatenate(
        [reach.reshape(*shape, -1), joints.reshape(*shape, -1), ground[..., None]], axis=-1
    )


# -- axis-locked search ------------------------------------------------------------------


def search_ranges(geometry: StanceGeometry) -> ArrayF:
    """How far each direction is searched: 2L for translations, π for rotations."""
    leg_length = sum(geometry.lengths)
    return np.array([2 * leg_length if a in TRANSLATIONS else math.pi for a, _ in DIRECTIONS])


def first_crossings(
    margins: Callable[[ArrayF, ArrayF], ArrayF], t_max: ArrayF
) -> tuple[ArrayF, npt.NDArray[np.int_]]:
    """For each direction d, the first t ∈ (0, t_max[d]] where any margin turns negative.

    The scan steps through (0, t_max] at t_max/:data:`SCAN_STEPS` in chunks, dropping
    directions that have broken, so only the first failure along the motion counts.
    In each bracket every constraint that broke is solved on its own (smooth) margin by
    Anderson–Björck regula falsi, and the earliest root wins.

    Args:
        margins: Maps (direction index (K,), t (K,)) to margins (K, C).
        t_max: Search range per direction (D,).

    Returns:
        The crossing t per direction (t_max where nothing breaks), and the index of
        the breaking constraint (−1 where nothing breaks).

    """
    t_max = np.asarray(t_max, dtype=float)
    count = len(t_max)
    lo, hi = np.zeros(count), t_max.copy()
    broken = np.zeros(count, dtype=bool)
    per_chunk = SCAN_STEPS // SCAN_CHUNKS
    fractions = np.linspace(0.0, 1.0, per_chunk + 1)
    for chunk in range(SCAN_CHUNKS):
        active = np.flatnonzero(~broken)
        if active.size == 0:
            break
        start = t_max[active] * chunk / SCAN_CHUNKS
        t = start[:, None] + (t_max[active] / SCAN_CHUNKS)[:, None] * fractions
        rows = np.broadcast_to(active[:, None], t.shape)
        smallest = margins(rows.ravel(), t.ravel()).min(axis=-1).reshape(t.shape)
        if chunk == 0 and np.any(smallest[:, 0] < 0):
            raise HexalegError("the nominal stance itself violates a stance constraint")
        infeasible = smallest < 0
        hit = infeasible.any(axis=1)
        first = np.argmax(infeasible, axis=1)
        for k in np.flatnonzero(hit):
            d = active[k]
            lo[d], hi[d] = t[k, first[k] - 1], t[k, first[k]]
        broken[active[hit]] = True
    which = np.full(count, -1)
    index = np.flatnonzero(broken)
    if index.size:
        # Solve every constraint that broke inside its bracket on its own smooth margin,
        # then keep, per direction, the one that breaks first.
        at_hi = margins(index, hi[index])
        pair_row, pair_constraint = np.nonzero(at_hi < 0)
        directions = index[pair_row]

        def pair_margin(t: ArrayF) -> ArrayF:
            return margins(directions, t)[np.arange(len(t)), pair_constraint]

        root = _anderson_bjorck(pair_margin, lo[directions], hi[directions])
        for d in index:
            mine = np.flatnonzero(directions == d)
            first = mine[np.argmin(root[mine])]
            lo[d], which[d] = root[first], pair_constraint[first]
    return np.where(broken, lo, t_max), which


def _anderson_bjorck(g: Callable[[ArrayF], ArrayF], lo: ArrayF, hi: ArrayF) -> ArrayF:
    """Roots of g in brackets [lo, hi] with g(lo) ≥ 0 > g(hi), vectorized; returns the feasible end.

    Regula falsi with the Anderson–Björck correction: when the same end moves
    twice, the other end's value is scaled by m = 1 − g(new)/g(old) (½ if m ≤ 0),
    which keeps the bracket and converges superlinearly on smooth margins.
    """
    g_lo, g_hi = g(lo), g(hi)
    side = np.zeros(len(lo))  # which end moved last: +1 lo, −1 hi
    tolerance = BRACKET_TOLERANCE * np.maximum(hi, 1.0)
    for _ in range(REFINE_ITERATIONS):
        # done: a tight bracket, or a feasible end whose margin is at round-off level
        done = (hi - lo <= tolerance) | (g_lo <= MARGIN_ROUNDOFF)
        if np.all(done):
            break
        t = (lo * g_hi - hi * g_lo) / (g_hi - g_lo)
        t = np.where((t > lo) & (t < hi), t, 0.5 * (lo + hi))
        g_t = g(t)
        feasible = (g_t >= 0) & ~done
        replaced_hi = (g_t < 0) & ~done
        old = np.where(feasible, g_lo, g_hi)  # value at the end being replaced
        scale = 1.0 - g_t / np.where(old != 0, old, 1.0)
        scale = np.where(scale > 0, scale, 0.5)
        g_hi = np.where(feasible & (side > 0), scale * g_hi, g_hi)
        g_lo = np.where(replaced_hi & (side < 0), scale * g_lo, g_lo)
        lo, g_lo = np.where(feasible, t, lo), np.where(feasible, g_t, g_lo)
        hi, g_hi = np.where(replaced_hi, t, hi), np.where(replaced_hi, g_t, g_hi)
        side = np.where(feasible, 1.0, np.where(replaced_hi, -1.0, side))
    return lo


def axis_locked_extremes(geometry: StanceGeometry) -> tuple[Extreme, ...]:
    """The twelve axis-locked extremes of a stance geometry, with their causes."""
    axis_of = np.array([AXES.index(a) for a, _ in DIRECTIONS])
    sign_of = np.array([s for _, s in DIRECTIONS], dtype=float)

    def margins(direction: ArrayF, t: ArrayF) -> ArrayF:
        rotation, translation = direction_poses(
            geometry, axis_of[direction], sign_of[direction] * t
        )
        return stance_margins(geometry, rotation, translation)

    t_cross, which = first_crossings(margins, search_ranges(geometry))
    labels = constraint_labels(geometry.legs)
    return tuple(
        Extreme(axis, sign, float(sign * t), labels[k] if k >= 0 else Cause("range"))
        for (axis, sign), t, k in zip(DIRECTIONS, t_cross, which, strict=True)
    )


def axis_locked_flexibility(
    design: HexapodDesign,
    stance: str | Sequence[str] = "all",
    model: HexapodModel | None = None,
    geometry: StanceGeometry | None = None,
) -> FlexibilityResult:
    """Axis-locked flexibility of ``design`` (the ADAMS semantics).

    Args:
        design: The design.
        stance: ``"all"``, ``"tripod"`` or a list of stance legs.
        model: Its Pinocchio model, if already built.
        geometry: A template geometry of the same body and mounts (fast path for
            sweeps: the design's legs replace the template's by :meth:`StanceGeometry.with_design`).

    """
    if geometry is None:
        model = HexapodModel(design) if model is None else model
        geometry = StanceGeometry.from_model(model, stance)
    else:
        geometry = geometry.with_design(design)
    return FlexibilityResult(design, geometry.legs, "axis", axis_locked_extremes(geometry))


# -- free-coupled NLP --------------------------------------------------------------------


def free_flexibility(
    design: HexapodDesign,
    stance: str | Sequence[str] = "all",
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


def flexibility(
    design: HexapodDesign,
    mode: str = "axis",
    stance: str | Sequence[str] = "all",
    model: HexapodModel | None = None,
) -> FlexibilityResult:
    """Body flexibility of ``design``: ``mode`` is ``"axis"`` (axis-locked) or ``"free"``."""
    if mode == "axis":
        return axis_locked_flexibility(design, stance, model)
    if mode == "free":
        return free_flexibility(design, stance, model)
    raise HexalegError(f"mode = {mode!r} is not valid: use 'axis' or 'free'")
