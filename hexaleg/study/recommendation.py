"""The recommended leg: the best by the ranking rule, each candidate at its best posture.

The ranking rule (:mod:`hexaleg.study.ranking`) puts what the robot must do first (walk the
gait carrying the payload within every rating: a constraint) and then the paper's metrics
(improved area, w_A, FB: a score relative to the user's design). A leg's lengths are judged
at their best use, so every candidate stands at its best posture:

- **your lengths re-posed**: the user's segments with the hip and knee angles free within
  the stance limits (:func:`~hexaleg.study.best_leg.best_posture_of`): the cheapest
  improvement, since only the posture changes; its score is never below the design's own
  as posed, which is a candidate;
- **the recommended leg**: at each allowed coxa ratio (the paper's practical ones, ≥ 0.10,
  unless the user fixes the coxa), the tibia ratio and the posture free
  (:func:`~hexaleg.study.best_leg.best_leg_at`); the best of those.

**The band and the cliff.** Along the tibia ratio, at the recommended coxa ratio and
posture, the legs are profiled (:func:`tibia_profile`): where the constraint stops holding
between two neighbouring tibia ratios is a cliff (located by bisection), and a leg within
:data:`CLIFF_MARGIN` of one is not recommended (a tolerance or a heavier load would take it
over the edge). If the search's best sits that close, the recommendation steps back to the
best leg of the profile clear of every cliff. The band is the run of tibia ratios around the
recommendation that keep ≥ :data:`BAND` of its score, meet the constraint and are clear of
every cliff (:func:`band_and_cliffs`).

The grid of the design study (measured at the user's posture) is ranked by the same rule
for the Pareto front and the table of peaks (:func:`grid_ranking`).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass, field, replace

import numpy as np
import numpy.typing as npt
import pandas as pd

from hexaleg._typing import ArrayF
from hexaleg.evaluation.metrics import Metrics, MetricSpec
from hexaleg.exceptions import HexalegError
from hexaleg.gait.spec import Gait
from hexaleg.study.best_leg import Leg, Legs, best_leg_at, best_posture_of
from hexaleg.study.ranking import RANKED_METRICS, WalkingConstraint, relative_values, scores
from hexaleg.study.sweep import StudySpec
from hexaleg.swing.manipulability import AverageManipulabilityMap
from hexaleg.swing.workspace import improved_area_closed_form

BAND = 0.97
"""Share of the recommendation's score that defines the band around it."""

CLIFF_MARGIN = 0.02
"""How close to a cliff a recommended leg may not be: 2 % of the leg length, as a tibia
ratio [-] (a tibia made 1 % long, a heavier load or a stiffer gait must not take it over)."""

PROFILE_STEP = 0.01
"""Tibia-ratio step of the profile around a leg [-] (half the cliff margin)."""

BISECTIONS = 6
"""Halvings that locate a cliff between two profiled legs (to 0.01/64 of the tibia ratio)."""

PRACTICAL_L1_RATIO = 0.10
"""Smallest coxa ratio the paper calls practical (§5.3: "between 0.1 and 0.2"); every
kinematic metric improves as the coxa shrinks, so unless the user fixes the coxa, the
recommendation is made among coxa ratios at least this large."""


class NothingToRecommend(HexalegError):
    """No allowed leg meets the ranking's constraint."""


