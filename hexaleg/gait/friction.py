"""The standing feet's grip: each foot's tangential force within μ times its normal force.

A standing foot pushed by the ground with force f (ground frame: f_n = f_z along the
ground's normal, f_t = (f_x, f_y) along it) holds without sliding while
|f_t| ≤ μ·f_n (Coulomb's cone). On a slope the weight has a component along the ground,
so the feet must push along it: a walk whose planned forces leave the cone slides, and is
not feasible (:attr:`~hexaleg.gait.analysis.GaitAnalysis.feasible`). Each leg's worst
sample is named (:class:`Slip`).

The forces of a gait are affine in one parameter wherever the walk's limits are solved in
closed form: f = f₀ + t·Δf with t the payload (:mod:`hexaleg.gait.capacity`) or 1/T²
(:mod:`hexaleg.gait.limits`). Then g(t) = μ·f_n(t) − |f_t(t)| is concave in t, so the set
of t ≥ 0 that grips is an interval from 0, and its end is where μ²·f_n² = |f_t|² with
f_n ≥ 0: a root of a quadratic (:func:`cone_limit`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF
from hexaleg.cause import Cause

GRIP_TOLERANCE = 1e-9
"""How far a foot's force may lie outside the cone, as a share of its size, before it slides
(round-off of forces that touch the cone exactly) [-]."""


@dataclass(frozen=True)
class Slip:
    """A standing foot whose planned force leaves the friction cone: where it slides worst.

    Attributes:
        leg: The leg.
        time: When its ratio |f_t| / f_n is largest [s].
        ratio: That ratio [-] (infinite where the ground would have to pull).
        friction: The friction coefficient μ it exceeds [-].

    """

    leg: str
    time: float
    ratio: float
    friction: float

    @property
    def cause(self) -> Cause:
        """The foot sliding, as a cause."""
        return Cause("slide", self.leg)

    def __str__(self) -> str:
        ratio = "∞ (the ground would pull)" if math.isinf(self.ratio) else f"{self.ratio:.3g}"
        return (
            f"{self.leg} foot slides at t = {self.time:.3f} s: tangential / normal force "
            f"{ratio} > μ = {self.friction:g}"
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``leg``, ``time`` [s], ``ratio`` and ``friction`` [-] (``None``: ∞)."""
        ratio = None if math.isinf(self.ratio) else self.ratio
        return {"leg": self.leg, "time": self.time, "ratio": ratio, "friction": self.friction,
                "description": str(self)}  # fmt: skip


def friction_ratios(forces: ArrayF, stance: npt.NDArray[np.bool_]) -> ArrayF:
    """|f_t| / f_n of each standing foot (N, 6) [-]: 0 swinging, ∞ where f_n ≤ 0 standing.

    Args:
        forces: Each foot's force from the ground (N, 6, 3), ground frame [N].
        stance: Which feet stand (N, 6).

    """
    tangential = np.hypot(forces[..., 0], forces[..., 1])
    normal = forces[..., 2]
    pushing = normal > 0
    ratios = np.where(pushing, tangential / np.where(pushing, normal, 1.0), np.inf)
    out: ArrayF = np.where(stance, ratios, 0.0)
    return out


def slips(
    ratios: ArrayF, times: ArrayF, legs: tuple[str, ...], friction: float
) -> tuple[Slip, ...]:
    """Each leg whose foot's ratio (N, 6) exceeds μ anywhere, at its worst sample, leg order."""
    worst = ratios.argmax(axis=0)
    found = []
    for i, leg in enumerate(legs):
        ratio = float(ratios[worst[i], i])
        if ratio > friction * (1 + GRIP_TOLERANCE):
            found.append(Slip(leg, float(times[worst[i]]), ratio, friction))
    return tuple(found)


def cone_limit(
    base: ArrayF, slope: ArrayF, stance: npt.NDArray[np.bool_], friction: float
) -> tuple[float, int] | None:
    """The largest t ≥ 0 keeping every standing foot's f₀ + t·Δf in the cone, and which binds.

    Args:
        base: f₀ (N, 6, 3), ground frame [N].
        slope: Δf (N, 6, 3) [N per unit of t].
        stance: Which feet stand (N, 6).
        friction: μ [-].

    Returns:
        (t, flat index into (N, 6) of the foot that binds); a negative t with the index of
        the worst foot when one slides at t = 0 already; ``None`` when no t bounds them.

    """
    value, index = _cone_limit(base, slope, stance, friction, friction**2)
    return None if index < 0 else (value, index)


