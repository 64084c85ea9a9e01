"""Every metric a design has, declared once, and a design's values of them, one field each.

A metric is one number measured on one design (its FB, its payload capacity, its max
speed). :class:`PerMetric` has one field per metric, and each field's declaration (its
:class:`MetricSpec`: unit, label, words, which way is better, what measures it) is that
field's metadata: the field's name is the metric's name in every record, table column,
JSON object and option, written nowhere else. The same fields hold whatever there is one
of per metric: :data:`METRICS` the declarations (``METRICS.fb`` is FB's), a design's
:class:`Metrics` its values (``metrics.fb``), :class:`Causes` what limits each and
:class:`Reasons` why one has no value. Code about one metric reads its field; code about
every metric iterates the declarations (:meth:`PerMetric.items`). Dictionaries appear
only at the edges, in :meth:`PerMetric.to_dict` and :meth:`Metrics.from_dict`.

Adding a metric is adding its field here and its measuring step in
:mod:`hexaleg.evaluation.evaluate`.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field, fields, replace
from typing import TYPE_CHECKING, Any, Generic, Literal, TypeVar

from hexaleg.cause import Cause
from hexaleg.exceptions import ParameterError

if TYPE_CHECKING:
    from hexaleg.design import HexapodDesign

T = TypeVar("T")

Better = Literal["maximize", "minimize"]
"""Which way a metric is better."""

Analysis = Literal[
    "geometry",
    "workspace",
    "manipulability",
    "flexibility",
    "clearance",
    "standing",
    "walking",
    "speed",
    "period",
    "motors",
    "structure",
]
"""The analysis that measures a metric (the evaluation runs each one at most once, in this order).

``walking``: the largest payload carried walking the gait; ``speed``: the fastest walk of
its stride; ``period``: one period of the gait (torques, work, ZMP); ``motors``: that
period through the design's actuators and battery; ``structure``: the legs' tubes under
their loads.
"""

WALKING: frozenset[Analysis] = frozenset({"walking", "speed", "period", "motors"})
"""The analyses that walk the gait."""

Torque = Literal["peak", "rms"]
"""Which torque of a joint type over a gait period a metric is."""

DesignTable = Literal["actuators", "battery"]
"""A table of the design file a metric may be measured through (``[actuators]``, ``[battery]``)."""

TABLE_WORDS: Mapping[DesignTable, str] = {
    "battery": "a [battery] table",
    "actuators": "an [actuators] table",
}
"""Each design-file table a metric may need, in words, in the order a refusal names them."""


@dataclass(frozen=True)
class MetricSpec:
    """Everything said about one metric, once.

    Attributes:
        name: Its key in every record, table column, JSON object and option: the name of
            its field of :class:`PerMetric`.
        unit: Its SI unit as written in brackets (``"1"`` for a pure number).
        label: Its name in a sentence or a table cell: ``"FB"``, ``"improved area"``.
        text: What it is, with its source: ``"body flexibility FB (eq 29, axis-locked)"``.
        better: Whether larger or smaller is better.
        analysis: What measures it.
        objective: Whether ``decide`` offers it as an objective (in its better direction).
        torque: For a joint type's torque over a gait period, which: peak or RMS.
        joint: That joint type (``root``, ``hip`` or ``knee``).
        needs: The design-file tables it is measured through: without one, it has no value.

    """

    name: str
    unit: str
    label: str
    text: str
    better: Better
    analysis: Analysis
    objective: bool = False
    torque: Torque | None = None
    joint: str | None = None
    needs: tuple[DesignTable, ...] = ()

    @property
    def walks(self) -> bool:
        """Whether measuring it walks the gait."""
        return self.analysis in WALKING

    def lacks(self, design: HexapodDesign, actuators: bool = False) -> tuple[DesignTable, ...]:
        """The tables it :attr:`needs` that ``design`` has not, in declared order.

        ``actuators``: motors are being chosen for it (``decide --choose-actuators``).
        """
        has = {
            "actuators": actuators or design.actuators is not None,
            "battery": design.battery is not None,
        }
        return tuple(table for table in self.needs if not has[table])

    @property
    def described(self) -> str:
        """What it is with its unit: ``"body flexibility FB [-] (eq 29, axis-locked)"``."""
        unit = "-" if self.unit == "1" else self.unit
        head, _, source = self.text.partition(" (")
        return f"{head} [{unit}]" + (f" ({source}" if source else "")

    def format(self, value: float) -> str:
        """The value with its unit, four significant digits; angles also in degrees."""
        if self.unit == "rad":
            return f"{significant(value, 4)} rad ({significant(math.degrees(value))}°)"
        text = significant(value, 4)
        return text if self.unit == "1" else f"{text} {self.unit}"

    def cell(self, value: float) -> str:
        """The value in a table cell whose header gives the unit: four significant digits."""
        return significant(value, 4)

    def short(self, value: float) -> str:
        """The value in a sentence, as an engineer writes it: ``2000 kg``, ``0.0123 m``, ``17°``.

        Three significant digits, never an exponent; angles in degrees.
        """
        if self.unit == "rad":
            return f"{significant(math.degrees(value))}°"
        text = significant(value)
        return text if self.unit == "1" else f"{text} {self.unit}"


def significant(value: float, digits: int = 3) -> str:
    """``value`` rounded to ``digits`` significant digits, written without an exponent."""
    if not math.isfinite(value) or value == 0:
        return f"{value:g}"
    rounded = float(f"{value:.{digits}g}")
    decimals = max(0, digits - 1 - math.floor(math.log10(abs(rounded))))
    text = f"{rounded:.{decimals}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


_DECLARATION = "metric"
"""The key of a :class:`PerMetric` field's metadata holding its declaration."""


