"""What a simulated walk found, as one frozen record and its JSON."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from hexaleg._typing import ArrayF
from hexaleg.design import HexapodDesign
from hexaleg.gait.spec import Gait
from hexaleg.robot.model import HexapodModel
from hexaleg.sim.measure import WalkMetrics
from hexaleg.sim.model import ServoGains, SimModel
from hexaleg.sim.standing_tripod import StandingCheck
from hexaleg.statics.forces import Payload


@dataclass(frozen=True)
class SimulationResult:
    """One design walking one gait in MuJoCo, and standing on a tripod.

    Attributes:
        design: The design.
        gait: The gait walked.
        payload: The payload carried.
        friction: Coefficient of friction μ between feet and floor [-].
        cycles: Gait periods simulated (the first one is not measured).
        gains: The joint servos' gains.
        metrics: The walk's measures over the cycles after the first (``None``: it
            diverged, and measures nothing).
        planned_peak_torque: The gait's planned peak |τ| per joint type [N·m].
        standing: The tripod standing check (``None``: the walk or the stand diverged).
        frames: The robot's Pinocchio configuration (F, nq) at ``frame_rate``, whole run.
        frame_torques: The servos' torques (F, legs, 3) at those frames [N·m].
        frame_rate: Frames per second [1/s].
        model: The Pinocchio model it walked (``None``: the design's own, which
            :meth:`sim_model` builds again from the design).
        controller: How the joints followed the plan: ``"servo"`` or ``"torque"``.
        diverged: Where and why the simulation diverged and stopped (``while walking, at
            t = 0.038 s: …``): nothing it measured holds then; empty if it did not.

    """

    design: HexapodDesign
    gait: Gait
    payload: Payload
    friction: float
    cycles: int
    gains: ServoGains
    metrics: WalkMetrics | None
    planned_peak_torque: dict[str, float]
    standing: StandingCheck | None
    frames: ArrayF
    frame_torques: ArrayF
    frame_rate: float
    model: HexapodModel | None = None
    controller: str = "servo"
    diverged: str = ""

    @property
    def mid_stride_frame(self) -> int:
        """The frame half a period into the last cycle: one tripod up, mid-swing."""
        time = (self.cycles - 0.75) * self.gait.period
        return min(len(self.frames) - 1, round(time * self.frame_rate))

    def sim_model(self) -> SimModel:
        """The MuJoCo model the walk ran on, built again (for a video or a still)."""
        model = HexapodModel(self.design) if self.model is None else self.model
        return SimModel(model, self.payload, self.friction, self.gains)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: what ``hexaleg simulate --json`` prints (SI units: m, rad, N, N·m).

        A run that diverged has ``diverged`` (where, why) and ``null`` measures.
        """
        metrics, standing = self.metrics, self.standing
        measured: dict[str, Any] = dict.fromkeys(WALK_FIELDS)
        if metrics is not None:
            measured = {
                "planned_distance": metrics.planned_distance,
                "distance": metrics.distance,
                "max_tilt": metrics.max_tilt,
                "min_height": metrics.min_height,
                "fell": metrics.fell,
                "tracking_rms": metrics.tracking_rms,
                "slip": metrics.slip,
                "internal_force": metrics.internal_force,
                "peak_torque_measured": dict(metrics.peak_torque),
                "over_rating": [o.to_dict() for o in metrics.over_rating],
            }
        return {
            "design": self.design.as_dict(),
            "gait": self.gait.to_dict(),
            "payload": self.payload.to_dict(self.design),
            "cycles": self.cycles,
            "controller": self.controller,
            "diverged": self.diverged or None,
            **{key: value for key, value in measured.items() if key != "over_rating"},
            "peak_torque_planned": dict(self.planned_peak_torque),
            "over_rating": measured["over_rating"],
            "standing": None if standing is None else standing.to_dict(),
        }


WALK_FIELDS = (
    "planned_distance", "distance", "max_tilt", "min_height", "fell", "tracking_rms", "slip",
    "internal_force", "peak_torque_measured", "over_rating",
)  # fmt: skip
"""The JSON's measures of the walk (``null`` each when it diverged)."""