@dataclass(frozen=True)
class DecisionOptions:
    """What the decision may choose from, and what every leg must do.

    Attributes:
        l1_ratios: Coxa ratios the recommendation may take; ``None``: the swept ones at
            least :data:`PRACTICAL_L1_RATIO` (all of them if none is).
        collisions: The robot's own parts touching also stop the body (FB).
        gait: The gait every leg walks (the design file's ``[gait]``, else the default).
        payload: The payload every ranked leg walks it with [kg] (the requirements', or 0).
        walking_slope: The slope every ranked leg walks it up, down and across [rad] (the
            requirements', or 0: level ground).

    """

    l1_ratios: tuple[float, ...] | None = None
    collisions: bool = False
    gait: Gait = field(default_factory=Gait)
    payload: float = 0.0
    walking_slope: float = 0.0

    @property
    def constraint(self) -> WalkingConstraint:
        """What every ranked leg must do: walk the gait carrying :attr:`payload`."""
        return WalkingConstraint(self.payload, self.walking_slope)

    def describe_candidates(self) -> str:
        """The allowed coxa ratios, in words."""
        if self.l1_ratios:
            listed = ", ".join(f"{r:.3g}" for r in self.l1_ratios)
            return f"the coxa ratios you allowed ({listed})"
        return f"the paper's practical coxa ratios (≥ {PRACTICAL_L1_RATIO:.2f})"


@dataclass(frozen=True)
class Cliff:
    """Where the constraint stops holding along the tibia ratio, at a coxa ratio and posture.

    Attributes:
        l3_ratio: Where it stops holding [-] (between :attr:`held` and :attr:`broken`).
        held: The nearest tibia ratio measured where it holds [-].
        broken: The nearest measured beyond, where it does not [-].
        capacity: The walking payload capacity at :attr:`held` [kg].
        why: What stops the walk (or limits its payload) at :attr:`broken`.

    """

    l3_ratio: float
    held: float
    broken: float
    capacity: float
    why: str

    def describe(self) -> str:
        """``"at tibia ratio 0.725 (72.7 kg walking at 0.7249; at 0.7251 knee torque …)"``."""
        return (
            f"at tibia ratio {self.l3_ratio:.3f} ({self.capacity:.1f} kg walking at "
            f"{self.held:.4f}; at {self.broken:.4f} {self.why or 'it does not walk'})"
        )

    def to_dict(self) -> dict[str, float | str]:
        """JSON-ready (ratios [-], capacity [kg])."""
        return {
            "l3_ratio": self.l3_ratio,
            "held": self.held,
            "broken": self.broken,
            "capacity": self.capacity,
            "why": self.why,
        }


@dataclass(frozen=True)
class Profile:
    """Legs along the tibia ratio at one coxa ratio and posture, in tibia order.

    Attributes:
        legs: The legs measured, in increasing tibia ratio.
        cliffs: Where the constraint stops holding between two of them.

    """

    legs: tuple[Leg, ...]
    cliffs: tuple[Cliff, ...]


@dataclass(frozen=True)
class Recommendation:
    """The recommended leg and the evidence behind it.

    Attributes:
        best: The recommended leg at its posture (its robot, evaluation and score).
        reposed: Your lengths at their best posture (only the posture changed).
        yours: Your design as posed.
        l3_band: The tibia ratios around it that keep ≥ :data:`BAND` of its score, meet
            the constraint and are clear of every cliff [-].
        cliffs: The cliffs found along its tibia ratio at its posture.
        searched: The search's best leg at each allowed coxa ratio (before any step back).
        constraint: What every ranked leg must do.
        peaks: On the study's grid (your posture), per coxa ratio, where each ranked metric
            and the score peak among the legs that meet the constraint.
        scores: Every grid leg's metrics, relative to yours, whether it meets the
            constraint, and its score.
        evaluations: Legs measured by the searches and the profiles.
        relaxed: The constraint asked for, when no allowed leg met it and the legs were
            ranked by :attr:`constraint` instead (walking the gait unloaded).

    """

    best: Leg
    reposed: Leg
    yours: Leg
    l3_band: tuple[float, float]
    cliffs: tuple[Cliff, ...]
    searched: tuple[Leg, ...]
    constraint: WalkingConstraint
    peaks: pd.DataFrame
    scores: pd.DataFrame
    evaluations: int
    relaxed: WalkingConstraint | None = None

    @property
    def l1_ratio(self) -> float:
        """Recommended coxa ratio [-]."""
        return self.best.l1_ratio

    @property
    def l3_ratio(self) -> float:
        """Recommended tibia ratio [-]."""
        return self.best.l3_ratio

    @property
    def l2_ratio(self) -> float:
        """Femur ratio 1 − l1 − l3 [-]."""
        return 1.0 - self.l1_ratio - self.l3_ratio

    @property
    def nominal_angles(self) -> tuple[float, float, float]:
        """The recommended leg's posture (θ1, θ2, θ3) [rad]."""
        return self.best.design.nominal_angles

    @property
    def score(self) -> float:
        """Its score [-] (your design: 1)."""
        return self.best.score

    @property
    def reference(self) -> Metrics:
        """Your design's metrics: what every score is relative to."""
        return self.yours.evaluation.metrics

    @property
    def metrics(self) -> Metrics:
        """The recommended leg's metrics."""
        return self.best.evaluation.metrics

    @property
    def stepped_back(self) -> Leg | None:
        """The search's best at the recommended coxa ratio, if the recommendation stepped back.

        It did when that leg sat within :data:`CLIFF_MARGIN` of a cliff.
        """
        for leg in self.searched:
            if math.isclose(leg.l1_ratio, self.l1_ratio) and leg.design != self.best.design:
                return leg
        return None


