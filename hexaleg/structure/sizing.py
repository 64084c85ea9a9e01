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
from hexaleg.structure.tube_kernel import holding_tubes, lightest_triple

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

    def choose(
        terms: tuple[ArrayF, ArrayF], loading: tuple[int, int, int]
    ) -> tuple[tuple[int, int, int], bool]:
        loads = section_loads(terms[0])
        best = choose_tubes(
            loads, terms[1], structure, design.lengths, limit, grid, active, loading
        )
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
    choose: Callable[
        [tuple[ArrayF, ArrayF], tuple[int, int, int]], tuple[tuple[int, int, int], bool]
    ],
    chosen: tuple[int, int, int],
    most: int,
) -> _Rounds:
    """Load ``chosen``, choose the tubes that hold the loads, ... until they settle."""
    iterations, settled, found = 0, False, True
    terms = loads(chosen)
    while True:
        iterations += 1
        best, found = choose(terms, chosen)
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

    Compiled (:func:`~.tube_kernel.holding_tubes`): each tube's loads until one breaks it.
    """
    rows = np.ascontiguousarray(np.abs(loads.reshape(-1, 3, 3)).swapaxes(0, 1))  # (3, R, 3)
    shear = structure.material.shear_strength
    return holding_tubes(
        rows,
        *grid.sections,
        structure.allowed_stress,
        structure.safety_factor,
        0.0 if shear is None else shear,
    )


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
    hint: tuple[int, int, int] | None = None,
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
        hint: Tubes likely to hold (the ones that loaded them, in sizing's rounds): if
            they do, their mass bounds the search (:func:`~.tube_kernel.lightest_triple`).

    """
    _, area, moment = grid.sections
    holds = segment_holds(loads, structure, grid)
    density = structure.material.density
    vectors = integrals.reshape(-1, 3, 3) / structure.material.youngs_modulus  # (C, 3, 3)
    active = [] if active is None else active
    triple, added = lightest_triple(
        holds,
        grid.by_area,
        area,
        moment,
        np.array([density * length for length in lengths]),
        np.ascontiguousarray(vectors),
        limit,
        np.array(active, dtype=np.int64),
        np.array((-1, -1, -1) if hint is None else hint, dtype=np.int64),
    )
    active.extend(int(case) for case in added)
    if triple[0] < 0:
        return None
    return (int(triple[0]), int(triple[1]), int(triple[2]))
