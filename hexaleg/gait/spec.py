"""What a gait is: the pattern, period, stride, step height, heading and sampling of one period.

The body moves at constant velocity v = S / (β·T) along the heading ψ (body frame),
level, at its nominal height, never rotating; S is how far a foot moves relative to the
body while it stands, β the pattern's duty factor (:mod:`hexaleg.gait.pattern`).

Defaults, chosen for the default robot (the paper's leg on hexaleg's default body and
actuators, :class:`~hexaleg.design.HexapodDesign`): a tripod, period T = 2 s, stride
S = 0.3 m, step height H = 0.1 m, straight ahead, 200 samples. The stride stays well short
of that robot's max stride (:func:`~hexaleg.gait.limits.max_stride`, where a front foot runs
out of reach), so every leg keeps inside its stance limits with room to spare; the period
makes v = S / (β·T) = 0.3 m/s, a construction robot's walking pace, within the rated joint
speeds. The hips set the limit: a tripod's lone middle leg holds nearly half the robot's
weight, so the hips' ratings bound the speed and the payload
(:func:`~hexaleg.gait.limits.max_speed`; a tetrapod shares the weight among more legs). A
step height of 0.1 m clears rubble of a brick's height. 200 samples resolve the swing's
fastest change (a tripod's swing lasts half of them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

from hexaleg._checks import require_in_range
from hexaleg._typing import GaitPattern, require_choice
from hexaleg.exceptions import DesignError, ParameterError
from hexaleg.field_spec import FieldSpec
from hexaleg.gait.pattern import duty_factor
from hexaleg.table_records import require_table, unknown_key

PERIOD_RANGE = (0.05, 1000.0)
"""Allowed gait period T [s]."""
STRIDE_RANGE = (1e-4, 100.0)
"""Allowed stride S [m]."""
STEP_HEIGHT_RANGE = (0.0, 100.0)
"""Allowed step height H [m]."""
SPEED_RANGE = (1e-4, 100.0)
"""Allowed body speed v [m/s] (``--speed``)."""
SAMPLES_RANGE = (12, 100_000)
"""Allowed samples N per period."""

TABLE = "gait"
"""The design file's table of the gait every walking command uses by default."""

TABLE_KEYS: tuple[FieldSpec, ...] = (
    FieldSpec("gait pattern: tripod, tetrapod or wave", kind="choice", name="pattern"),
    FieldSpec("period T", "s", PERIOD_RANGE, name="period"),
    FieldSpec("stride S", "m", STRIDE_RANGE, name="stride"),
    FieldSpec("step height H", "m", STEP_HEIGHT_RANGE, name="step_height"),
    FieldSpec("heading ψ", "rad", (-math.pi, math.pi), name="heading"),
    FieldSpec("body speed v (sets the period)", "m/s", SPEED_RANGE, name="speed"),
    FieldSpec("samples N per period", "-", SAMPLES_RANGE, name="samples"),
)
"""The ``[gait]`` table's keys (the ``gait`` command's options, ``--step-height`` as
``step_height``) and what each allows, in the words every table's unknown key uses."""