def declare(
    unit: str,
    label: str,
    text: str,
    better: Better,
    analysis: Analysis,
    *,
    objective: bool = False,
    torque: Torque | None = None,
    joint: str | None = None,
    needs: tuple[DesignTable, ...] = (),
) -> Any:
    """A field of :class:`PerMetric` declaring its metric (named after the field)."""
    spec = MetricSpec("", unit, label, text, better, analysis, objective, torque, joint, needs)
    return field(default=None, metadata={_DECLARATION: spec})


@dataclass(frozen=True)
class PerMetric(Generic[T]):
    """One ``T`` for each metric, a field each, in the order answers list them (default ``None``).

    Each field's metadata is its metric's declaration; :data:`METRICS` holds them.
    """

    improved_area: T = declare(
        unit="m²",
        label="improved area",
        text="improved workspace area (eq 16)",
        better="maximize",
        analysis="workspace",
        objective=True,
    )
    average_manipulability: T = declare(
        unit="m³",
        label="w_A",
        text="average manipulability w_A (eq 27, improved domain)",
        better="maximize",
        analysis="manipulability",
        objective=True,
    )
    fb: T = declare(
        unit="1",
        label="FB",
        text="body flexibility FB (eq 29, axis-locked)",
        better="maximize",
        analysis="flexibility",
        objective=True,
    )
    payload_capacity: T = declare(
        unit="kg",
        label="payload",
        text="payload capacity (nominal stance, on the required slope if one is)",
        better="maximize",
        analysis="standing",
        objective=True,
    )
    walking_payload_capacity: T = declare(
        unit="kg",
        label="walking payload",
        text="walking payload capacity (the gait within every rating, the ZMP inside)",
        better="maximize",
        analysis="walking",
        objective=True,
    )
    max_slope: T = declare(
        unit="rad",
        label="slope",
        text="steepest slope stood on in every heading, with the payload",
        better="maximize",
        analysis="standing",
    )
    ground_clearance: T = declare(
        unit="m",
        label="ground clearance",
        text="body underside above the ground (nominal stance)",
        better="maximize",
        analysis="clearance",
    )
    leg_length: T = declare(
        unit="m",
        label="leg length",
        text="total leg length l1 + l2 + l3",
        better="minimize",
        analysis="geometry",
        objective=True,
    )
    coxa_length: T = declare(
        unit="m",
        label="coxa",
        text="coxa length l1",
        better="maximize",
        analysis="geometry",
    )
    robot_mass: T = declare(
        unit="kg",
        label="robot mass",
        text="the whole robot's mass",
        better="minimize",
        analysis="geometry",
        objective=True,
    )
    max_speed: T = declare(
        unit="m/s",
        label="speed",
        text="fastest walk of the gait's stride within the ratings",
        better="maximize",
        analysis="speed",
        objective=True,
    )
    gait_peak_torque: T = declare(
        unit="N·m",
        label="peak torque",
        text="largest joint torque over a gait period",
        better="minimize",
        analysis="period",
        objective=True,
    )
    mechanical_cost_of_transport: T = declare(
        unit="1",
        label="mechanical cost of transport",
        text="positive mechanical work per weight and distance walked",
        better="minimize",
        analysis="period",
        objective=True,
    )
    mechanical_energy_per_km: T = declare(
        unit="Wh/km",
        label="mechanical energy",
        text="positive mechanical work per kilometre walked",
        better="minimize",
        analysis="period",
    )
    energy_per_km: T = declare(
        unit="Wh/km",
        label="energy per km",
        text="electrical energy per kilometre walked, through the motors",
        better="minimize",
        analysis="motors",
        objective=True,
        needs=("actuators",),
    )
    electrical_cost_of_transport: T = declare(
        unit="1",
        label="electrical cost of transport",
        text="electrical energy per weight and distance walked",
        better="minimize",
        analysis="motors",
        needs=("actuators",),
    )
    continuous_load: T = declare(
        unit="1",
        label="continuous load",
        text="largest RMS torque over its actuator's continuous torque, any joint",
        better="minimize",
        analysis="motors",
        needs=("actuators",),
    )
    battery_range: T = declare(
        unit="km",
        label="range",
        text="distance walked on one charge of the battery",
        better="maximize",
        analysis="motors",
        objective=True,
        needs=("actuators", "battery"),
    )
    min_zmp_margin: T = declare(
        unit="m",
        label="ZMP margin",
        text="the gait's least ZMP distance inside the standing feet",
        better="maximize",
        analysis="period",
    )
    gait_peak_root_torque: T = declare(
        unit="N·m",
        label="root peak torque",
        text="peak root torque over a gait period (the worst leg)",
        better="minimize",
        analysis="period",
        torque="peak",
        joint="root",
    )
    gait_rms_root_torque: T = declare(
        unit="N·m",
        label="root rms torque",
        text="RMS root torque over a gait period (the worst leg)",
        better="minimize",
        analysis="period",
        torque="rms",
        joint="root",
    )
    gait_peak_hip_torque: T = declare(
        unit="N·m",
        label="hip peak torque",
        text="peak hip torque over a gait period (the worst leg)",
        better="minimize",
        analysis="period",
        torque="peak",
        joint="hip",
    )
    gait_rms_hip_torque: T = declare(
        unit="N·m",
        label="hip rms torque",
        text="RMS hip torque over a gait period (the worst leg)",
        better="minimize",
        analysis="period",
        torque="rms",
        joint="hip",
    )
    gait_peak_knee_torque: T = declare(
        unit="N·m",
        label="knee peak torque",
        text="peak knee torque over a gait period (the worst leg)",
        better="minimize",
        analysis="period",
        torque="peak",
        joint="knee",
    )
    gait_rms_knee_torque: T = declare(
        unit="N·m",
        label="knee rms torque",
        text="RMS knee torque over a gait period (the worst leg)",
        better="minimize",
        analysis="period",
        torque="rms",
        joint="knee",
    )
    nominal_height: T = declare(
        unit="m",
        label="body height",
        text="body frame's height above the ground at the nominal stance",
        better="maximize",
        analysis="geometry",
    )
    stability_margin: T = declare(
        unit="m",
        label="stability margin",
        text="centre of mass's footprint inside the support polygon (nominal stance)",
        better="maximize",
        analysis="standing",
    )
    structure_load: T = declare(
        unit="1",
        label="structure load",
        text="the legs' tubes: the largest von Mises stress over strength / safety factor, "
        "or foot deflection over its limit (nominal stance, 12 extremes, the slope; and "
        "walking the gait when the robot must walk)",
        better="minimize",
        analysis="structure",
    )

    def __getitem__(self, spec: MetricSpec) -> T:
        """The field of metric ``spec``."""
        value: T = getattr(self, spec.name)
        return value

    def items(self) -> Iterator[tuple[MetricSpec, T]]:
        """Each metric's declaration and its field, in declared order."""
        return zip(METRICS, vars(self).values(), strict=True)  # fields set in declared order

    def given(self) -> Iterator[tuple[MetricSpec, T]]:
        """:meth:`items` without the fields that are ``None``."""
        return ((spec, value) for spec, value in self.items() if value is not None)

    def to_dict(self) -> dict[str, T]:
        """The fields that are not ``None``, by metric name (JSON's and the tables' keys)."""
        return {name: value for name, value in vars(self).items() if value is not None}


