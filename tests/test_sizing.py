"""Sizing the tubes: never heavier than any triple of its grid that holds its own loads.

The brute force here evaluates every triple of a small grid under the loads its own masses
make. The standing wrenches and deflection integrals are affine in the three segments'
masses (the tubes are uniform, centred mid-segment; the minimum-norm feet forces are linear
in the robot's weight and its moment), so four evaluations give every triple's, and a
fifth checks that they are; stresses, ratios and deflections are then computed here with
the brief's formulas, for every triple at once.
"""

from __future__ import annotations

import itertools
import math
import pickle

import numpy as np
import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.exceptions import ParameterError
from hexaleg.leg_structure import Structure, Tube
from hexaleg.materials import shipped_materials
from hexaleg.statics.forces import Payload
from hexaleg.structure.affine import affine_terms
from hexaleg.structure.grid import DEFAULT_GRID, TubeGrid
from hexaleg.structure.sizing import choose_tubes, segment_holds, size_for_cases, size_structure
from hexaleg.structure.standing import check_standing, standing_cases, standing_terms

CATALOG = shipped_materials()
SMALL = TubeGrid(
    smallest_diameter=0.010,
    largest_diameter=0.050,
    diameter_step=0.010,
    wall_step=0.002,
    max_slenderness=30.0,
)


def seeded(seed):
    rng = np.random.default_rng(seed)
    while True:
        material = CATALOG.entries[rng.integers(len(CATALOG) - 1)]  # not the printed polymer
        try:
            return HexapodDesign(
                l1=rng.uniform(0.05, 0.25),
                l2=rng.uniform(0.2, 0.5),
                l3=rng.uniform(0.2, 0.5),
                body_mass=rng.uniform(5, 150),
                nominal_angles=(0.0, rng.uniform(-0.3, 0.3), rng.uniform(-2.0, -0.8)),
                structure=Structure(
                    material,
                    size=True,
                    safety_factor=rng.uniform(1.5, 4.0),
                    deflection_limit=rng.uniform(0.002, 0.05),
                ),
            )
        except ValueError:
            continue


def evaluate(design, model, cases, tubes):
    """The wrenches and deflection integrals with these (coxa, femur, tibia) tubes."""
    structured = design.replace(structure=design.structure.with_tubes(tubes))
    return standing_terms(model.with_design(structured), cases)


def brute_force(design, model, cases):
    """(mass, feasible) of every triple of SMALL's tubes, each under its own loads."""
    structure, lengths = design.structure, np.array(design.lengths)
    outer, wall = SMALL.tubes
    tubes = [Tube(float(d), float(t)) for d, t in zip(outer, wall, strict=True)]
    inner = outer - 2 * wall
    area = math.pi / 4 * (outer**2 - inner**2)
    moment = math.pi / 64 * (outer**4 - inner**4)
    density = structure.material.density
    base = (tubes[0], tubes[0], tubes[0])
    base_mass = density * area[0] * lengths
    w0, d0 = evaluate(design, model, cases, base)
    slopes = []
    for s in range(3):  # one segment at a time heavier: the change per kilogram
        heavier = list(base)
        heavier[s] = tubes[-1]
        w, d = evaluate(design, model, cases, tuple(heavier))
        step = density * (area[-1] - area[0]) * lengths[s]
        slopes.append(((w - w0) / step, (d - d0) / step))
    probe = (tubes[5], tubes[-3], tubes[9])  # affine indeed: a triple predicted and computed
    probe_mass = density * np.array([area[5], area[-3], area[9]]) * lengths - base_mass
    w, d = evaluate(design, model, cases, probe)
    predicted_w = w0 + sum(m * sw for m, (sw, _) in zip(probe_mass, slopes, strict=True))
    predicted_d = d0 + sum(m * sd for m, (_, sd) in zip(probe_mass, slopes, strict=True))
    np.testing.assert_allclose(w, predicted_w, rtol=0, atol=1e-9 * np.abs(w).max())
    np.testing.assert_allclose(d, predicted_d, rtol=0, atol=1e-9 * np.abs(d).max())

    count = len(tubes)
    index = np.array(list(itertools.product(range(count), repeat=3)))  # (T, 3)
    masses = density * area[index] * lengths  # (T, 3)
    extra = masses - base_mass
    wrenches = w0[None] + np.einsum("ts,s...->t...", extra, np.array([sw for sw, _ in slopes]))
    bends = d0[None] + np.einsum("ts,s...->t...", extra, np.array([sd for _, sd in slopes]))
    allowed = structure.material.yield_strength / structure.safety_factor
    holds = np.ones(len(index), dtype=bool)
    for s in range(3):
        tube = index[:, s]
        w = wrenches[:, :, :, s, :]  # (T, K, 6, 6)
        axial, torsion = np.abs(w[..., 0]), np.abs(w[..., 3])
        bending = np.hypot(w[..., 4], w[..., 5])
        fibre = (outer[tube] / 2)[:, None, None]
        sigma = axial / area[tube][:, None, None] + bending * fibre / moment[tube][:, None, None]
        tau = torsion * fibre / (2 * moment[tube][:, None, None])
        ratio = np.sqrt(sigma**2 + 3 * tau**2) / allowed
        if structure.material.shear_strength is not None:
            ratio = np.maximum(
                ratio, tau * structure.safety_factor / structure.material.shear_strength
            )
        holds &= (ratio <= 1).all(axis=(1, 2))
    stiffness = structure.material.youngs_modulus * moment[index]  # (T, 3)
    deflection = np.linalg.norm(np.einsum("tklsc,ts->tklc", bends, 1 / stiffness), axis=-1)
    holds &= (deflection <= structure.limit(design.leg_length)).all(axis=(1, 2))
    return masses.sum(axis=1), holds, [tuple(tubes[i] for i in triple) for triple in index]


