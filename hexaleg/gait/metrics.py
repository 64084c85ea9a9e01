"""What motors and batteries are chosen by: peaks, RMS, positive work and cost of transport.

Per joint type (root, hip, knee), over all six legs and the N samples of one period:
peak |τ| [N·m], RMS τ = √(mean τ²) [N·m], peak |q̇| [rad/s] and peak |τ·q̇| [W]. The
positive mechanical work per period W⁺ = Σ_k Σ_joints max(τ·q̇, 0)·T/N [J] counts what
the motors put in and nothing they could take back (no regeneration); the mechanical
cost of transport CoT = W⁺ / (M·g·v·T) [-] divides it by the weight carried over the
period's distance, M the total mass with the payload.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.limits import LEG_JOINTS


def per_joint(values: ArrayF) -> dict[str, float]:
    """(root, hip, knee) of the last axis, as a dict."""
    return {joint: float(v) for joint, v in zip(LEG_JOINTS, values, strict=True)}


@dataclass(frozen=True)
class GaitMetrics:
    """The motor and energy metrics of one gait period (the ZMP's is the analysis's).

    Attributes:
        peak_torque: Largest |τ| per joint type [N·m].
        rms_torque: RMS τ over the period per joint type, its worst leg's [N·m] (what heats
            a motor).
        peak_speed: Largest |q̇| per joint type [rad/s].
        peak_power: Largest |τ·q̇| per joint type [W].
        positive_work: W⁺ per period [J].
        cost_of_transport: W⁺ / (M·g·v·T) [-].

    """

    peak_torque: dict[str, float]
    rms_torque: dict[str, float]
    peak_speed: dict[str, float]
    peak_power: dict[str, float]
    positive_work: float
    cost_of_transport: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (N·m, rad/s, W, J, m)."""
        return {
            "peak_torque": self.peak_torque,
            "rms_torque": self.rms_torque,
            "peak_speed": self.peak_speed,
            "peak_power": self.peak_power,
            "positive_work": self.positive_work,
            "mechanical_cost_of_transport": self.cost_of_transport,
        }


def positive_work(torques: ArrayF, speeds: ArrayF, period: float) -> float:
    """W⁺ = Σ_k Σ_joints max(τ·q̇, 0)·T/N [J] of one period's (N, 6, 3) samples."""
    return float(np.maximum(torques * speeds, 0.0).sum() * period / len(torques))


def gait_metrics(
    torques: ArrayF,
    speeds: ArrayF,
    period: float,
    weight_travel: float,
) -> GaitMetrics:
    """The metrics of a period's samples.

    Args:
        torques: τ (N, 6, 3) [N·m].
        speeds: q̇ (N, 6, 3) [rad/s].
        period: T [s].
        weight_travel: M·g·v·T: the weight carried times the distance walked [J].

    """
    power = torques * speeds
    work = positive_work(torques, speeds, period)
    return GaitMetrics(
        peak_torque=per_joint(_peak(torques)),
        rms_torque=per_joint(np.sqrt((torques**2).mean(axis=0)).max(axis=0)),
        peak_speed=per_joint(_peak(speeds)),
        peak_power=per_joint(_peak(power)),
        positive_work=work,
        cost_of_transport=work / weight_travel,
    )


def _peak(values: ArrayF) -> ArrayF:
    """The largest |value| per joint type (3,) of (N, 6, 3) samples.

    Over the samples, then the legs: NumPy reduces two leading axes at once many times
    slower over a last axis of three.
    """
    peak: ArrayF = np.abs(values).max(axis=0).max(axis=0)
    return peak