def candidate_mask(
    l1_ratios: npt.ArrayLike, candidates: Sequence[float] | None
) -> npt.NDArray[np.bool_]:
    """Which coxa ratios the recommendation may take.

    Args:
        l1_ratios: Coxa ratios (N,) [-], e.g. of a grid or of a study's rows.
        candidates: The allowed coxa ratios; by default those ≥ :data:`PRACTICAL_L1_RATIO`.

    Returns:
        A mask (N,); all true if no ratio is allowed (the whole grid competes).

    """
    r1 = np.asarray(l1_ratios, dtype=float)
    if candidates is not None:
        mask = np.isclose(r1[:, None], np.asarray(candidates, dtype=float)[None, :]).any(axis=1)
    else:
        mask = r1 >= PRACTICAL_L1_RATIO - 1e-12
    return mask if mask.any() else np.ones_like(mask)


# -- the search ----------------------------------------------------------------------------


@dataclass(frozen=True)
class Searching:
    """What every search measures: the study's robot and conditions, the metrics, the rule.

    Attributes:
        spec: The study: its robot, its conditions (each leg's, without kept analyses) and
            its tibia-ratio range.
        metrics: What each leg is measured for (the report's metrics: its one evaluation).
        constraint: What a ranked leg must do.
        yours: Your design as posed, measured: the reference of every score, never
            measured again.

    """

    spec: StudySpec
    metrics: tuple[MetricSpec, ...]
    constraint: WalkingConstraint
    yours: Leg

    def legs(self) -> Legs:
        """The legs of the study's robot, each measured once, ranked against yours."""
        conditions = replace(self.spec.conditions, keep=False)  # only numbers: legs are many
        return Legs(
            self.spec.robot,
            self.metrics,
            conditions,
            self.constraint,
            self.yours.evaluation.metrics,
            (self.yours,),
        )

    @property
    def l3_range(self) -> tuple[float, float]:
        """The tibia ratios a leg may take: the study's [-]."""
        return (min(self.spec.l3_ratios), max(self.spec.l3_ratios))


def recommend(
    searching: Searching, options: DecisionOptions, executor: Executor | None = None
) -> tuple[Leg, tuple[Leg, ...], int]:
    """Your lengths re-posed, and the best leg at each allowed coxa ratio (each at its posture).

    Args:
        searching: What every search measures.
        options: The allowed coxa ratios.
        executor: Where the searches run (one task each); this process if omitted.

    Returns:
        Your lengths re-posed, the best leg of each allowed coxa ratio, and how many legs
        the searches measured.

    """
    spec = searching.spec
    allowed = np.asarray(spec.l1_ratios)[candidate_mask(spec.l1_ratios, options.l1_ratios)]
    light = replace(searching, yours=_light(searching.yours))  # what crosses to a process
    tasks = [(light, None), *((light, float(r1)) for r1 in allowed)]
    found = list(map(_run, tasks)) if executor is None else list(executor.map(_run, tasks))
    reposed, count = found[0]
    assert reposed is not None  # your posture is a candidate
    legs = tuple(leg for leg, _ in found[1:] if leg is not None)
    return reposed, legs, count + sum(n for _, n in found[1:])


