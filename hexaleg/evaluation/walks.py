"""The walking metrics of one design: the gait walked on every ground asked, the worst kept.

A robot that must walk a slope walks it uphill, downhill and across
(:func:`walking_grounds`); one that walks level ground walks it once. :class:`Walks` walks the
gait on each ground (:class:`~hexaleg.gait.walk.Walker`, its ground and the motors' safety
factor F), each analysis at most once per ground — the largest payload carried
(:func:`~hexaleg.gait.capacity.walker_capacity`), one period with the fastest walk of its
stride (:func:`~hexaleg.gait.analysis.analyze_walker`) — and each walking metric is the
worst over the grounds (the least of a metric better larger, the most of one better
smaller), with what limits it on that ground, or why it has no value on some ground.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property

from hexaleg.evaluation.metrics import METRICS, Analysis, Causes, Metrics, MetricSpec, Reasons
from hexaleg.gait.analysis import GaitAnalysis, analyze_walker
from hexaleg.gait.capacity import walker_capacity
from hexaleg.gait.spec import Gait
from hexaleg.gait.walk import Walker
from hexaleg.ratings import NEEDS_RATING
from hexaleg.robot.model import HexapodModel
from hexaleg.statics.forces import Payload
from hexaleg.statics.ground import LEVEL, Ground

__all__ = ["Measured", "Walks", "walking_grounds"]


def walking_grounds(slope: float, gait: Gait, friction: float | None = None) -> tuple[Ground, ...]:
    """The grounds a robot that must walk ``slope`` [rad] walks ``gait`` on.

    Level ground once (``slope`` 0); else uphill (the ground rising along the gait's heading
    ψ), downhill, and across (rising along ψ + π/2). ``friction``: the ground's μ (the
    default if ``None``).
    """
    kept = {} if friction is None else {"friction": friction}
    if slope == 0:
        return (replace(LEVEL, **kept),)
    across = math.remainder(gait.heading + math.pi / 2, 2 * math.pi)
    return (
        Ground(slope, None, **kept),
        Ground(-slope, None, **kept),
        Ground(slope, across, **kept),
    )


@dataclass(frozen=True)
class Measured:
    """What an analysis found: metric values, what limits them, why some have none."""

    metrics: Metrics = field(default_factory=Metrics)
    causes: Causes = field(default_factory=Causes)
    unmeasured: Reasons = field(default_factory=Reasons)


class Walks:
    """One design walking one gait with one payload on each ground, each analysis once.

    Args:
        model: The design's model (its tubes' masses in it).
        gait: The gait walked.
        payload: The payload carried (the capacity walks the gait unloaded).
        grounds: The grounds walked (at least one).
        safety_factor: The motors' F ≥ 1: peak torques and speeds within rating / F.

    """

    def __init__(
        self,
        model: HexapodModel,
        gait: Gait,
        payload: Payload,
        grounds: Sequence[Ground],
        safety_factor: float,
    ) -> None:
        self.model, self.gait, self.payload = model, gait, payload
        self.grounds, self.safety_factor = tuple(grounds), safety_factor

    @cached_property
    def walkers(self) -> tuple[Walker, ...]:
        """The gait walked with the payload, on each ground."""
        return tuple(
            Walker(self.model, self.gait, self.payload, ground=ground,
                   safety_factor=self.safety_factor)
            for ground in self.grounds
        )  # fmt: skip

    @cached_property
    def periods(self) -> tuple[GaitAnalysis, ...]:
        """One period of the gait on each ground, with the fastest walk of its stride."""
        return tuple(analyze_walker(walker, limits=False, speed=True) for walker in self.walkers)

    @cached_property
    def walks(self) -> bool | None:
        """Whether the design walks the gait unloaded within its ratings on every ground."""
        return self._capacities[1]

    def measure(self, analysis: Analysis) -> Measured:
        """The metrics ``analysis`` measures, each the worst over the grounds."""
        per_ground: Callable[[int], Measured] = getattr(self, f"_{analysis}")
        return worst([per_ground(k) for k in range(len(self.grounds))])

    # -- one ground ----------------------------------------------------------------------

    @cached_property
    def _capacities(self) -> tuple[tuple[Measured, ...], bool | None]:
        """The walking payload capacity on each ground, and whether it walks on them all."""
        if not self.model.design.rated:  # the capacity within ratings the design does not give
            unrated = without((METRICS.walking_payload_capacity,), NEEDS_RATING)
            return (unrated,) * len(self.grounds), None
        found = []
        for walker in self.walkers:
            empty = self.payload.with_mass(0.0)  # the capacity walks the gait unloaded
            unloaded = walker if walker.payload == empty else walker.carrying(empty)
            capacity = walker_capacity(unloaded)
            found.append((capacity, Measured(
                Metrics(walking_payload_capacity=capacity.mass),
                Causes(walking_payload_capacity=capacity.limited_by),
            )))  # fmt: skip
        return tuple(m for _, m in found), all(capacity.walks for capacity, _ in found)

    def _walking(self, k: int) -> Measured:
        return self._capacities[0][k]

    def _speed(self, k: int) -> Measured:
        limit = self.periods[k].max_speed
        if limit is None:  # speed=True: the design gives no ratings, the max speed needs one
            return without((METRICS.max_speed,), NEEDS_RATING)
        return Measured(Metrics(max_speed=limit.value), Causes(max_speed=limit.limited_by))

    def _period(self, k: int) -> Measured:
        walked = self.periods[k]
        if not walked.walkable:
            return without(of("period"), f"cannot walk the gait: {walked.violations[0]}")
        metrics = walked.metrics
        distance = walked.gait.speed * walked.gait.period  # per period [m]
        torques = {  # each joint type's peak and RMS torque, as declared
            spec.name: (metrics.peak_torque if spec.torque == "peak" else metrics.rms_torque)[
                spec.joint
            ]
            for spec in METRICS
            if spec.torque is not None and spec.joint is not None
        }
        return Measured(Metrics(
            gait_peak_torque=max(metrics.peak_torque.values()),
            mechanical_cost_of_transport=metrics.cost_of_transport,
            mechanical_energy_per_km=metrics.positive_work / distance * 1000 / 3600,
            min_zmp_margin=walked.min_zmp_margin,
            **torques,
        ))  # fmt: skip

    def _motors(self, k: int) -> Measured:
        walked = self.periods[k]
        if not walked.walkable:
            return without(of("motors"), f"cannot walk the gait: {walked.violations[0]}")
        electrical, found = walked.electrical, Measured()
        if electrical is not None:
            ratios = electrical.ratings.ratios[1]  # RMS over continuous torque (L, 3)
            battery = electrical.battery  # its range: capacity·(1 − reserve) walked
            found = Measured(Metrics(
                energy_per_km=electrical.energy_per_km,
                electrical_cost_of_transport=electrical.cost_of_transport,
                continuous_load=float(ratios.max()),
                battery_range=math.nan if battery is None else battery.range,
            ))  # fmt: skip
        for spec in of("motors"):  # without a table it is measured through: no value
            lacking = spec.lacks(walked.design)
            if lacking:
                found = without((spec,), f"the design has no [{lacking[0]}]", found)
        return found


def worst(found: Sequence[Measured]) -> Measured:
    """Each metric's worst over ``found`` (one per ground), with its cause or reason.

    A metric without a value on some ground has none (NaN) and that ground's reason.
    """
    metrics, causes, reasons = {}, {}, {}
    for spec, _ in found[0].metrics.given():
        values = [measured.metrics.value(spec) for measured in found]
        missing = [k for k, value in enumerate(values) if math.isnan(value)]
        if missing:
            metrics[spec.name], reasons[spec.name] = math.nan, found[missing[0]].unmeasured[spec]
            continue
        pick = min if spec.better == "maximize" else max
        k = pick(range(len(values)), key=values.__getitem__)
        metrics[spec.name], causes[spec.name] = values[k], found[k].causes[spec]
    return Measured(Metrics(**metrics), Causes(**causes), Reasons(**reasons))


def without(specs: Sequence[MetricSpec], why: str, found: Measured | None = None) -> Measured:
    """``found`` (if any) with ``specs`` without a value (NaN), and ``why`` they have none."""
    found = found or Measured()
    names = [spec.name for spec in specs]
    return Measured(
        replace(found.metrics, **dict.fromkeys(names, math.nan)),
        found.causes,
        replace(found.unmeasured, **dict.fromkeys(names, why)),
    )


def of(analysis: Analysis) -> list[MetricSpec]:
    """The metrics ``analysis`` measures."""
    return [spec for spec in METRICS if spec.analysis == analysis]