@dataclass(frozen=True)
class Gait:
    """One gait period, as walked by every design it is applied to.

    Attributes:
        pattern: ``"tripod"``, ``"tetrapod"`` or ``"wave"`` (:mod:`hexaleg.gait.pattern`).
        period: Period T [s].
        stride: Stride S [m]: how far a standing foot moves relative to the body.
        step_height: Step height H [m]: the swing foot's highest point above the ground.
        heading: Direction of travel ψ in the body frame [rad] (0: straight ahead, x).
        samples: Samples N per period, at t_k = k·T/N, k = 0 … N−1.

    """

    pattern: GaitPattern = "tripod"
    period: float = 2.0
    stride: float = 0.3
    step_height: float = 0.1
    heading: float = 0.0
    samples: int = 200

    def __post_init__(self) -> None:
        require_choice("pattern", self.pattern, GaitPattern)
        for name, (lower, upper, unit) in {
            "period": (*PERIOD_RANGE, "s"),
            "stride": (*STRIDE_RANGE, "m"),
            "step_height": (*STEP_HEIGHT_RANGE, "m"),
            "heading": (-math.pi, math.pi, "rad"),
        }.items():
            object.__setattr__(
                self, name, require_in_range(name, getattr(self, name), lower, upper, unit)
            )
        samples = self.samples
        if isinstance(samples, bool) or not isinstance(samples, int):
            raise DesignError("samples", samples, "must be an integer")
        if not SAMPLES_RANGE[0] <= samples <= SAMPLES_RANGE[1]:
            raise DesignError(
                "samples", samples, f"must lie in [{SAMPLES_RANGE[0]}, {SAMPLES_RANGE[1]}]"
            )

    @property
    def duty_factor(self) -> float:
        """β: the fraction of the period each foot stands [-]."""
        return duty_factor(self.pattern)

    @property
    def speed(self) -> float:
        """Body speed v = S / (β·T) [m/s]."""
        return self.stride / (self.duty_factor * self.period)

    @property
    def named(self) -> str:
        """How prose, captions and legends name it: "the default gait", or "the design's gait".

        A gait other than the default comes from a design file's ``[gait]`` table (or the
        command line); a text that needs its pattern and speed says them beside the name.
        """
        return "the default gait" if self == Gait() else "the design's gait"

    def with_speed(self, speed: float) -> Gait:
        """The same stride at body speed ``speed`` [m/s]: period T = S / (β·v)."""
        speed = require_in_range("speed", speed, *SPEED_RANGE, "m/s")
        period = self.stride / (self.duty_factor * speed)
        if not PERIOD_RANGE[0] <= period <= PERIOD_RANGE[1]:
            low = self.stride / (self.duty_factor * PERIOD_RANGE[1])
            high = self.stride / (self.duty_factor * PERIOD_RANGE[0])
            raise DesignError(
                "speed",
                speed,
                f"must lie in [{low:.4g}, {high:.4g}] [m/s] at stride {self.stride:g} m",
            )
        return replace(self, period=period)

    @classmethod
    def from_table(cls, table: Any, base: Gait | None = None) -> Gait:
        """The gait a design file's ``[gait]`` table describes: its keys over ``base``.

        ``base``: the gait walked without a table (:class:`Gait`'s defaults if omitted; a
        robot's own, :func:`~hexaleg.gait.defaults.default_gait`).

        ``speed`` sets the period from the stride (:meth:`with_speed`), so the table gives
        ``speed`` or ``period``, not both.

        Raises:
            ParameterError: One line naming ``gait.<key>`` and its range, or an unknown key
                with the nearest known one.

        """
        known = [spec.name for spec in TABLE_KEYS]
        table = require_table(TABLE, table, ", ".join(known))
        for key in table:
            if key not in known:
                raise unknown_key(TABLE, key, TABLE_KEYS)
        if "speed" in table and "period" in table:
            raise ParameterError(
                f"{TABLE}.speed", table["speed"], "sets the period: give speed or period, not both"
            )
        fields = {k: v for k, v in table.items() if k != "speed"}
        try:
            gait = replace(cls() if base is None else base, **fields)
            return gait if "speed" not in table else gait.with_speed(table["speed"])
        except ParameterError as err:
            raise ParameterError(f"{TABLE}.{err.field}", err.value, err.allowed) from None

    def replace(self, **changes: Any) -> Gait:
        """Copy with some fields changed (validated again)."""
        return replace(self, **changes)

    def to_toml(self) -> str:
        """The design file's ``[gait]`` table of this gait (exact: :meth:`from_table` reads it)."""
        keys = ("pattern", "period", "stride", "step_height", "heading", "samples")
        lines = [
            f'{key} = "{value}"' if isinstance(value, str) else f"{key} = {value!r}"
            for key, value in ((key, getattr(self, key)) for key in keys)
        ]
        head = "# The gait every walking command walks by default (s, m, rad)."
        return "\n".join([head, f"[{TABLE}]", *lines]) + "\n"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form, with the duty factor and speed it implies (s, m, rad, m/s)."""
        return {
            "pattern": self.pattern,
            "duty_factor": self.duty_factor,
            "period": self.period,
            "stride": self.stride,
            "step_height": self.step_height,
            "heading": self.heading,
            "speed": self.speed,
            "samples": self.samples,
        }