@dataclass(frozen=True)
class Metrics(PerMetric["float | None"]):
    """One design's metrics [each its declared unit].

    ``None``: not measured (nobody asked for it). NaN: asked for, but the design has no
    value of it — :attr:`~hexaleg.evaluation.evaluate.Evaluation.unmeasured` says why (a
    gait it cannot walk, no actuators).
    """

    def value(self, spec: MetricSpec) -> float:
        """The value of metric ``spec`` [its unit]; NaN where it has none or was not measured."""
        value = self[spec]
        return math.nan if value is None else value

    def joint_torques(self, torque: Torque) -> dict[str, float | None]:
        """Each joint type's peak (or RMS) torque over the gait period [N·m], by joint."""
        return {
            spec.joint: value
            for spec, value in self.items()
            if spec.torque == torque and spec.joint is not None
        }

    @classmethod
    def from_dict(cls, values: Mapping[str, Any]) -> Metrics:
        """Metrics from :meth:`to_dict` (a JSON null is NaN); ValueError on another key."""
        unknown = [name for name in values if name not in METRICS]
        if unknown:
            raise ValueError(f"unknown metric {unknown[0]!r}")
        return cls(**{k: math.nan if v is None else float(v) for k, v in values.items()})


@dataclass(frozen=True)
class Causes(PerMetric["Cause | None"]):
    """What limits each metric, where something does (payload, slope, speed)."""

    @classmethod
    def from_dict(cls, causes: Mapping[str, Any]) -> Causes:
        """Causes from :meth:`to_dict` with each cause as its own ``to_dict``."""
        unknown = [name for name in causes if name not in METRICS]
        if unknown:
            raise ValueError(f"unknown metric {unknown[0]!r}")
        return cls(**{k: Cause.from_dict(v) for k, v in causes.items()})


