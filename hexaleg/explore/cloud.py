"""The study's cloud of designs that the page places the current design on.

The loaded robot at its leg length, at the paper's coxa ratios and its own, over a grid
of tibia ratios (:meth:`~hexaleg.robot.robot.Robot.at_ratios`), each measured for FB and
the walking payload capacity under the loaded conditions (a batch per coxa ratio,
:func:`~hexaleg.evaluation.evaluate.evaluate_many`).
It is measured once, in a background thread, while the page already answers.
"""

from __future__ import annotations

import math
import threading
from typing import Any

from hexaleg.design import HexapodDesign, l3_ratio_grid
from hexaleg.evaluation.evaluate import Conditions, evaluate_many
from hexaleg.evaluation.metrics import METRICS, MetricSpec
from hexaleg.exceptions import HexalegError
from hexaleg.paper import L1_RATIOS
from hexaleg.robot.robot import Robot
from hexaleg.stance.geometry import StanceGeometry

__all__ = ["CLOUD_METRICS", "Cloud"]

CLOUD_METRICS: tuple[MetricSpec, ...] = (METRICS.fb, METRICS.walking_payload_capacity)
"""What each design of the cloud is measured for."""

TIBIA_POINTS = 12
"""Tibia ratios per coxa ratio."""


class Cloud:
    """The cloud, measured in a background thread; :meth:`to_dict` answers what is there."""

    def __init__(self, robot: Robot, conditions: Conditions) -> None:
        """``robot``: the loaded robot, whose designs at other ratios the cloud is."""
        self._robot, self._conditions = robot, conditions
        self._points: list[dict[str, float | None]] = []
        self._error = ""
        self._done = threading.Event()
        self._thread = threading.Thread(target=self._measure, daemon=True, name="cloud")

    def start(self) -> Cloud:
        """Start measuring; return the cloud."""
        self._thread.start()
        return self

    def wait(self, timeout: float) -> bool:
        """Wait at most ``timeout`` [s] for the cloud; whether it is complete."""
        return self._done.wait(timeout)

    def to_dict(self) -> dict[str, Any]:
        """``ready``, ``points`` (l1_ratio, l3_ratio and the metrics of each) and ``error``."""
        return {"ready": self._done.is_set(), "points": list(self._points), "error": self._error}

    def _measure(self) -> None:
        try:
            for l1_ratio in coxa_ratios(self._robot.design):
                self._points += self._row(l1_ratio)
        except HexalegError as err:  # the loaded body cannot stand at these ratios
            self._error = str(err)
        finally:
            self._done.set()

    def _row(self, l1_ratio: float) -> list[dict[str, float | None]]:
        """One coxa ratio's designs, measured together."""
        robots = []
        for l3_ratio in l3_ratio_grid(TIBIA_POINTS):
            try:
                robots.append(self._robot.at_ratios(l1_ratio, float(l3_ratio)))
            except HexalegError:
                continue  # this leg cannot stand on the loaded body
        if not robots:
            return []
        template = StanceGeometry.template_of(robots[0].model, self._conditions.stance)
        designs = [robot.design for robot in robots]
        models = [robot.model for robot in robots]
        found = evaluate_many(designs, CLOUD_METRICS, self._conditions, models, template)
        points = []
        for design, evaluation in zip(designs, found, strict=True):
            if evaluation.error:
                continue
            point: dict[str, float | None] = {
                "l1_ratio": l1_ratio,
                "l3_ratio": design.l3 / design.leg_length,
            }
            for spec in CLOUD_METRICS:
                value = evaluation.metrics.value(spec)
                point[spec.name] = value if math.isfinite(value) else None
            points.append(point)
        return points


def coxa_ratios(design: HexapodDesign) -> list[float]:
    """The paper's coxa ratios and the design's own, in increasing order."""
    own = round(design.l1 / design.leg_length, 6)
    return sorted({*L1_RATIOS, own})
