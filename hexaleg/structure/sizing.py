"""Sizing the legs' tubes: the lightest on a grid that holds every standing case.

The tubes come from a grid (:mod:`.grid`: D on a 1 mm grid from 4 to 120 mm, walls in
0.5 mm steps, D/t ≤ 50). For given loads the choice is exact on the grid: each segment's
tubes that keep every ratio ≤ 1 (:mod:`.stresses`) are reduced to those no lighter tube
is as stiff as (the others cannot be lighter and still hold the deflection), and the
triple of least mass Σ ρ·A·l whose feet deflect within the limit in every standing case
is searched among them, exhaustively over the cases that bind (a case is added when the
best triple so far breaks it; a triple found to hold first bounds the search).

A tube's mass changes the loads (its weight, and the feet's forces), so sizing iterates:
the loads with the grid's lightest tubes, the lightest tubes that hold them, the loads
with those, ... until the tubes chosen are the tubes that loaded them
(:attr:`SizedStructure.iterations` rounds, :data:`MAX_ITERATIONS` at most). The loads so
grow from below; hexaleg's tests hold the tubes settled on against every triple of a
small grid checked under its own loads. With the min-norm distribution a round's loads
are read off their affine model in the three segments' masses (:mod:`.affine`): exact, not
an estimate (the loads are affine in those masses), so the tubes settled on are checked
with them (:func:`size_for_cases`; hexaleg's tests hold both to a model built with the tubes).
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF, Distribution, FlexibilityMode, StanceSet
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import ParameterError
from hexaleg.leg_structure import Structure, Tube
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.extremes import Extreme
from hexaleg.stance.flexibility import flexibility
from hexaleg.stance.geometry import stance_legs
from hexaleg.statics.forces import DEFAULT_FRICTION, Payload
from hexaleg.structure.affine import affine_terms
from hexaleg.structure.check import StructureCheck
from hexaleg.structure.deflection import foot_deflections
from hexaleg.structure.grid import DEFAULT_GRID, TubeGrid
from hexaleg.structure.standing import StandingCases, standing_cases, standing_terms
from hexaleg.structure.stresses import section_loads, stress_ratio, tube_stresses

MAX_ITERATIONS = 30
"""Most rounds of loads and tubes before sizing gives up settling."""


class SizingWarning(UserWarning):
    """Sizing found no tubes on its grid that hold every case: the strongest are kept."""


@dataclass(frozen=True, eq=False)
class SizedStructure:
    """The tubes sizing chose, and the structure checked with them.

    Attributes:
        design: The design with the chosen tubes.
        check: Its structure in every standing case, with its own loads.
        iterations: Rounds of loads and tubes until the tubes settled.
        settled: Whether they settled (else :data:`MAX_ITERATIONS` rounds ran).
        found: Whether some tubes on the grid hold every case (else the strongest are kept).
        grid: The grid chosen from.

    """

    design: HexapodDesign
    check: StructureCheck
    iterations: int
    settled: bool
    found: bool
    grid: TubeGrid

    @property
    def structure(self) -> Structure:
        """The structure with the chosen tubes."""
        assert self.design.structure is not None
        return self.design.structure

    def to_dict(self) -> dict[str, Any]:
        """How sizing went (the tubes are the check's)."""
        return {
            "iterations": self.iterations,
            "settled": self.settled,
            "found": self.found,
            "grid": self.grid.to_dict(),
        }


def size_structure(
    design: HexapodDesign,
    *,
    payload: Payload | None = None,
    slope: float = 0.0,
    friction: float = DEFAULT_FRICTION,
    stance: StanceSet | Sequence[str] = "all",
    distribution: Distribution = "min-norm",
    mode: FlexibilityMode = "axis",
    model: HexapodModel | None = None,
    grid: TubeGrid | None = None,
    extremes: Sequence[Extreme] | None = None,
) -> SizedStructure:
    """The lightest tubes of ``grid`` that hold every standing case of ``design``.

    Args:
        design: A design with a ``[structure]`` (its material, safety factor and limit;
            its tubes, if any, are replaced).
        payload: The payload on the body in every case (none by default).
        slope: The slope [rad] stood on in every heading (0: level ground only).
        friction: Friction coefficient μ [-].
        stance: Stance legs.
        distribution: How the feet share the load.
        mode: Which flexibility extremes: axis-locked or free-coupled.
        model: ``design``'s model (hexaleg's template), if already built.
        grid: The tubes to choose from (:class:`TubeGrid`'s defaults if omitted).
        extremes: The design's flexibility extremes of ``stance`` and ``mode``, if already
            found (an evaluation's; they depend on the geometry only).

    """
    if design.structure is None:
        raise ParameterError("structure", None, "the design has no [structure] to size")
    grid = DEFAULT_GRID if grid is None else grid
    model = HexapodModel(design) if model is None else model
    legs = stance_legs(model, stance)
    if extremes is None:
        extremes = flexibility(design, mode, legs, model).extremes
    cases = standing_cases(model, legs, extremes, payload, slope, friction, distribution)
    return size_for_cases(design, cases, model, grid)


def size_for_cases(
    design: HexapodDesign,
    cases: StandingCases,
    model: HexapodModel,
    grid: TubeGrid,
    *,
    affine: bool = True,
) -> SizedStructure:
    """The lightest tubes of ``grid`` that hold ``cases`` (see :func:`size_structure`).

    With the min-norm distribution (and ``affine``) the rounds read the loads off
    :func:`affine_terms` (measured once at ``model``'s masses, with their exact
    derivatives: no new Pinocchio model a round), and so does the check of the tubes they
    settle on. Another distribution has real loads every round (their own model's
    :func:`standing_terms`), as with ``affine=False``: the same tubes and check, slower.
    """
    structure = design.structure
    if structure is None:
        raise ParameterError("structure", None, "the design has no [structure] to size")
    limit = structure.limit(design.leg_length)
    active: list[int] = []

    def choose(terms: tuple[ArrayF, ArrayF]) -> tuple[tuple[int, int, int], bool]:
        loads = section_loads(terms[0])
        best = choose_tubes(loads, terms[1], structure, design.lengths, limit, grid, active)
        return (_strongest(loads, structure, grid), False) if best is None else (best, True)

    def loaded(chosen: tuple[int, int, int]) -> tuple[ArrayF, ArrayF]:
        sized = _with_structure(design, structure.with_tubes(_tubes(grid, chosen)))
        return standing_terms(model.with_design(sized), cases)

    load = loaded
    if affine and cases.distribution == "min-norm":
        terms = affine_terms(model, cases)
        densities = [structure.material.density * length for length in design.lengths]

        def exact(chosen: tuple[int, int, int]) -> tuple[ArrayF, ArrayF]:
            area = grid.sections[1][list(chosen)]
            return terms.at([d * a for d, a in zip(densities, area, strict=True)])

        load = exact
    lightest = int(np.argmin(grid.sections[1]))
    rounds = _rounds(load, choose, (lightest, lightest, lightest), MAX_ITERATIONS)
    final = structure.with_tubes(_tubes(grid, rounds.chosen))
    # unsettled, the last loads were the tubes' before: check the last tubes' own
    wrenches, integrals = rounds.terms if rounds.settled else load(rounds.chosen)
    deflections = np.linalg.norm(foot_deflections(integrals, final), axis=-1)
    check = StructureCheck(
        final, design.lengths, model.leg_names, cases.names, wrenches, deflections, limit
    )
    return SizedStructure(
        _with_structure(design, final), check, rounds.iterations, rounds.settled, rounds.found, grid
    )


@dataclass(frozen=True, eq=False)
class _Rounds:
    """Where rounds of loads and tubes ended.

    Attributes:
        chosen: The last tubes chosen (grid indices).
        settled: Whether they are the tubes that loaded them.
        found: Whether tubes of the grid held the last loads (else the strongest are chosen).
        iterations: The rounds run.
        terms: The last loads (wrenches, deflection integrals): ``chosen``'s if settled.

    """

    chosen: tuple[int, int, int]
    settled: bool
    found: bool
    iterations: int
    terms: tuple[ArrayF, ArrayF]


def _rounds(
    loads: Callable[[tuple[int, int, int]], tuple[ArrayF, ArrayF]],
    choose: Callable[[tuple[ArrayF, ArrayF]], tuple[tuple[int, int, int], bool]],
    chosen: tuple[int, int, int],
    most: int,
) -> _Rounds:
    """Load ``chosen``, choose the tubes that hold the loads, ... until they settle."""
    iterations, settled, found = 0, False, True
    terms = loads(chosen)
    while True:
        iterations += 1
        best, found = choose(terms)
        settled, chosen = best == chosen, best
        if settled or iterations >= most:
            return _Rounds(chosen, settled, found, iterations, terms)
        terms = loads(chosen)


def _with_structure(design: HexapodDesign, structure: Structure) -> HexapodDesign:
    """``design`` with another structure, without checking its other fields again.

    The structure checks itself and no other field depends on it; a design's own checks
    (its mounts, its footholds) cost a millisecond a round.
    """
    changed = copy.copy(design)
    object.__setattr__(changed, "structure", structure)
    return changed


def _tubes(grid: TubeGrid, chosen: tuple[int, int, int]) -> tuple[Tube, Tube, Tube]:
    return (grid.tube(chosen[0]), grid.tube(chosen[1]), grid.tube(chosen[2]))


def segment_ratios(loads: ArrayF, structure: Structure, grid: TubeGrid) -> ArrayF:
    """Each grid tube's worst ratio (3, n) per segment, over every case and leg [-]."""
    outer = grid.sections[0]
    every = np.arange(len(outer))
    return np.stack(
        [_worst_ratio(loads[:, :, s].reshape(-1, 3), every, structure, grid) for s in range(3)]
    )


def segment_holds(loads: ArrayF, structure: Structure, grid: TubeGrid) -> npt.NDArray[np.bool_]:
    """Whether each grid tube's worst ratio is at most 1 (3, n): ``segment_ratios(...) <= 1``.

    Bit for bit, and cheaper: a tube's ratio grows with each of |N|, |M_b| and |T| (so do
    its floating-point operations), so its worst lies between that of the loads largest
    in one of them and that of their three maxima together; only the tubes those two do
    not decide are loaded with every case and leg.
    """
    every = np.arange(len(grid.sections[0]))
    rows = np.abs(loads.reshape(-1, 3, 3)).swapaxes(0, 1)  # (3 segments, R, 3)
    peaks = rows.max(axis=1)  # each segment's three maxima (3, 3)
    largest = rows[np.arange(3)[:, None], np.argmax(rows, axis=1)]  # their loads (3, 3, 3)
    high = _worst_ratio(peaks[:, None], every, structure, grid)  # (3, n)
    low = _worst_ratio(largest, every, structure, grid)
    out = high <= 1
    for segment in range(3):
        unsure = np.flatnonzero((low[segment] <= 1) & (high[segment] > 1))
        if unsure.size:
            worst = _worst_ratio(rows[segment], unsure, structure, grid)
            out[segment, unsure] = worst <= 1
    return out


def _worst_ratio(
    rows: ArrayF, tubes: npt.NDArray[np.intp], structure: Structure, grid: TubeGrid
) -> ArrayF:
    """The worst ratio [-] of section loads ``rows`` (..., R, 3) on each of ``tubes`` (n,).

    Leading axes of ``rows`` (sets of loads, each its own worst) lead the result (..., n).
    """
    outer, area, moment = (values[tubes, None] for values in grid.sections)
    _, tau, von_mises = tube_stresses(rows[..., None, :, :], outer, area, moment)
    worst: ArrayF = stress_ratio(von_mises, tau, structure).max(axis=-1)
    return worst


def _strongest(loads: ArrayF, structure: Structure, grid: TubeGrid) -> tuple[int, int, int]:
    """Each segment's grid tube of the least worst ratio (when none holds)."""
    ratios = segment_ratios(loads, structure, grid)
    coxa, femur, tibia = (int(np.argmin(r)) for r in ratios)
    return (coxa, femur, tibia)


def choose_tubes(
    loads: ArrayF,
    integrals: ArrayF,
    structure: Structure,
    lengths: tuple[float, float, float],
    limit: float,
    grid: TubeGrid,
    active: list[int] | None = None,
) -> tuple[int, int, int] | None:
    """The grid tubes (coxa, femur, tibia) of least mass that hold these loads, if any.

    Args:
        loads: Section loads (K, legs, 3, 3) [N, N·m, N·m].
        integrals: Deflection integrals (K, legs, 3, 3) [N·m³] (:mod:`.deflection`).
        structure: The material, safety factor.
        lengths: Segment lengths [m].
        limit: The foot's deflection limit [m].
        grid: The tubes (indices into its :attr:`~TubeGrid.sections`).
        active: The cases (flat index of case and leg) that bound the deflection last
            time, searched from the start; the cases found binding are added to it.

    """
    _, area, moment = grid.sections
    holds = segment_holds(loads, structure, grid)
    fronts = [_stiffest_for_mass(np.flatnonzero(ok), area, moment) for ok in holds]
    if any(len(front) == 0 for front in fronts):
        return None
    density = structure.material.density
    masses = [density * area[f] * length for f, length in zip(fronts, lengths, strict=True)]
    vectors = integrals.reshape(-1, 3, 3) / structure.material.youngs_modulus  # (C, 3, 3)
    per_segment = vectors.transpose(1, 0, 2).reshape(3, -1)  # (3, C·3)
    inverse = [1.0 / moment[f] for f in fronts]
    bound = _bound(masses, inverse, per_segment, limit)
    if bound is not None:  # no triple heavier than a feasible one can be the lightest
        floor = sum(m[0] for m in masses)
        kept = [np.flatnonzero(m - m[0] <= bound - floor) for m in masses]
        fronts = [f[k] for f, k in zip(fronts, kept, strict=True)]
        masses = [m[k] for m, k in zip(masses, kept, strict=True)]
        inverse = [x[k] for x, k in zip(inverse, kept, strict=True)]
    active = [] if active is None else active
    while True:
        best = _least_mass(masses, inverse, vectors[active], limit)
        if best is None:
            return None
        x = np.array([[inverse[s][best[s]] for s in range(3)]])
        bent = _bends(per_segment, x)[0]
        worst = int(np.argmax(bent))
        if bent[worst] <= limit:
            return (int(fronts[0][best[0]]), int(fronts[1][best[1]]), int(fronts[2][best[2]]))
        active.append(worst)


def _bends(per_segment: ArrayF, inverse: ArrayF) -> ArrayF:
    """Each foot's deflection [m] in each case (S, C) of S triples' 1/I (S, 3) [m⁻⁴].

    ``per_segment`` (3, C·3): each case's deflection vector per unit 1/I of each segment
    (the deflection integrals over E), the cases' side by side.
    """
    bent = (inverse @ per_segment).reshape(len(inverse), -1, 3)  # (S, C, 3)
    found: ArrayF = np.sqrt((bent * bent).sum(axis=-1))
    return found


def _bound(
    masses: list[ArrayF], inverse: list[ArrayF], per_segment: ArrayF, limit: float
) -> float | None:
    """The mass of some triple that holds every case, if one is found, else ``None``.

    Each front is walked up together, at the same share of its length: the first share
    whose triple holds bounds the lightest from above, found to 1/4096 of the way by
    three rounds of 16 shares at once (each round within the last one's step).
    """
    ends = np.array([len(m) - 1 for m in masses])

    def triples(shares: ArrayF) -> npt.NDArray[np.intp]:  # (S, 3)
        return np.minimum(np.round(shares[:, None] * ends), ends).astype(np.intp)

    def holding(index: npt.NDArray[np.intp]) -> npt.NDArray[np.bool_]:  # (S,)
        x = np.stack([inverse[s][index[:, s]] for s in range(3)], axis=-1)  # (S, 3)
        return _bends(per_segment, x).max(axis=1) <= limit

    if not holding(triples(np.ones(1)))[0]:
        return None
    low, high = 0.0, 1.0
    for _ in range(3):
        shares = low + (high - low) * np.arange(1, 17) / 16
        held = holding(triples(shares))
        if not held.any():  # the last share is high, which holds (kept, whatever rounding)
            break
        first = int(np.argmax(held))
        low, high = (low if first == 0 else float(shares[first - 1])), float(shares[first])
    best = triples(np.array([high]))[0]
    return float(sum(m[i] for m, i in zip(masses, best, strict=True)))


def _stiffest_for_mass(
    indices: npt.NDArray[np.intp], area: ArrayF, moment: ArrayF
) -> npt.NDArray[np.intp]:
    """Of ``indices``, by area, those stiffer (I) than every lighter one."""
    order = indices[np.lexsort((-moment[indices], area[indices]))]
    stiffest = np.maximum.accumulate(moment[order])
    kept = np.ones(len(order), dtype=bool)
    kept[1:] = moment[order][1:] > stiffest[:-1]
    return order[kept]


def _least_mass(
    masses: list[ArrayF], inverse: list[ArrayF], vectors: ArrayF, limit: float
) -> tuple[int, int, int] | None:
    """Indices into each front of the lightest triple whose feet deflect within ``limit``.

    Args:
        masses: Each segment's front's masses, ascending [kg].
        inverse: Their 1/I, descending [m⁻⁴].
        vectors: Each active case's deflection per unit 1/I of each segment (A, 3, 3).
        limit: The deflection limit [m].

    A case's deflection is ‖Σ_s x_s·v_s‖, x_s a segment's 1/I: for a coxa and a femur,
    ‖b + x·c‖ with x the tibia's is within the limit on an interval of x (a convex
    quadratic's sublevel set), written with the products v_s·v_t; the lightest tibia is
    the least stiff one inside every case's interval.

    """
    if len(vectors) == 0:
        return (0, 0, 0)
    gram = np.einsum("aik,ajk->aij", vectors, vectors)[:, :, :, None, None]  # (A, 3, 3, 1, 1)
    xc, xf = inverse[0][:, None], inverse[1][None, :]  # (C, 1), (1, F)
    bb = gram[:, 0, 0] * xc * xc + 2 * gram[:, 0, 1] * xc * xf + gram[:, 1, 1] * xf * xf
    bc = gram[:, 0, 2] * xc + gram[:, 1, 2] * xf  # (A, C, F)
    cc = np.broadcast_to(gram[:, 2, 2], bb.shape)
    square = bc * bc - cc * (bb - limit * limit)
    with np.errstate(divide="ignore", invalid="ignore"):
        root = np.sqrt(np.maximum(square, 0.0))
        low = np.where(cc > 0, (-bc - root) / cc, np.where(bb <= limit * limit, -np.inf, np.inf))
        high = np.where(cc > 0, (-bc + root) / cc, np.where(bb <= limit * limit, np.inf, -np.inf))
    empty = (cc > 0) & (square < 0)
    low, high = np.where(empty, np.inf, low).max(axis=0), np.where(empty, -np.inf, high).min(axis=0)
    descending = -inverse[2]  # ascending: the tibia's front from light (large 1/I) to stiff
    first = np.searchsorted(descending, -high, side="left")  # first tibia with 1/I ≤ high
    last = np.searchsorted(descending, -low, side="right") - 1  # last with 1/I ≥ low
    ok = (first <= last) & (first < len(descending))
    if not ok.any():
        return None
    tibia = masses[2][np.minimum(first, len(descending) - 1)]
    total = np.where(ok, masses[0][:, None] + masses[1][None, :] + tibia, np.inf)
    i, j = np.unravel_index(int(np.argmin(total)), total.shape)
    return (int(i), int(j), int(first[i, j]))