def _run(task: tuple[Searching, float | None]) -> tuple[Leg | None, int]:
    """One search (your lengths re-posed, or one coxa ratio): its best leg, legs measured."""
    searching, l1_ratio = task
    legs = searching.legs()
    if l1_ratio is None:
        found: Leg | None = best_posture_of(legs, searching.yours.robot)
    else:
        found = best_leg_at(legs, l1_ratio, searching.l3_range)
    return found, legs.measured


def _light(leg: Leg) -> Leg:
    """The leg without its kept analyses: what crosses to a search's process."""
    evaluation = replace(leg.evaluation, flexibility=None, loads=None, gait=None)
    return replace(leg, evaluation=evaluation)


# -- the profile, the cliffs and the band ----------------------------------------------------


def tibia_profile(legs: Legs, leg: Leg, l3_range: tuple[float, float], whole: bool) -> Profile:
    """Legs along the tibia ratio at ``leg``'s coxa ratio and posture, and their cliffs.

    Args:
        legs: How to measure a leg (each once).
        leg: The leg profiled around (one of the profile's legs).
        l3_range: The tibia ratios a leg may take [-].
        whole: Profile the whole range (to step back from a cliff); otherwise outward from
            ``leg`` until the score falls below :data:`BAND` of its own or the constraint
            breaks, and :data:`CLIFF_MARGIN` beyond.

    """
    angles = (leg.design.nominal_angles[1], leg.design.nominal_angles[2])
    r1, r3 = leg.l1_ratio, leg.l3_ratio

    def at(ratio: float) -> Leg | None:
        return leg if ratio == r3 else legs.at(r1, ratio, angles)

    found: dict[float, Leg] = {r3: leg}
    for direction in (-1, 1):
        beyond: float | None = None
        for k in range(1, int((l3_range[1] - l3_range[0]) / PROFILE_STEP) + 2):
            ratio = r3 + direction * k * PROFILE_STEP
            if not l3_range[0] - 1e-12 <= ratio <= l3_range[1] + 1e-12:
                break
            sample = at(ratio)
            if sample is None:
                break
            found[ratio] = sample
            failed = not sample.ranked or sample.score < BAND * leg.score
            if failed and beyond is None and not whole:
                beyond = ratio + direction * CLIFF_MARGIN
            if beyond is not None and direction * (ratio - beyond) >= -1e-12:
                break
    ordered = tuple(found[ratio] for ratio in sorted(found))
    return Profile(ordered, tuple(_cliffs(ordered, at)))


def _cliffs(ordered: Sequence[Leg], at: Callable[[float], Leg | None]) -> list[Cliff]:
    """Each place between two neighbours where the constraint flips, located by bisection."""
    cliffs = []
    for left, right in itertools.pairwise(ordered):
        if left.meets == right.meets:
            continue
        held, broken = (left, right) if left.meets else (right, left)
        for _ in range(BISECTIONS):
            middle = at(0.5 * (held.l3_ratio + broken.l3_ratio))
            if middle is None:
                break
            held, broken = (middle, broken) if middle.meets else (held, middle)
        cliffs.append(
            Cliff(
                0.5 * (held.l3_ratio + broken.l3_ratio),
                held.l3_ratio,
                broken.l3_ratio,
                held.capacity,
                broken.limited_by,
            )
        )
    return cliffs