def check_against_brute_force(design, cases):
    model = HexapodModel(design)
    sized = size_for_cases(design, cases, model, SMALL)
    total, holds, triples = brute_force(design, model, cases)
    chosen = sized.structure.tubes
    density = design.structure.material.density
    mass = sum(
        density * tube.area * length for tube, length in zip(chosen, design.lengths, strict=True)
    )
    if not holds.any():
        assert not sized.found and not sized.check.feasible
        return None
    assert sized.found and sized.settled
    assert mass <= total[holds].min() * (1 + 1e-12)  # never heavier than a triple that holds
    assert holds[triples.index(chosen)]  # and it holds under its own loads, by the brute force
    assert sized.check.feasible
    again = check_standing(model.with_design(sized.design), cases)  # the record is the check's
    np.testing.assert_allclose(again.ratios, sized.check.ratios, rtol=1e-12)
    return sized


@pytest.mark.parametrize(
    "seed", [4, 9, pytest.param(2, marks=pytest.mark.slow)]
)  # a stress binds; the deflection binds, with thick walls; the deflection alone
def test_sizing_is_never_heavier_than_any_grid_triple_holding_its_own_loads(seed):
    design = seeded(seed)
    model = HexapodModel(design)
    cases = standing_cases(model, model.leg_names, payload=Payload(5.0))  # the nominal stance
    check_against_brute_force(design, cases)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [1, 5, 7, 8, 13, 14])
def test_sizing_against_brute_force_with_the_extremes_and_a_slope(seed):
    from hexaleg.stance.flexibility import flexibility

    design = seeded(seed)
    model = HexapodModel(design)
    extremes = flexibility(design, "axis", model.leg_names, model).extremes
    cases = standing_cases(model, model.leg_names, extremes, Payload(8.0), math.radians(10))
    check_against_brute_force(design, cases)


def test_sizing_the_default_robot_holds_and_settles_on_the_default_grid():
    design = HexapodDesign(structure=Structure(CATALOG.material("aluminium_6061_t6"), size=True))
    sized = size_structure(design, payload=Payload(20.0), slope=math.radians(10))
    assert sized.found and sized.settled and 2 <= sized.iterations <= 10
    assert sized.check.feasible and sized.check.worst_ratio <= 1
    assert sized.check.deflection <= 0.01 * design.leg_length
    for tube in sized.structure.tubes:
        assert 0.004 <= tube.outer_diameter <= 0.120
        assert tube.outer_diameter / tube.wall <= 50 + 1e-9
        assert round(tube.outer_diameter * 1e3, 6) == round(tube.outer_diameter * 1e3)
        assert round(tube.wall * 2e3, 6) == round(tube.wall * 2e3)  # 0.5 mm steps


