"""What a design costs: the statics at the nominal stance and at each body extreme.

:func:`analyze_loads` gathers, for one design, the foot forces and joint torques
holding the nominal stance, the torques and stability margin at each of the twelve
flexibility extremes (the pose each extreme reports), the steepest slope per heading
and the payload capacity.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg._typing import Distribution, FlexibilityMode, StanceSet
from hexaleg.design import HexapodDesign
from hexaleg.limits import LEG_JOINTS
from hexaleg.ratings import NEEDS_RATING
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.configurations import extreme_configurations
from hexaleg.stance.extremes import Extreme, FlexibilityResult
from hexaleg.stance.flexibility import flexibility
from hexaleg.stance.geometry import stance_legs
from hexaleg.statics.capacity import PayloadCapacity, payload_capacity
from hexaleg.statics.forces import DEFAULT_FRICTION, Payload, Statics, StaticState
from hexaleg.statics.ratings import OverRating, over_rating
from hexaleg.statics.slopes import SlopeLimit, slope_limits
from hexaleg.structure.check import StructureCheck
from hexaleg.structure.standing import check_standing, standing_cases


@dataclass(frozen=True)
class ExtremeLoads:
    """The statics at one flexibility extreme.

    Attributes:
        extreme: The extreme (its pose and joint angles).
        state: Forces, torques and stability margin there.

    """

    extreme: Extreme
    state: StaticState


@dataclass(frozen=True)
class LoadsAnalysis:
    """Everything the statics tell about one design.

    Attributes:
        design: The design.
        payload: The payload carried.
        friction: Friction coefficient μ [-].
        distribution: How the feet share the load.
        nominal: The statics at the nominal stance.
        extremes: The statics at each of the twelve extremes.
        slopes: The steepest slope per heading.
        capacity: The largest payload at the payload's point (torques within rating / F);
            ``None`` when the design gives no rated torques (it needs a rating).
        mode: Which flexibility extremes (axis-locked or free-coupled).
        structure: The legs' tubes checked at the nominal stance, the extremes and the
            slope (:mod:`hexaleg.structure`); ``None`` without a ``[structure]`` whose
            tubes are all given.
        safety_factor: F [-]: every torque is held within its rating / F.

    """

    design: HexapodDesign
    payload: Payload
    friction: float
    distribution: Distribution
    nominal: StaticState
    extremes: tuple[ExtremeLoads, ...]
    slopes: tuple[SlopeLimit, ...]
    capacity: PayloadCapacity | None
    mode: FlexibilityMode
    structure: StructureCheck | None = None
    safety_factor: float = 1.0

    @property
    def peak_torques(self) -> dict[str, float]:
        """Largest |τ| per joint type over the nominal stance and every extreme [N·m]."""
        states = [self.nominal, *(e.state for e in self.extremes)]
        peaks = np.abs(np.concatenate([s.joint_torques for s in states])).max(axis=0)
        return {joint: float(peak) for joint, peak in zip(LEG_JOINTS, peaks, strict=True)}

    @property
    def tips_over(self) -> bool:
        """Whether the robot tips over on level ground with its payload.

        The nominal stability margin is not positive: the centre of mass's footprint
        lies outside the support polygon (or on its edge), every max slope is 0, and the
        forces and torques hold the stance only with the feet fastened to the ground.
        """
        return self.nominal.stability_margin <= 0

    @property
    def worst_slope(self) -> SlopeLimit:
        """The heading with the smallest max slope."""
        return min(self.slopes, key=lambda s: s.max_slope)

    def study_columns(self) -> dict[str, float | str]:
        """The design's columns in a study table (N·m, m, rad) beside its metrics.

        The payload capacity and the stability margin are the study's metrics; what limits
        the capacity is a column here (:data:`~hexaleg.ratings.NEEDS_RATING` without rated
        torques).
        """
        nominal, overall = self.nominal.peak_torques(), self.peak_torques
        columns: dict[str, float | str] = {}
        for joint in LEG_JOINTS:
            columns[f"peak_{joint}_torque_nominal"] = nominal[joint]
            columns[f"peak_{joint}_torque"] = overall[joint]
        return columns | {
            "worst_max_slope": self.worst_slope.max_slope,
            "payload_limited_by": NEEDS_RATING
            if self.capacity is None
            else str(self.capacity.limited_by),
        }

    @property
    def over_rating(self) -> tuple[OverRating, ...]:
        """Each stance joint over its rating / F (|τ|) at the nominal stance or an extreme."""
        states = [self.nominal, *(e.state for e in self.extremes)]
        places = ["nominal", *(e.extreme.name for e in self.extremes)]
        return over_rating(
            self.nominal.legs,
            [s.joint_torques for s in states],
            self.design.rated_torques,
            places,
            "torque",
            self.safety_factor,
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (SI units: N, N·m, m, kg, rad)."""
        legs = self.nominal.legs
        return {
            "design": self.design.as_dict(),
            "payload": self.payload.to_dict(self.design),
            "friction": self.friction,
            "distribution": self.distribution,
            "safety_factor": self.safety_factor,
            "stance": list(legs),
            "mass": self.nominal.mass,
            "com": self.nominal.com.tolist(),
            "nominal": _state_dict(self.nominal),
            "extremes_mode": self.mode,
            "extremes": [
                {
                    "axis": e.extreme.axis,
                    "sign": e.extreme.sign,
                    "value": e.extreme.value,
                    "joint_torques": _torques(legs, e.state),
                    "peak_torque": e.state.peak_torques(),
                    "stability_margin": e.state.stability_margin,
                }
                for e in self.extremes
            ],
            "peak_torque": self.peak_torques,
            "slopes": [
                {
                    "heading": s.heading,
                    "max_slope": s.max_slope,
                    "limited_by": s.limited_by.to_dict(),
                }
                for s in self.slopes
            ],
            "payload_capacity": None
            if self.capacity is None
            else {
                "mass": self.capacity.mass,
                "limited_by": self.capacity.limited_by.to_dict(),
                "tips_over": self.tips_over,
            },
            "over_rating": [o.to_dict() for o in self.over_rating],
            "structure": None if self.structure is None else self.structure.to_dict(),
            "units": {
                "force": "N, ground frame",
                "torque": "N·m",
                "mass": "kg",
                "com, position, stability_margin": "m",
                "heading, max_slope, value of roll/pitch/yaw": "rad",
            },
        }


