"""The answer to the user's requirements, as the Decision section shows it first.

Pure presentation of a :class:`~hexaleg.study.decide.DecideResult`: the best design that
meets every requirement (or the least infeasible one and what conflicts), each
requirement's value, margin and whether it binds, and the user's design checked against
each. The decision itself is :func:`hexaleg.study.decide.decide`.
"""

from __future__ import annotations

from hexaleg.evaluation.goal import Objective
from hexaleg.evaluation.requirements import format_margin
from hexaleg.output.report.document import table
from hexaleg.statics.ratings import OverRating
from hexaleg.study.decide import CheckedDesign, DecideResult
from hexaleg.study.decide_rows import BoundRow, RequirementRow, answer_rows, value_text


def requirement_blocks(result: DecideResult) -> tuple[str, ...]:
    """Markdown blocks: the verdict, the requirements table, joints over ratings, the search."""
    best, yours, objective = result.best, result.yours, result.objective
    lengths = ", ".join(f"{v:.3f}" for v in best.design.lengths)
    if result.feasible:
        extreme = "largest" if objective.sense == "maximize" else "smallest"
        verdict = (
            f"**The best leg meeting your requirements: l = ({lengths}) m**, the {extreme} "
            f"{objective.spec.label} of those that do: {_objective(best, objective)}"
        )
    else:
        reason = result.conflict.description if result.conflict else "nothing meets them all"
        verdict = (
            f"**No leg within the bounds meets every requirement:** {reason}. The leg closest "
            f"to meeting them is l = ({lengths}) m, {objective.spec.label} "
            f"{_objective(best, objective)}"
        )
    answer = answer_rows(result)
    rows = [_row(row) for row in answer.requirements] + [_bound_row(b) for b in answer.bounds]
    free = ", ".join(f"{v.name} {v.lower:.3g}–{v.upper:.3g}" for v in result.variables)
    walking = f" Walking: {result.walking_text()}." if result.walks else ""
    return (
        f"{verdict}; your design: {objective.spec.label} {_objective(yours, objective)}.",
        table(
            ["requirement", "best design", "margin", "binds", "your design", "yours meets it"],
            rows,
        ),
        over_rating_table(result),
        f"*How it was found.* Standing: at the nominal stance and the 12 axis-locked body "
        f"extremes.{walking} {result.evaluations} designs searched over {free} by "
        f"{result.method}, seed {result.seed}; the best was measured again from its own URDF. "
        "A requirement binds where the best design meets it within 1 % of the required value: "
        "relaxing it would buy a better design; so does a free variable at its search bound.",
    )


def _row(row: RequirementRow) -> tuple[str, ...]:
    """A requirement: the best design's value, margin and whether it binds; yours beside it."""
    best, yours = row.best, row.yours
    return (
        row.text,
        "—" if best is None else f"{value_text(best)} (limited by {best.limited_by})",
        "—" if best is None else format_margin(best),
        "" if best is None else "yes" if best.binds else "" if best.met else "NOT MET",
        "—" if yours is None else value_text(yours),
        "—" if yours is None else "yes" if yours.met else f"no ({format_margin(yours)})",
    )


def _bound_row(row: BoundRow) -> tuple[str, ...]:
    """A free variable at its search bound: it binds as a requirement would."""
    at = row.at
    variable, unit = at.variable, at.variable.unit
    return (
        f"{variable.name} within its searched {variable.lower:.3g}–{variable.upper:.3g} {unit}",
        f"{at.value:.4g} {unit} (at its {at.bound} bound; {at.remedy})",
        "±0",
        "yes",
        f"{row.yours:.4g} {unit}",
        "—",
    )


def _objective(checked: CheckedDesign, objective: Objective) -> str:
    value = checked.evaluation.metrics[objective.spec]
    return "—" if value is None else f"{value:.4g}"


SHOWN_OVER_RATING = 4
"""Joints over their ratings a cell lists, the furthest over first."""


def over_rating_table(result: DecideResult) -> str:
    """Each design's joints over their ratings, standing and walking, as a table."""
    best = result.best.over_rating_groups(result)
    yours = result.yours.over_rating_groups(result)
    rows = [
        (where, _flags(flags), _flags(your_flags))
        for (where, flags), (_, your_flags) in zip(best, yours, strict=True)
    ]
    return table(["joints over their ratings", "best design", "your design"], rows)


def _flags(flags: list[OverRating]) -> str:
    shown = "; ".join(str(flag) for flag in flags[:SHOWN_OVER_RATING]) or "none"
    more = len(flags) - SHOWN_OVER_RATING
    return shown + (f"; and {more} more (report.json lists them)" if more > 0 else "")