def band_and_cliffs(
    l3_ratios: Sequence[float],
    scores_: Sequence[float],
    meets: Sequence[bool],
    chosen: int,
    cliffs: Sequence[float],
) -> tuple[float, float] | None:
    """The band around leg ``chosen`` of a profile: the run of clear, good legs around it.

    Args:
        l3_ratios: The profile's tibia ratios, increasing [-].
        scores_: Their scores [-] (NaN: none).
        meets: Whether each meets the constraint.
        chosen: The index of the recommended leg.
        cliffs: Where the constraint stops holding [-].

    Returns:
        (lowest, highest) tibia ratio of the run around ``chosen`` whose legs meet the
        constraint, keep ≥ :data:`BAND` of its score and lie at least :data:`CLIFF_MARGIN`
        from every cliff; ``None`` if the chosen leg itself is not such a leg.

    """
    ratios = np.asarray(l3_ratios, dtype=float)
    best = float(scores_[chosen])

    def good(i: int) -> bool:
        clear = all(abs(ratios[i] - c) >= CLIFF_MARGIN - 1e-12 for c in cliffs)
        value = float(scores_[i])
        return bool(meets[i]) and math.isfinite(value) and value >= BAND * best and clear

    if not good(chosen):
        return None
    low = high = chosen
    while low - 1 >= 0 and good(low - 1):
        low -= 1
    while high + 1 < len(ratios) and good(high + 1):
        high += 1
    return float(ratios[low]), float(ratios[high])


def clear_of_cliffs(profile: Profile) -> Leg | None:
    """The best ranked leg of a profile at least :data:`CLIFF_MARGIN` from every cliff."""
    clear = [
        leg
        for leg in profile.legs
        if leg.ranked
        and all(abs(leg.l3_ratio - c.l3_ratio) >= CLIFF_MARGIN - 1e-12 for c in profile.cliffs)
    ]
    return max(clear, key=lambda leg: leg.score, default=None)


def settled(legs: Legs, leg: Leg, l3_range: tuple[float, float]) -> tuple[Leg, Profile]:
    """``leg``, or the best leg clear of every cliff of its profile if it is not; its profile."""
    profile = tibia_profile(legs, leg, l3_range, whole=False)
    near = any(abs(leg.l3_ratio - c.l3_ratio) < CLIFF_MARGIN for c in profile.cliffs)
    if not near:
        return leg, profile
    whole = tibia_profile(legs, leg, l3_range, whole=True)
    chosen = clear_of_cliffs(whole) or leg
    return chosen, tibia_profile(legs, chosen, l3_range, whole=False)


def band_of(leg: Leg, profile: Profile) -> tuple[float, float]:
    """The band around ``leg`` in its profile (just its own tibia ratio if it has none)."""
    ratios = [x.l3_ratio for x in profile.legs]
    chosen = next(i for i, x in enumerate(profile.legs) if x.design == leg.design)
    found = band_and_cliffs(
        ratios,
        [x.score for x in profile.legs],
        [x.meets for x in profile.legs],
        chosen,
        [c.l3_ratio for c in profile.cliffs],
    )
    return found or (leg.l3_ratio, leg.l3_ratio)


def recommendation(
    searching: Searching,
    options: DecisionOptions,
    grid: tuple[pd.DataFrame, pd.DataFrame],
    executor: Executor | None = None,
) -> Recommendation:
    """The recommended leg, your lengths re-posed, the band and its cliffs.

    Args:
        searching: What every search measures (the study, the metrics, your design).
        options: The allowed coxa ratios and the constraint.
        grid: The study grid's ranking at your posture (:func:`grid_ranking`): peaks, scores.
        executor: Where the searches run.

    Raises:
        NothingToRecommend: No allowed leg meets the constraint.

    """
    reposed, searched, count = recommend(searching, options, executor)
    legs = searching.legs()
    legs.know((reposed, *searched))
    settled_legs = [settled(legs, leg, searching.l3_range) for leg in searched if leg.ranked]
    if not settled_legs:
        raise NothingToRecommend(
            f"no allowed leg {searching.constraint.describe()} "
            f"({options.describe_candidates()}): nothing to recommend"
        )
    best, profile = max(settled_legs, key=lambda found: found[0].score)
    return Recommendation(
        best=best,
        reposed=reposed,
        yours=searching.yours,
        l3_band=band_of(best, profile),
        cliffs=profile.cliffs,
        searched=searched,
        constraint=searching.constraint,
        peaks=grid[0],
        scores=grid[1],
        evaluations=count + legs.measured,
    )