def test_a_grid_with_no_tube_that_holds_keeps_the_strongest_and_says_so():
    design = HexapodDesign(
        body_mass=200.0,
        structure=Structure(CATALOG.material("pla_printed"), size=True),
    )
    tiny = TubeGrid(smallest_diameter=0.004, largest_diameter=0.008)
    sized = size_structure(design, grid=tiny)
    assert not sized.found and not sized.check.feasible
    assert sized.check.over_strength  # every segment over its strength is named


def random_tubes(rng):
    """Three tubes of random diameter and wall (a solid rod at times)."""
    outer = rng.uniform(0.008, 0.08, 3)
    return tuple(Tube(float(d), float(rng.uniform(0.0005, 0.5) * d)) for d in outer)


def requirement_cases(design, model, rng, extremes=True):
    """Seeded standing cases: the extremes, a payload somewhere on the body, a slope."""
    from hexaleg.stance.flexibility import flexibility

    found = flexibility(design, "axis", model.leg_names, model).extremes if extremes else []
    payload = Payload(rng.uniform(0, 40), tuple(rng.uniform(-0.1, 0.1, 3)))
    return standing_cases(model, model.leg_names, found, payload, rng.uniform(0, 0.4))


@pytest.mark.parametrize("seed", [3, 6, pytest.param(11, marks=pytest.mark.slow)])
def test_the_affine_terms_are_the_full_computation_at_any_tube_masses(seed):
    # the oracle: the wrenches and deflection integrals of a model built with the tubes
    design = seeded(seed)
    model = HexapodModel(design)
    rng = np.random.default_rng(seed)
    cases = requirement_cases(design, model, rng)
    terms = affine_terms(model, cases)
    for _ in range(3):
        tubes = random_tubes(rng)
        wrenches, integrals = evaluate(design, model, cases, tubes)
        density = design.structure.material.density
        masses = [
            density * t.area * length for t, length in zip(tubes, design.lengths, strict=True)
        ]
        predicted_w, predicted_d = terms.at(masses)
        np.testing.assert_allclose(
            predicted_w, wrenches, rtol=0, atol=1e-9 * np.abs(wrenches).max()
        )
        np.testing.assert_allclose(
            predicted_d, integrals, rtol=0, atol=1e-9 * np.abs(integrals).max()
        )


def test_the_affine_terms_refuse_a_distribution_that_is_not_linear():
    design = seeded(0)
    model = HexapodModel(design)
    cases = standing_cases(model, model.leg_names, distribution="min-torque")
    with pytest.raises(ParameterError, match="min-norm"):
        affine_terms(model, cases)


@pytest.mark.parametrize(
    "seed", [0, 10, *(pytest.param(s, marks=pytest.mark.slow) for s in (12, 15, 16, 17, 18, 19))]
)
def test_sizing_on_the_affine_loads_answers_as_the_real_rounds_do(seed):
    # the oracle: the rounds with a new model and its real loads every round
    design = seeded(seed)
    model = HexapodModel(design)
    cases = requirement_cases(design, model, np.random.default_rng(seed))
    fast = size_for_cases(design, cases, model, DEFAULT_GRID)
    real = size_for_cases(design, cases, model, DEFAULT_GRID, affine=False)
    assert fast.structure.tubes == real.structure.tubes
    assert (fast.iterations, fast.settled, fast.found) == (
        real.iterations,
        real.settled,
        real.found,
    )
    np.testing.assert_allclose(fast.check.ratios, real.check.ratios, rtol=1e-12)
    np.testing.assert_allclose(fast.check.deflections, real.check.deflections, rtol=1e-12)


@pytest.mark.parametrize("seed", range(4))
def test_a_tube_holds_where_its_worst_ratio_over_every_load_is_at_most_one(seed):
    # the oracle: each tube's ratio under each load, by the brief's formulas, here
    rng = np.random.default_rng(seed)
    structure = seeded(seed).structure
    scale = np.array([200.0, 30.0, 5.0]) * 10 ** rng.uniform(-0.5, 1)  # N [N], M_b, T [N·m]
    loads = rng.normal(size=(5, 6, 3, 3)) * scale
    outer, area, moment = DEFAULT_GRID.sections
    magnitude = np.abs(loads)[..., None]  # (5, 6, 3, 3, n)
    sigma = magnitude[..., 0, :] / area + magnitude[..., 1, :] * (outer / 2) / moment
    tau = magnitude[..., 2, :] * (outer / 2) / (2 * moment)
    ratio = np.sqrt(sigma**2 + 3 * tau**2) / structure.allowed_stress
    if structure.material.shear_strength is not None:
        ratio = np.maximum(ratio, tau * structure.safety_factor / structure.material.shear_strength)
    expected = ratio.max(axis=(0, 1)) <= 1  # (3, n)
    assert 0 < expected.sum() < expected.size  # some tubes hold, some do not
    np.testing.assert_array_equal(segment_holds(loads, structure, DEFAULT_GRID), expected)


