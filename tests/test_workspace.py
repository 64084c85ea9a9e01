"""Workspace: Monte Carlo cloud, planar areas against eq 16 and an independent integral."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from hexaleg import IMPROVED_LIMITS, WORKSPACE_LIMITS, HexapodDesign, foot_position
from hexaleg.swing.workspace import (
    analyze_workspace,
    improved_area_by_l3_ratio,
    improved_area_closed_form,
    monte_carlo_workspace,
    planar_workspace,
)


def test_monte_carlo_is_seeded_within_limits_and_equals_the_model(default_design, leg_model):
    cloud = monte_carlo_workspace(default_design, samples=500, seed=3)
    again = monte_carlo_workspace(default_design, samples=500, seed=3)
    np.testing.assert_array_equal(cloud.points, again.points)
    assert WORKSPACE_LIMITS.contains(cloud.theta).all()
    np.testing.assert_allclose(cloud.points, leg_model.foot_positions(cloud.theta), atol=1e-12)
    assert np.all(cloud.lower_bound <= cloud.points) and np.all(cloud.points <= cloud.upper_bound)


def test_monte_carlo_respects_the_coupled_knee(default_design):
    cloud = monte_carlo_workspace(default_design, samples=2000, seed=1, limits=IMPROVED_LIMITS)
    assert IMPROVED_LIMITS.contains(cloud.theta).all()


def test_monte_carlo_cloud_lies_inside_the_planar_workspace_when_rotated(default_design):
    cloud = monte_carlo_workspace(default_design, samples=3000, seed=2)
    radial = np.hypot(cloud.points[:, 0], cloud.points[:, 1])
    ws = planar_workspace(default_design.lengths, WORKSPACE_LIMITS)
    from matplotlib.path import Path

    inside = Path(ws.boundary).contains_points(np.c_[radial, cloud.points[:, 2]], radius=1e-9)
    assert inside.mean() > 0.995  # boundary points may fall either side of the polygon


def _area_by_change_of_variables(lengths, limits):
    """Independent oracle: ∫∫ |det J_planar| dθ3 dθ2 = ∫∫ l2·l3·|sin θ3| (one knee branch)."""
    _, l2, l3 = lengths
    value, _ = integrate.dblquad(
        lambda t3, t2: l2 * l3 * abs(math.sin(t3)),
        limits.theta2[0],
        limits.theta2[1],
        lambda t2: float(limits.knee_lower(t2)),
        lambda t2: limits.theta3[1],
        epsabs=1e-13,
        epsrel=1e-12,
    )
    return value


@pytest.mark.parametrize("lengths", [(0.2, 0.4, 0.4), (0.05, 0.3, 0.65), (0.1, 0.7, 0.2)])
def test_rectangular_area_equals_an_independent_integral(lengths):
    area = planar_workspace(lengths, WORKSPACE_LIMITS).area
    assert area == pytest.approx(_area_by_change_of_variables(lengths, WORKSPACE_LIMITS), rel=1e-10)
    # and the exact integral: l2·l3·Δθ2·(1 − cos θ3_min)
    exact = lengths[1] * lengths[2] * (2 * math.pi / 3) * (1 - math.cos(-3 * math.pi / 4))
    assert area == pytest.approx(exact, rel=1e-12)


def test_improved_area_equals_eq16_for_random_lengths():
    rng = np.random.default_rng(21)
    for l1, l2, l3 in rng.uniform(0.02, 1.0, size=(25, 3)):
        area = planar_workspace((l1, l2, l3), IMPROVED_LIMITS).area
        assert area == pytest.approx(improved_area_closed_form(l2, l3), rel=1e-10)


def test_boundary_polygon_is_consistent_with_the_area(default_design):
    ws = planar_workspace(default_design.lengths, IMPROVED_LIMITS, points_per_edge=2000)
    x, z = ws.boundary[:, 0], ws.boundary[:, 1]
    shoelace = 0.5 * np.sum(x * np.roll(z, -1) - np.roll(x, -1) * z)
    assert shoelace > 0  # counter-clockwise
    assert shoelace == pytest.approx(ws.area, rel=1e-5)  # polygon converges as O(h²)
    corner = foot_position(default_design.lengths, [0, -np.pi / 3, -np.pi / 6])[[0, 2]]
    assert np.linalg.norm(ws.boundary - corner, axis=1).min() < 1e-12  # a domain corner


@pytest.mark.slow  # a sweep of improved workspaces
def test_area_is_largest_at_equal_femur_and_tibia():
    for l1_ratio in (0.05, 0.1, 0.15, 0.2):
        l3_ratios = np.linspace(0.1, 0.85 - l1_ratio, 301)
        areas = improved_area_by_l3_ratio(l1_ratio, l3_ratios, 1.0, IMPROVED_LIMITS)
        best = l3_ratios[np.argmax(areas)]
        assert best == pytest.approx((1 - l1_ratio) / 2, abs=l3_ratios[1] - l3_ratios[0])


def test_area_falls_as_the_coxa_grows():
    areas = [
        planar_workspace((r, (1 - r) / 2, (1 - r) / 2), IMPROVED_LIMITS).area
        for r in (0.05, 0.10, 0.15, 0.20)
    ]
    assert areas == sorted(areas, reverse=True)


def test_both_knee_branches_are_refused():
    from hexaleg import JointLimits
    from hexaleg.exceptions import HexalegError

    with pytest.raises(HexalegError, match="both knee branches"):
        planar_workspace((0.2, 0.4, 0.4), JointLimits((-1, 1), (-1, 1), (-1, 0.5)))


def test_analysis_summary_has_the_documented_keys():
    summary = analyze_workspace(HexapodDesign(), samples=100).to_dict()
    assert set(summary["area"]) == {"improved", "improved_closed_form", "rectangular"}
    assert summary["monte_carlo"]["samples"] == 100
    assert summary["design"]["l1"] == 0.2


def test_coxa_series_areas_follow_eq16_and_peak_at_equal_femur_and_tibia(default_design):
    from hexaleg.swing.workspace import coxa_series

    series = coxa_series(default_design, (0.05, 0.2))
    for ratio, ws in zip(series.l1_ratios, series.workspaces, strict=True):
        half = (1 - ratio) * default_design.leg_length / 2
        assert ws.area == pytest.approx(2 * np.pi * half * half / 3, rel=1e-6)  # eq 16
    l2 = (1 - series.fixed_l1_ratio - series.l3_ratios) * default_design.leg_length
    np.testing.assert_allclose(
        series.areas, 2 * np.pi * l2 * series.l3_ratios * default_design.leg_length / 3, rtol=1e-6
    )
