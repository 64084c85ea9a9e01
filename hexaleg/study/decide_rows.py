"""The decision's answer as rows: built once here, rendered by the command line and the report.

:func:`answer_rows` turns a :class:`~hexaleg.study.decide.DecideResult` into one
:class:`RequirementRow` per requirement — what it asks in words, and on the best design
and on the user's the value, the margin, whether it is met and binds and what limits it —
and one :class:`BoundRow` per free variable the best design holds at a search bound
(that bound binds as a requirement would). ``hexaleg decide`` prints them design by design
(:mod:`hexaleg.cli.decide`), the report's Decision section as one table
(:mod:`hexaleg.output.report.requirements`); each only lays them out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from hexaleg.evaluation.requirements import RequirementCheck, format_value
from hexaleg.study.decide import DecideResult
from hexaleg.study.search_space import AtBound, value_of

__all__ = [
    "AnswerRows",
    "BoundRow",
    "PostureRow",
    "RequirementRow",
    "answer_rows",
    "exact",
    "value_text",
]


@dataclass(frozen=True)
class RequirementRow:
    """One requirement of the answer, checked on the best design and on the user's.

    Attributes:
        text: The requirement in words, with its conditions: ``payload ≥ 30 kg (...)``.
        best: Its check on the best design (``None``: that design could not be measured).
        yours: Its check on the user's design (``None``: likewise).

    """

    text: str
    best: RequirementCheck | None
    yours: RequirementCheck | None


@dataclass(frozen=True)
class BoundRow:
    """A free variable the best design holds at a search bound.

    Attributes:
        at: The variable and the bound it sits at.
        yours: The user's design's value of that variable [m or rad].

    """

    at: AtBound
    yours: float


@dataclass(frozen=True)
class PostureRow:
    """A design's posture and what it means for the robot (:func:`~.decide.posture_figures`).

    Attributes:
        nominal_angles: θ1, θ2, θ3 [rad].
        nominal_height: The body frame above the ground [m].
        foothold_radius: Each nominal foothold's horizontal distance from its leg's root [m].

    """

    nominal_angles: tuple[float, float, float]
    nominal_height: float
    foothold_radius: float

    def text(self) -> str:
        """``posture θ = (0, -0.418, -1.553) rad (0°, -24°, -89°), body height …, …``.

        The angles exactly as measured (a rounded answer's are milliradians).
        """
        radians = ", ".join(exact(a) for a in self.nominal_angles)
        degrees = ", ".join(f"{math.degrees(a):.3g}°" for a in self.nominal_angles)
        return (
            f"posture θ = ({radians}) rad ({degrees}), body height {self.nominal_height:.4g} m, "
            f"foothold radius {self.foothold_radius:.4g} m"
        )


@dataclass(frozen=True)
class AnswerRows:
    """Every row of the answer: the requirements in declared order, then the bounds that bind.

    Attributes:
        requirements: One row per requirement given.
        bounds: One row per free variable at a search bound.
        postures: The best design's posture and the user's (``None``: a robot file's legs,
            which stand as their file does).

    """

    requirements: tuple[RequirementRow, ...]
    bounds: tuple[BoundRow, ...]
    postures: tuple[PostureRow, PostureRow] | None = None


def answer_rows(result: DecideResult) -> AnswerRows:
    """The rows of a decision's answer (see the module's docstring)."""
    best = {check.name: check for check in result.best.checks}
    yours = {check.name: check for check in result.yours.checks}
    requirements = tuple(
        RequirementRow(result.requirements.describe(name), best.get(name), yours.get(name))
        for name in result.requirements.given
        if name in best or name in yours
    )
    design = result.yours.design
    bounds = tuple(BoundRow(at, value_of(design, at.variable.name)) for at in result.bounds_binding)
    figures = result.postures()
    postures = None if figures is None else (_posture(figures[0]), _posture(figures[1]))
    return AnswerRows(requirements, bounds, postures)


def _posture(figures: dict[str, Any]) -> PostureRow:
    angles = figures["nominal_angles"]
    return PostureRow(
        (angles[0], angles[1], angles[2]), figures["nominal_height"], figures["foothold_radius"]
    )


def exact(value: float) -> str:
    """``value`` exactly as measured: the shortest decimal that reads back as the same float."""
    return repr(float(value))


def value_text(check: RequirementCheck) -> str:
    """A check's value with its unit; ``-`` where it could not be measured (NaN)."""
    return "-" if math.isnan(check.value) else format_value(check.name, check.value)