def _torques(legs: Sequence[str], state: StaticState) -> dict[str, dict[str, float]]:
    return {
        leg: dict(zip(LEG_JOINTS, (float(t) for t in torques), strict=True))
        for leg, torques in zip(legs, state.joint_torques, strict=True)
    }


def _state_dict(state: StaticState) -> dict[str, Any]:
    return {
        "foot_forces": {
            leg: [float(f) for f in force]
            for leg, force in zip(state.legs, state.foot_forces, strict=True)
        },
        "joint_torques": _torques(state.legs, state),
        "peak_torque": state.peak_torques(),
        "stability_margin": state.stability_margin,
    }


def analyze_loads(
    design: HexapodDesign,
    payload: Payload | None = None,
    friction: float = DEFAULT_FRICTION,
    stance: StanceSet | Sequence[str] = "all",
    distribution: Distribution = "min-norm",
    mode: FlexibilityMode = "axis",
    model: HexapodModel | None = None,
    slope: float = 0.0,
    safety_factor: float = 1.0,
) -> LoadsAnalysis:
    """The statics of ``design``: nominal stance, twelve extremes, slopes, payload capacity.

    Args:
        design: The design.
        payload: A point mass on the body (none by default).
        friction: Friction coefficient μ [-].
        stance: Stance legs.
        distribution: ``"min-norm"`` or ``"min-torque"``.
        mode: The extremes of axis-locked or free-coupled flexibility.
        model: The design's Pinocchio model, if already built.
        slope: The slope [rad] the legs' structure is also checked on, every heading.
        safety_factor: F ≥ 1 [-]: torques held within rating / F (flags and capacity).

    """
    model = HexapodModel(design) if model is None else model
    result = flexibility(design, mode, stance_legs(model, stance), model)
    return loads_at_extremes(model, result, payload, friction, distribution, slope, safety_factor)


def loads_at_extremes(
    model: HexapodModel,
    result: FlexibilityResult,
    payload: Payload | None = None,
    friction: float = DEFAULT_FRICTION,
    distribution: Distribution = "min-norm",
    slope: float = 0.0,
    safety_factor: float = 1.0,
) -> LoadsAnalysis:
    """The statics of a flexibility result's design, at its nominal stance and extremes.

    With a ``[structure]`` whose tubes are given, the legs' tubes are checked there too,
    and on ``slope`` [rad] in every heading. ``safety_factor`` F divides every rated torque
    (the flags and the payload capacity).
    """
    design, legs, mode = result.design, result.legs, result.mode
    statics = Statics(model, legs, payload, friction, safety_factor)
    q = model.nominal_configuration()
    nominal, *at_extremes = statics.states(
        [q, *extreme_configurations(model, result.extremes)], distribution
    )
    extremes = tuple(
        ExtremeLoads(e, state) for e, state in zip(result.extremes, at_extremes, strict=True)
    )
    return LoadsAnalysis(
        design=design,
        payload=statics.payload,
        friction=friction,
        distribution=distribution,
        nominal=nominal,
        extremes=extremes,
        slopes=slope_limits(statics.support, nominal.com, friction),
        capacity=None
        if design.rated_torques is None
        else payload_capacity(statics, q, distribution, at=nominal),
        mode=mode,
        structure=_structure(model, result, statics, distribution, slope),
        safety_factor=statics.safety_factor,
    )


def _structure(
    model: HexapodModel,
    result: FlexibilityResult,
    statics: Statics,
    distribution: Distribution,
    slope: float,
) -> StructureCheck | None:
    """The legs' tubes checked in the standing cases, if the design gives them all."""
    structure = model.design.structure
    if structure is None or any(tube is None for tube in structure.tubes):
        return None
    cases = standing_cases(
        model, result.legs, result.extremes, statics.payload, slope, statics.friction, distribution
    )
    return check_standing(model, cases)
