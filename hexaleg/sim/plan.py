"""The planned motion a simulation follows, and its reference at any time.

A :class:`Plan` is one period of a gait sampled at t_k = k·T/N: joint angles, speeds,
feed-forward torques and which feet stand; it repeats every period. Between samples
the joint angles follow the cubic Hermite curve through the samples' angles and
speeds, the speeds and torques a straight line; which feet stand is the last sample's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.exceptions import HexalegError, ParameterError


@dataclass(frozen=True)
class Plan:
    """One period of planned motion, N samples, L legs.

    Attributes:
        period: Period T [s].
        angles: Joint angles q (N, L, 3) [rad].
        rates: Joint speeds q̇ (N, L, 3) [rad/s].
        torques: Inverse-dynamics joint torques, the servos' feed-forward (N, L, 3) [N·m].
        standing: Whether each foot stands (N, L).
        velocity: Body velocity (vx, vy) in the world, whose axes are the body's at t = 0 [m/s].

    """

    period: float
    angles: ArrayF
    rates: ArrayF
    torques: ArrayF
    standing: npt.NDArray[np.bool_]
    velocity: ArrayF

    def __post_init__(self) -> None:
        shape = self.angles.shape
        if len(shape) != 3 or shape[2] != 3 or shape[0] < 2:
            raise HexalegError(f"plan angles have shape {shape}, expected (N ≥ 2, legs, 3)")
        if self.rates.shape != shape or self.torques.shape != shape:
            raise HexalegError("plan angles, rates and torques must have one shape")
        if self.standing.shape != shape[:2]:
            raise HexalegError(
                f"plan standing has shape {self.standing.shape}, expected {shape[:2]}"
            )
        if not (np.isfinite(self.period) and self.period > 0):
            raise ParameterError("period", self.period, "must be > 0 [s]")

    @property
    def samples(self) -> int:
        """Samples N per period."""
        return int(self.angles.shape[0])

    def reference(
        self, times: npt.ArrayLike
    ) -> tuple[ArrayF, ArrayF, ArrayF, npt.NDArray[np.bool_]]:
        """Angles, speeds, torques (K, L, 3) and standing feet (K, L) at ``times`` (K,) [s].

        The motion repeats every period; time 0 is the first sample.
        """
        t = np.asarray(times, dtype=float)
        step = self.period / self.samples
        position = np.mod(t, self.period) / step
        k = np.minimum(np.floor(position).astype(int), self.samples - 1)
        s = (position - k)[:, None, None]
        after = (k + 1) % self.samples
        q0, q1 = self.angles[k], self.angles[after]  # the period's end joins its start
        v0, v1 = self.rates[k], self.rates[after]
        h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
        h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
        angles = h00 * q0 + h10 * step * v0 + h01 * q1 + h11 * step * v1
        rates = (1 - s) * v0 + s * v1
        torques = (1 - s) * self.torques[k] + s * self.torques[after]
        return angles, rates, torques, self.standing[k]