# -- the study's grid, at your posture -------------------------------------------------------


def grid_ranking(
    average_map: AverageManipulabilityMap,
    study: pd.DataFrame,
    reference: Metrics,
    constraint: WalkingConstraint,
    total: float,
) -> tuple[pd.DataFrame, pd.DataFrame]:
    """The study's grid ranked by the rule at your posture: (peaks, scores).

    Args:
        average_map: w_A on the grid (its ratios define the grid).
        study: The study on the same grid (columns ``fb``, the walking payload capacity
            and ``walks``).
        reference: Your design's metrics.
        constraint: What a ranked leg must do.
        total: The leg length [m].

    """
    r1, r3 = average_map.l1_ratios, average_map.l3_ratios
    l2 = (1 - r1[:, None] - r3[None, :]) * total
    area = np.where(l2 > 0, improved_area_closed_form(l2, r3[None, :] * total), np.nan)
    met = constraint.met_rows(study).astype(float)
    values = np.stack(
        [
            area,
            average_map.improved,
            _study_map(study, RANKED_METRICS[2].name, r1, len(r3)),
        ],
        axis=-1,
    )
    meets = _study_map(study.assign(meets=met), "meets", r1, len(r3)) == 1
    ranked = np.where(meets[..., None], values, np.nan)
    grid_scores = scores(ranked, reference)
    return _peaks(r1, r3, ranked, grid_scores), _scores(r1, r3, values, meets, reference,
                                                         grid_scores)  # fmt: skip


def _study_map(study: pd.DataFrame, column: str, l1_ratios: ArrayF, width: int) -> ArrayF:
    """A study column on the (coxa, tibia) grid: each coxa ratio's rows in tibia order."""
    values = np.full((len(l1_ratios), width), np.nan)
    if column in study:
        for i, ratio in enumerate(l1_ratios):
            values[i] = study.loc[np.isclose(study["l1_ratio"], ratio), column].to_numpy(float)
    return values


def _peaks(r1: ArrayF, r3: ArrayF, values: ArrayF, grid_scores: ArrayF) -> pd.DataFrame:
    """Per coxa ratio: where each metric and the score peak, and the best score."""
    rows = []
    for i, ratio in enumerate(r1):
        row: dict[str, float] = {"l1_ratio": float(ratio)}
        for k, spec in enumerate(RANKED_METRICS):
            row[f"{spec.name}_peak_l3_ratio"] = _peak(r3, values[i, :, k])
        row["score_peak_l3_ratio"] = _peak(r3, grid_scores[i])
        finite = grid_scores[i][np.isfinite(grid_scores[i])]
        row["best_score"] = float(finite.max()) if finite.size else float("nan")
        rows.append(row)
    return pd.DataFrame(rows)


def _scores(
    r1: ArrayF,
    r3: ArrayF,
    values: ArrayF,
    meets: npt.NDArray[np.bool_],
    reference: Metrics,
    grid_scores: ArrayF,
) -> pd.DataFrame:
    """Every grid leg: ratios, each metric, each relative to yours, the constraint, the score."""
    grid1, grid3 = np.meshgrid(r1, r3, indexing="ij")
    relative = relative_values(values, reference)
    return pd.DataFrame(
        {
            "l1_ratio": grid1.ravel(),
            "l3_ratio": grid3.ravel(),
            **{spec.name: values[..., k].ravel() for k, spec in enumerate(RANKED_METRICS)},
            **{
                f"{spec.name}_relative": relative[..., k].ravel()
                for k, spec in enumerate(RANKED_METRICS)
            },
            "meets": meets.ravel(),
            "score": grid_scores.ravel(),
        }
    )


def _peak(ratios: ArrayF, values: ArrayF) -> float:
    if np.all(np.isnan(values)):
        return float("nan")
    return float(ratios[int(np.nanargmax(values))])
