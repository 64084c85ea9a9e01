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
    (x0, y0, n0), (dx, dy, dn) = base[stance].T, slope[stance].T  # each (K,): x, y, normal
    size = np.sqrt(x0 * x0 + y0 * y0 + n0 * n0) + GRIP_TOLERANCE  # |f₀|
    start = friction * n0 - np.hypot(x0, y0)
    where = np.flatnonzero(stance.ravel())
    if (start < -GRIP_TOLERANCE * size).any():
        worst = int(np.argmin(start / size))
        return float(start[worst]), int(where[worst])
    mu2 = friction**2
    a = mu2 * dn**2 - (dx * dx + dy * dy)
    b = 2 * (mu2 * n0 * dn - (x0 * dx + y0 * dy))
    c = mu2 * n0**2 - (x0 * x0 + y0 * y0)
    ends = _first_ends(a, b, c, n0, dn)
    if not np.isfinite(ends).any():
        return None
    index = int(np.argmin(ends))
    return float(ends[index]), int(where[index])


def _first_ends(a: ArrayF, b: ArrayF, c: ArrayF, n0: ArrayF, dn: ArrayF) -> ArrayF:
    """Each least t > 0 where μ²f_n² − |f_t|² = a·t² + b·t + c reaches 0 with f_n ≥ 0 (∞: none).

    Each foot grips at t = 0 (c ≥ 0 up to round-off, f_n ≥ 0); g = μf_n − |f_t| is concave,
    so the first root on the f_n ≥ 0 branch ends the interval that grips. The roots are
    taken without cancellation: q = −(b + sign(b)·√(b² − 4ac))/2, t = q/a and c/q.
    """
    scale = np.maximum(np.maximum(np.abs(a), np.abs(b)), np.maximum(np.abs(c), 1e-300))
    flat = np.abs(a) <= 1e-12 * scale
    with np.errstate(divide="ignore", invalid="ignore"):
        linear = np.where(np.abs(b) > 1e-12 * scale, -c / b, np.nan)
        disc = b * b - 4 * a * c
        q = -0.5 * (b + np.copysign(np.sqrt(np.maximum(disc, 0.0)), b))
        real = ~flat & (disc >= 0)
        roots = np.stack(
            (np.where(flat, linear, np.where(real, q / a, np.nan)),
             np.where(real & (q != 0), c / q, np.nan))
        )  # fmt: skip
    slack = -GRIP_TOLERANCE * (np.abs(n0) + np.abs(roots * dn))
    valid = (roots > 0) & (n0 + roots * dn >= slack)
    ends = np.where(valid, roots, np.inf).min(axis=0)
    ends[(c <= 0) & (b < 0)] = 0.0  # touching the cone at t = 0 and leaving it
    out: ArrayF = ends
    return out