@compiled
def _cone_limit(
    base: ArrayF, slope: ArrayF, stance: npt.NDArray[np.bool_], friction: float, mu2: float
) -> tuple[float, int]:  # pragma: no cover - compiled; tested through cone_limit
    """:func:`cone_limit`'s work, foot by foot (index −1: no t bounds them).

    A foot sliding at t = 0 by more than :data:`GRIP_TOLERANCE` of its force's size
    breaks the walk: the worst one (the least μ·f_n − |f_t| over that size) is returned.
    Else μ²f_n² − |f_t|² = a·t² + b·t + c, and :func:`_first_end` ends each interval.
    """
    count, legs = stance.shape
    worst, worst_at, broken = math.inf, -1, False
    for k in range(count * legs):
        n, leg = divmod(k, legs)
        if stance[n, leg]:
            x0, y0, n0 = base[n, leg, 0], base[n, leg, 1], base[n, leg, 2]
            size = math.sqrt(x0 * x0 + y0 * y0 + n0 * n0) + GRIP_TOLERANCE
            start = friction * n0 - math.hypot(x0, y0)
            broken |= start < -GRIP_TOLERANCE * size
            share = start / size
            if worst_at < 0 or share < worst or (share != share and worst == worst):
                worst, worst_at = share, k  # the first least, or the first NaN (argmin's)
    if broken:
        n, leg = divmod(worst_at, legs)
        x0, y0, n0 = base[n, leg, 0], base[n, leg, 1], base[n, leg, 2]
        return friction * n0 - math.hypot(x0, y0), worst_at
    least, least_at = math.inf, -1
    for k in range(count * legs):
        n, leg = divmod(k, legs)
        if stance[n, leg]:
            x0, y0, n0 = base[n, leg, 0], base[n, leg, 1], base[n, leg, 2]
            dx, dy, dn = slope[n, leg, 0], slope[n, leg, 1], slope[n, leg, 2]
            a = mu2 * (dn * dn) - (dx * dx + dy * dy)
            b = 2 * (mu2 * n0 * dn - (x0 * dx + y0 * dy))
            c = mu2 * (n0 * n0) - (x0 * x0 + y0 * y0)
            end = _first_end(a, b, c, n0, dn)
            if end < least:
                least, least_at = end, k
    return least, least_at


@compiled
def _first_end(
    a: float, b: float, c: float, n0: float, dn: float
) -> float:  # pragma: no cover - compiled
    """The least t > 0 where μ²f_n² − |f_t|² = a·t² + b·t + c reaches 0 with f_n ≥ 0 (∞: none).

    The foot grips at t = 0 (c ≥ 0 up to round-off, f_n ≥ 0); g = μf_n − |f_t| is concave,
    so the first root on the f_n ≥ 0 branch ends the interval that grips. The roots are
    taken without cancellation: q = −(b + sign(b)·√(b² − 4ac))/2, t = q/a and c/q.
    """
    if c <= 0 and b < 0:
        return 0.0  # touching the cone at t = 0 and leaving it
    scale = _larger(_larger(abs(a), abs(b)), _larger(abs(c), 1e-300))
    flat = abs(a) <= 1e-12 * scale
    disc = b * b - 4 * a * c
    q = -0.5 * (b + math.copysign(math.sqrt(_larger(disc, 0.0)), b))
    real = not flat and disc >= 0
    if flat:
        first = -c / b if abs(b) > 1e-12 * scale else math.nan
    else:
        first = q / a if real else math.nan
    second = c / q if real and q != 0 else math.nan
    end = math.inf
    for root in (first, second):
        slack = -GRIP_TOLERANCE * (abs(n0) + abs(root * dn))
        if root > 0 and n0 + root * dn >= slack and root < end:
            end = root
    return end


@compiled
def _larger(x: float, y: float) -> float:  # pragma: no cover - compiled
    """NumPy's maximum of two numbers: NaN if either is."""
    return x if x >= y or x != x else y
