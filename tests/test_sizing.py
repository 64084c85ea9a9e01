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

import numpy as np
import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.leg_structure import Structure, Tube
from hexaleg.materials import shipped_materials
from hexaleg.statics.forces import Payload
from hexaleg.structure.grid import TubeGrid
from hexaleg.structure.sizing import size_for_cases, size_structure
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