def test_a_grid_pickles_by_its_fields_and_the_default_one_comes_back_as_itself():
    # a sized design sent back from a worker carries its grid: not its 7 000 tubes
    assert len(DEFAULT_GRID.useful) > 0  # the caches are filled
    assert pickle.loads(pickle.dumps(DEFAULT_GRID)) is DEFAULT_GRID
    assert len(pickle.dumps(DEFAULT_GRID)) < 500
    other = TubeGrid(wall_step=0.001, max_slenderness=30.0)
    back = pickle.loads(pickle.dumps(other))
    assert back == other and back is not DEFAULT_GRID
    np.testing.assert_array_equal(back.sections, other.sections)


MEDIUM = TubeGrid(
    smallest_diameter=0.006,
    largest_diameter=0.040,
    diameter_step=0.002,
    wall_step=0.001,
    max_slenderness=30.0,
)


@pytest.mark.parametrize("seed", range(6))
def test_the_tube_choice_is_the_lightest_triple_by_brute_force_with_or_without_a_hint(seed):
    # the oracle: every triple of a 44-tube grid, its ratios and deflections by the formulas
    rng = np.random.default_rng(100 + seed)
    structure = seeded(seed).structure
    lengths = tuple(rng.uniform(0.05, 0.5, 3))
    loads = rng.normal(size=(3, 6, 3, 3)) * np.array([300.0, 20.0, 3.0]) * 10 ** rng.uniform(0, 1.5)
    integrals = rng.normal(size=(3, 6, 3, 3)) * 10 ** rng.uniform(-2, 0)
    outer, area, moment = MEDIUM.sections
    magnitude = np.abs(loads).reshape(-1, 3, 3)  # (R, segment, 3)
    fibre = outer / 2
    sigma = magnitude[..., 0, None] / area + magnitude[..., 1, None] * fibre / moment
    tau = magnitude[..., 2, None] * fibre / (2 * moment)
    ratio = np.sqrt(sigma**2 + 3 * tau**2) / structure.allowed_stress  # (R, segment, n)
    if structure.material.shear_strength is not None:
        ratio = np.maximum(ratio, tau * structure.safety_factor / structure.material.shear_strength)
    holds = (ratio <= 1).all(axis=0)  # (segment, n)
    index = np.array(list(itertools.product(range(len(area)), repeat=3)))  # (T, 3)
    vectors = integrals.reshape(-1, 3, 3) / structure.material.youngs_modulus  # (C, s, 3)
    bent = np.linalg.norm(np.einsum("csk,ts->tck", vectors, 1 / moment[index]), axis=-1)
    mass = (structure.material.density * area[index] * np.array(lengths)).sum(axis=1)
    strong = holds[0, index[:, 0]] & holds[1, index[:, 1]] & holds[2, index[:, 2]]
    # a limit that binds: the median deflection of the triples strong enough
    limit = float(np.median(bent[strong].max(axis=1))) if strong.any() else 1.0
    feasible = strong & (bent.max(axis=1) <= limit)
    hints = [None, tuple(int(i) for i in index[rng.integers(len(index))])]
    if feasible.any():
        hints.append(tuple(int(i) for i in index[np.flatnonzero(feasible)[-1]]))
    for hint in hints:
        active: list[int] = []
        chosen = choose_tubes(loads, integrals, structure, lengths, limit, MEDIUM, active, hint)
        if not feasible.any():
            assert chosen is None
            continue
        assert chosen is not None
        row = int(np.flatnonzero((index == chosen).all(axis=1))[0])
        assert feasible[row]  # it holds, by the formulas
        assert mass[row] <= mass[feasible].min() * (1 + 1e-12)  # and none is lighter
