"""A body field swept over evenly spaced values: what a sensitivity table may vary.

``--sweep body_width=0.4:0.8:9`` (``study`` and ``report``) is parsed here, before any
study runs; :mod:`hexaleg.study.sensitivity` runs the study of each variant, and a
decision may free the same fields (:mod:`hexaleg.study.search_space`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg._checks import require_in_range
from hexaleg.design import FIELD_RANGES
from hexaleg.exceptions import DesignError

Variant = tuple[str, dict[str, Any]]
"""A name and the design fields it changes."""

SWEEPABLE: tuple[str, ...] = (
    "body_length",
    "body_width",
    "body_height",
    "body_radius",
    "first_leg_angle",
    "middle_leg_offset",
    "front_yaw",
    "rear_yaw",
)
"""Body and layout fields a sensitivity sweep can vary (the segments are the ratios)."""

MAX_SWEEP_POINTS = 50
"""Most values of a swept field."""


@dataclass(frozen=True)
class FieldSweep:
    """One design field at evenly spaced values: ``FIELD=START:STOP:COUNT``.

    Attributes:
        field: The design field (one of :data:`SWEEPABLE`).
        start: First value [m or rad].
        stop: Last value [m or rad].
        count: Number of values, 2..:data:`MAX_SWEEP_POINTS`.

    """

    field: str
    start: float
    stop: float
    count: int

    def __post_init__(self) -> None:
        if self.field not in SWEEPABLE:
            raise DesignError("--sweep", self.field, "a field among " + ", ".join(SWEEPABLE))
        lower, upper, unit = FIELD_RANGES[self.field]
        for name in ("start", "stop"):
            require_in_range(
                f"--sweep {self.field} {name}", getattr(self, name), lower, upper, unit
            )
        if not 2 <= self.count <= MAX_SWEEP_POINTS:
            raise DesignError(
                f"--sweep {self.field} count", self.count, f"from 2 to {MAX_SWEEP_POINTS} values"
            )

    @classmethod
    def parse(cls, text: str) -> FieldSweep:
        """``FIELD=START:STOP:COUNT``, e.g. ``body_width=0.4:0.8:9``."""
        match = re.fullmatch(r"\s*([a-z_]+)\s*=\s*([^:]+):([^:]+):([^:]+)\s*", text)
        if match is None:
            raise DesignError("--sweep", text, "FIELD=START:STOP:COUNT, e.g. body_width=0.4:0.8:9")
        try:
            start, stop = float(match[2]), float(match[3])
            count = int(match[4])
        except ValueError:
            raise DesignError(
                "--sweep", text, "START and STOP numbers, COUNT an integer (body_width=0.4:0.8:9)"
            ) from None
        return cls(match[1], start, stop, count)

    @property
    def values(self) -> tuple[float, ...]:
        """The swept values [m or rad]."""
        return tuple(float(v) for v in np.linspace(self.start, self.stop, self.count))

    def variants(self) -> tuple[Variant, ...]:
        """One variant per value, named ``field = value unit``."""
        unit = FIELD_RANGES[self.field][2]
        return tuple((f"{self.field} = {v:.4g} {unit}", {self.field: v}) for v in self.values)