@dataclass(frozen=True)
class Reasons(PerMetric["str | None"]):
    """Why a metric asked for has no value (``None``: it has one, or was not asked for)."""


@dataclass(frozen=True)
class Declarations(PerMetric[MetricSpec]):
    """Every metric's declaration, its field's: ``METRICS.fb`` is FB's."""

    def __iter__(self) -> Iterator[MetricSpec]:
        """The declarations, in declared order."""
        return iter(vars(self).values())

    def __contains__(self, name: object) -> bool:
        """Whether ``name`` names a metric."""
        return isinstance(name, str) and name in self.__dataclass_fields__

    def named(self, name: str) -> MetricSpec:
        """The declaration of metric ``name``; a ParameterError naming the known ones otherwise."""
        if name not in self:
            raise ParameterError("metric", name, "one of " + ", ".join(s.name for s in self))
        spec: MetricSpec = getattr(self, name)
        return spec


METRICS = Declarations(
    **{f.name: replace(f.metadata[_DECLARATION], name=f.name) for f in fields(PerMetric)}
)
"""Every metric's declaration, in the order answers list them."""


def objectives(better: Better) -> tuple[str, ...]:
    """The metrics ``decide`` offers to make best in direction ``better``."""
    return tuple(m.name for m in METRICS if m.objective and m.better == better)
