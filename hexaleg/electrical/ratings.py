"""Each joint against its actuator's ratings: which binds first, and which are exceeded.

Per leg and joint over one period (:mod:`hexaleg.electrical.equations`): its peak |τ|
against the peak torque / F, its RMS τ against the continuous torque, its largest voltage
needed against the bus voltage V and its peak |ω| against the speed rating / F (F ≥ 1 the
safety factor, 1 by default). Each gives a
ratio value/rating; above 1 the joint is over that rating (an
:class:`~hexaleg.statics.ratings.OverRating`), and the largest ratio names the rating
that binds first, e.g. ``"hip continuous torque"``: what a max-speed or max-stride
search holds at 1.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.actuators import Actuators
from hexaleg.electrical.equations import motor_samples, require_actuators, require_samples
from hexaleg.limits import LEG_JOINTS
from hexaleg.statics.ratings import DERATED, OverRating, Quantity, at_times, check_safety_factor

RATED: tuple[Quantity, ...] = ("peak_torque", "continuous_torque", "voltage", "speed")
"""The quantities held against the actuators' ratings, in the order of :class:`RatingLoads`."""


@dataclass(frozen=True)
class RatingBinding:
    """The rating nearest to (or furthest past) its limit.

    Attributes:
        quantity: ``"peak_torque"``, ``"continuous_torque"``, ``"voltage"`` or ``"speed"``.
        leg: The leg.
        joint: ``"root"``, ``"hip"`` or ``"knee"``.
        ratio: value / rating [-]: at most 1 within the ratings.
        value: The peak |τ| or RMS τ [N·m], the voltage needed [V] or the peak |ω| [rad/s].
        rating: What it is held against, in the same unit.

    """

    quantity: Quantity
    leg: str
    joint: str
    ratio: float
    value: float
    rating: float

    def __str__(self) -> str:
        return f"{self.joint} {self.quantity.replace('_', ' ')}"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form, with its name (``"hip continuous torque"``)."""
        return {
            "quantity": self.quantity,
            "leg": self.leg,
            "joint": self.joint,
            "ratio": self.ratio,
            "value": self.value,
            "rating": self.rating,
            "description": str(self),
        }


@dataclass(frozen=True)
class RatingLoads:
    """Each leg's joints against their actuators' ratings.

    Attributes:
        legs: Leg names (L,).
        values: Per :data:`RATED` quantity, leg and joint: peak |τ| [N·m], RMS τ [N·m],
            largest voltage needed [V], peak |ω| [rad/s] (4, L, 3).
        ratings: What they are held against, per quantity and joint type (4, 3): the
            peak torque and speed ratings divided by the safety factor.
        peak_samples: The sample each peak occurs at (4, L, 3); -1 for the RMS.
        safety_factor: F [-] the peak torque and speed ratings are divided by.

    """

    legs: tuple[str, ...]
    values: ArrayF
    ratings: ArrayF
    peak_samples: npt.NDArray[np.intp]
    safety_factor: float = 1.0

    @property
    def ratios(self) -> ArrayF:
        """Each value over its rating (4, L, 3) [-]: above 1, over the rating."""
        ratios: ArrayF = self.values / self.ratings[:, None, :]
        return ratios

    def binding(self) -> RatingBinding:
        """The largest ratio: the rating that binds first (ties: the first in RATED order)."""
        ratios = self.ratios
        kind, leg, joint = np.unravel_index(int(np.argmax(ratios)), ratios.shape)
        return RatingBinding(
            RATED[kind],
            self.legs[leg],
            LEG_JOINTS[joint],
            float(ratios[kind, leg, joint]),
            float(self.values[kind, leg, joint]),
            float(self.ratings[kind, joint]),
        )

    def over_rating(self, times: ArrayF) -> tuple[OverRating, ...]:
        """Every (quantity, leg, joint) over its rating, quantity then leg then joint order.

        Args:
            times: Each sample's time (N,) [s], which says where a peak occurs.

        """
        found = np.argwhere(self.values > self.ratings[:, None, :])
        samples = [int(self.peak_samples[kind, leg, joint]) for kind, leg, joint in found]
        places = at_times(times[[max(k, 0) for k in samples]])
        return tuple(
            OverRating(
                self.legs[leg],
                LEG_JOINTS[joint],
                RATED[kind],
                float(self.values[kind, leg, joint]),
                float(self.ratings[kind, joint]),
                place if sample >= 0 else "RMS over the period",
                self.safety_factor if RATED[kind] in DERATED else 1.0,
            )
            for (kind, leg, joint), sample, place in zip(found, samples, places, strict=True)
        )


def rating_loads(
    torques: ArrayF,
    speeds: ArrayF,
    actuators: Actuators,
    legs: Sequence[str],
    voltage: ArrayF,
    supply: float,
    safety_factor: float = 1.0,
) -> RatingLoads:
    """Peaks, RMS and voltages (4, L, 3) of one period's (N, L, 3) samples, with their ratings.

    ``voltage`` is what each sample needs [V], held against the bus voltage ``supply`` [V];
    the peak torque and speed ratings are divided by ``safety_factor`` F.
    """
    peaks = np.stack((np.abs(torques), voltage, np.abs(speeds)))  # (3, N, L, 3)
    at = peaks.argmax(axis=1)
    top = np.take_along_axis(peaks, at[:, None], axis=1)[:, 0]
    rms = np.sqrt(np.mean(torques**2, axis=0))
    factor = check_safety_factor(safety_factor)
    ratings = np.array(
        [
            np.array(actuators.rated_torques) / factor,
            actuators.continuous_torques,
            np.full(3, supply),
            np.array(actuators.rated_speeds) / factor,
        ]
    )
    values = np.stack((top[0], rms, top[1], top[2]))
    samples = np.stack((at[0], np.full_like(at[0], -1), at[1], at[2]))
    return RatingLoads(tuple(legs), values, ratings, samples, factor)


def binding_rating(
    torques: npt.ArrayLike,
    speeds: npt.ArrayLike,
    actuators: Actuators,
    legs: Sequence[str] | None = None,
    supply: float | None = None,
) -> RatingBinding:
    """Which rating binds first for one period's samples, and by what ratio.

    Args:
        torques: τ (N, L, 3) [N·m].
        speeds: ω (N, L, 3) [rad/s].
        actuators: The joint types' actuators.
        legs: Leg names (L,); :data:`~hexaleg.layouts.LEG_NAMES` for six legs if omitted.
        supply: The bus voltage [V]; the actuators' own (when they agree) if omitted.

    Returns:
        The largest value / rating, named like ``"hip continuous torque"``: at most 1
        when every joint is within its ratings.

    """
    return motor_loads(torques, speeds, actuators, legs, supply).binding()


def motor_loads(
    torques: npt.ArrayLike,
    speeds: npt.ArrayLike,
    actuators: Actuators,
    legs: Sequence[str] | None = None,
    supply: float | None = None,
    safety_factor: float = 1.0,
) -> RatingLoads:
    """One period's (N, L, 3) τ [N·m] and ω [rad/s] against every rating (see the module).

    ``supply`` is the bus voltage [V] (the actuators' own, when they agree, if omitted);
    ``safety_factor`` F divides the peak torque and speed ratings.
    """
    tau, omega, names = require_samples(torques, speeds, legs)
    actuators = require_actuators(actuators)
    voltage = motor_samples(tau, omega, actuators).voltage
    bus = actuators.supply_voltage() if supply is None else supply
    return rating_loads(tau, omega, actuators, names, voltage, bus, safety_factor)
