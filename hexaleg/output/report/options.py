"""What the report runs: the sizes of its sweeps and the choices the user made."""

from __future__ import annotations

from dataclasses import dataclass, field

from hexaleg._checks import require_int
from hexaleg.design import MAX_L3_POINTS, require_ratio
from hexaleg.evaluation.requirement_specs import WALKING_PAYLOAD
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError
from hexaleg.field_sweep import FieldSweep
from hexaleg.gait.spec import Gait
from hexaleg.paper import L1_RATIOS, L3_RATIO_POINTS
from hexaleg.ratios import MAX_L1_RATIOS
from hexaleg.study.executors import max_workers
from hexaleg.study.recommendation import DecisionOptions
from hexaleg.swing.workspace import MAX_SAMPLES

MIN_L3_POINTS = 10
"""Fewest tibia ratios a report accepts: coarser grids cannot bracket the peaks [-]."""

MAX_SENSITIVITY_POINTS = 400
"""Most tibia ratios per variant in the sensitivity table (8 variants × 2 coxa ratios)."""


@dataclass(frozen=True)
class ReportOptions:
    """How much of the paper's sweeps the report runs.

    Attributes:
        l3_points: Tibia ratios per coxa ratio in the sweeps (the paper: 80).
        sensitivity_points: Tibia ratios per coxa ratio in the posture sensitivity table.
        monte_carlo_samples: Samples of the Monte Carlo workspace.
        workers: Local processes for the flexibility study (default: CPUs).
        progress: ``False`` shows no progress; by default a bar on a terminal, a line
            every few seconds elsewhere (as a study: :class:`~hexaleg.study.progress.Progress`).
        l1_ratios: Coxa ratios to sweep and recommend from (a fixed coxa: one ratio);
            by default the paper's four, recommending among the practical ones (≥ 0.10).
        collisions: The robot's own parts touching also stop the body, in the design's
            flexibility and in the study.
        sweep: A body field to sweep in the sensitivity table instead of the posture and
            body variants (``--sweep body_width=0.4:0.8:9``).
        pdf: Also write ``report.pdf`` (needs the ``[pdf]`` extra).
        vector_figures: Write an SVG beside each PNG, linked from the report for print
            (always with ``pdf``, which is made of them); off, the figures take half the
            time.
        requirements: What the robot must do: the Decision section then shows first the
            best design that meets it (:func:`hexaleg.study.decide.decide`).
        simulate: Also walk :attr:`gait` in MuJoCo (the ``[sim]`` extra) for the
            "Simulated walk" section.
        gait: The gait every walking number of the report is measured on: the design
            file's ``[gait]`` table, else the default gait.
        default_gait: The robot's own default gait, if the caller found it already (a robot
            file's is found by walking it: :func:`~hexaleg.gait.defaults.default_gait`);
            the report finds it when it needs it otherwise.

    """

    l3_points: int = L3_RATIO_POINTS
    sensitivity_points: int = 40
    monte_carlo_samples: int = 20_000
    workers: int | None = None
    progress: bool | None = None
    l1_ratios: tuple[float, ...] | None = None
    collisions: bool = False
    sweep: FieldSweep | None = None
    pdf: bool = False
    vector_figures: bool = True
    requirements: Requirements | None = None
    simulate: bool = False
    gait: Gait = field(default_factory=Gait)
    default_gait: Gait | None = None

    def __post_init__(self) -> None:
        if self.l1_ratios is not None:
            object.__setattr__(self, "l1_ratios", tuple(float(r) for r in self.l1_ratios))
            if not 1 <= len(self.l1_ratios) <= MAX_L1_RATIOS:
                raise HexalegError(f"l1_ratios: give 1 to {MAX_L1_RATIOS} coxa ratios")
            for ratio in self.l1_ratios:
                require_ratio("l1_ratios", ratio)
        for name, (lower, upper) in {
            "l3_points": (2, MAX_L3_POINTS),
            "sensitivity_points": (2, MAX_SENSITIVITY_POINTS),
            "monte_carlo_samples": (1, MAX_SAMPLES),
            "workers": (1, max_workers()),
        }.items():
            if getattr(self, name) is not None:
                require_int(name, getattr(self, name), lower, upper)
        if self.l3_points < MIN_L3_POINTS:
            raise HexalegError(
                f"l3_points = {self.l3_points} is too coarse to locate the peaks: "
                f"the report needs {MIN_L3_POINTS}..{MAX_L3_POINTS} tibia ratios"
            )

    @property
    def swept_l1_ratios(self) -> tuple[float, ...]:
        """The coxa ratios the sweeps cover [-]."""
        return self.l1_ratios or L1_RATIOS

    @property
    def svg(self) -> bool:
        """Whether the report writes an SVG beside each PNG."""
        return self.vector_figures or self.pdf

    @property
    def decision(self) -> DecisionOptions:
        """What the decision may choose from (coxa ratios, collisions, gait) and its payload.

        Every ranked leg walks the gait carrying the payload the requirements ask for (the
        larger of the standing and the walking payload given), up, down and across their
        walking slope (none and level ground without requirements).
        """
        required = self.requirements
        payload = slope = 0.0
        if required is not None:
            walking = required.required(WALKING_PAYLOAD) or 0.0
            payload, slope = max(required.payload_mass, walking), required.walking_slope
        return DecisionOptions(self.l1_ratios, self.collisions, self.gait, payload, slope)
