"""Free-coupled flexibility: never smaller than axis-locked, and feasible; its table, for each
kind of robot."""

from __future__ import annotations

import itertools
import warnings

import pytest
from conftest import run_cli, small_free_search
from robots import KINDS, KRABY, robot_argv, robot_of
from test_axis_locked import DESIGNS

from hexaleg import HexapodModel
from hexaleg.stance import AXES, FlexibilityWarning, flexibility, free_flexibility

ROBOTS = [
    *(pytest.param("template", d, id=f"l={d.l1:.2f},{d.l2:.2f},{d.l3:.2f}") for d in DESIGNS[:3]),
    pytest.param("kraby", None, id="kraby"),
]
"""Hexaleg's template at three designs, and a robot file (each leg its own general leg)."""


@pytest.mark.parametrize(("kind", "design"), ROBOTS)
@pytest.mark.parametrize("stance", ["all", "tripod"])
def test_free_coupled_is_never_smaller_than_axis_locked(kind, design, stance):
    robot = robot_of(kind, design)
    design, model = robot.design, robot.model
    locked = flexibility(design, "axis", stance, model)
    with warnings.catch_warnings():  # convergence flags have their own test below
        warnings.simplefilter("ignore", FlexibilityWarning)
        free = free_flexibility(design, stance, model)
    for axis in AXES:
        assert free.ranges[axis] >= locked.ranges[axis] - 1e-12
    assert free.fb >= locked.fb
    for mine, theirs in zip(free.extremes, locked.extremes, strict=True):
        assert mine.sign * mine.value >= theirs.sign * theirs.value - 1e-9
    # the free extremes are real: re-solve the stance for each free pose is done inside;
    # here check the translation ones strictly beat axis-locked where the body can lean
    assert free.extreme("x", 1).value > locked.extreme("x", 1).value


@pytest.mark.slow
def test_causes_do_not_depend_on_the_blas_thread_count():
    """Mirror-image legs bind together; which one is named must not follow round-off."""
    import json
    import os
    import subprocess
    import sys

    outputs = []
    for threads in ("1", "2"):
        env = {**os.environ, "OPENBLAS_NUM_THREADS": threads, "OMP_NUM_THREADS": threads}
        result = subprocess.run(
            [sys.executable, "-m", "hexaleg", "flexibility", "--mode", "free", "--json"],
            capture_output=True,
            text=True,
            timeout=300,
            env=env,
        )
        assert result.returncode == 0, result.stderr
        outputs.append(json.loads(result.stdout)["extremes"])
    one, two = outputs
    assert [e["description"] for e in one] == [e["description"] for e in two]
    assert [e["binding"] for e in one] == [e["binding"] for e in two]
    for a, b in zip(one, two, strict=True):
        assert a["value"] == pytest.approx(b["value"], abs=1e-9)
    assert any(len(e["binding"]) > 1 for e in one)  # ties exist, and all tied legs are named


BETTER_POSES = [
    # (design fields, stance, direction, a better pose's value found by an independent search)
    ({"l1": 0.255, "l2": 0.152, "l3": 0.593}, "tripod", "roll+", 0.243015),
    ({"l1": 0.06, "l2": 0.35, "l3": 0.59}, "all", "z-", 0.196896),
    (
        {"l1": 0.18986180759758675, "l2": 0.15155430580598717, "l3": 0.6585838865964261},
        "tripod",
        "roll-",
        0.20821,  # short on another machine's floating-point path
    ),
]
"""Designs, directions and a better pose's value that a local search falls short of."""
COLLISION_ROWS = [
    ({"body_length": 0.12, "body_width": 0.45}, "roll+", 0.329050),
    ({"body_length": 0.12, "body_width": 0.45}, "roll-", 0.329050),
    ({"body_length": 0.1, "body_width": 0.4}, "pitch+", 0.486713),
    ({"body_length": 0.1, "body_width": 0.4}, "pitch-", 0.486713),
    ({"body_length": 0.1, "body_width": 0.4}, "x+", 0.370127),
    ({"body_length": 0.1, "body_width": 0.4}, "roll+", 0.317882),
    ({"body_length": 0.1, "body_width": 0.4}, "yaw+", 0.416732),
]
"""As :data:`BETTER_POSES`, with self-collision on short bodies (default legs)."""


@pytest.mark.parametrize(("fields", "stance", "name", "better"), BETTER_POSES, ids=str)
def test_the_better_poses_are_reached(fields, stance, name, better):
    """Fast, and able to catch a short extreme: a tripod's roll+ basin few starts reach."""
    from hexaleg import HexapodDesign

    result = free_flexibility(HexapodDesign(**fields), stance)
    extreme = next(e for e in result.extremes if e.name == name)
    assert extreme.sign * extreme.value >= better - 1e-6
    assert extreme.evidence.reachable and extreme.evidence.converged


@pytest.mark.slow
@pytest.mark.parametrize(("fields", "name", "better"), COLLISION_ROWS, ids=str)
def test_the_better_poses_with_collisions_are_reached(fields, name, better, collision_results):
    result = collision_results(tuple(sorted(fields.items())))
    extreme = next(e for e in result.extremes if e.name == name)
    assert extreme.sign * extreme.value >= better - 1e-6


@pytest.mark.slow
@pytest.mark.parametrize(
    ("fields", "name", "better"),
    COLLISION_ROWS,
    ids=str,
)
def test_a_collision_extreme_short_of_a_known_pose_is_not_reported_converged(
    fields, name, better, collision_results
):
    result = collision_results(tuple(sorted(fields.items())))
    extreme = next(e for e in result.extremes if e.name == name)
    if extreme.sign * extreme.value < better - 1e-6:
        assert not extreme.evidence.converged and not result.converged
        assert any(doubt.startswith(f"{name}: ") for doubt in result.doubts)


ROUNDING_CASES = [
    # (body length and width factors, BLAS threads, starts reversed, every start pose shifted)
    ((1 + 1e-12, 1 - 1e-12), 1, False, 0.0),
    ((1 + 1e-12, 1 + 1e-12), 2, True, 0.0),
    ((1 + 1e-15, 1 - 1e-15), 1, False, 0.0),
    ((1 + 1e-15, 1 + 1e-15), 2, False, 1e-14),  # (0.1 m is the shortest body: not below)
    ((1.0, 1.0), 1, False, -1e-14),
]
"""Rounding-level changes of the inputs and of the floating-point path: a seeded search
gives one answer on every machine."""


@pytest.mark.slow
@pytest.mark.parametrize(
    ("factors", "threads", "reversed_starts", "shift"), ROUNDING_CASES, ids=str
)
def test_a_collision_extreme_does_not_follow_round_off(
    factors, threads, reversed_starts, shift, collision_results, monkeypatch
):
    """The body's sizes by 1e-12 or 1e-15, every start pose (the axis-locked extreme's and
    the spread ones) moved by 1e-14, SLSQP's BLAS on another thread count (its steps then
    differ in the last bits) and the starts asked in reverse: the same yaw+ maximum as the
    unperturbed search, to 1e-6 rad, and never short of the independent search's pose."""
    from threadpoolctl import threadpool_limits

    from hexaleg import HexapodDesign
    from hexaleg.numerics import multistart
    from hexaleg.stance import collision_starts, free_coupled

    fields = {"body_length": 0.1, "body_width": 0.4}
    reference = collision_results(tuple(sorted(fields.items()))).extreme("yaw", 1)
    if reversed_starts or shift:
        order = slice(None, None, -1 if reversed_starts else 1)

        def moved(*args, **kwargs):
            return [start + shift for start in multistart.box_starts(*args, **kwargs)[order]]

        monkeypatch.setattr(free_coupled, "box_starts", moved)
        monkeypatch.setattr(collision_starts, "box_starts", moved)
    if shift:
        locked_start = free_coupled.axis_locked_start
        monkeypatch.setattr(
            free_coupled, "axis_locked_start", lambda extreme: locked_start(extreme) + shift
        )
    design = HexapodDesign(
        body_length=fields["body_length"] * factors[0],
        body_width=fields["body_width"] * factors[1],
    )
    with threadpool_limits(threads), warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexibilityWarning)
        extreme = free_flexibility(design, collisions=True).extreme("yaw", 1)
    assert extreme.value == pytest.approx(reference.value, abs=1e-6)
    better = next(b for f, name, b in COLLISION_ROWS if f == fields and name == "yaw+")
    assert extreme.value >= better - 1e-6
    assert extreme.evidence.converged and reference.evidence.converged


@pytest.fixture(scope="module")
def collision_results():
    from functools import cache

    from hexaleg import HexapodDesign

    @cache
    def run(fields):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", FlexibilityWarning)
            return free_flexibility(HexapodDesign(**dict(fields)), collisions=True)

    return run


@pytest.mark.parametrize(
    ("fields", "stance"),
    [({"l1": 0.255, "l2": 0.152, "l3": 0.593}, "tripod"), ({}, "all")],
    ids=["tripod", "all legs"],
)
def test_every_free_extreme_is_reached_from_nominal_by_a_feasible_path(fields, stance):
    """The path hexaleg finds, checked independently: NumPy margins every ≤ 1 mm, 1 mrad."""
    import numpy as np
    from margin_oracle import displaced

    from hexaleg import HexapodDesign
    from hexaleg.stance import StanceGeometry
    from hexaleg.stance.free_coupled import search_box
    from hexaleg.stance.margin_kernel import kernel_geometry
    from hexaleg.stance.paths import retreat

    design = HexapodDesign(**fields)
    geometry = StanceGeometry.from_model(HexapodModel(design), stance)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexibilityWarning)
        result = free_flexibility(design, stance)
    box = search_box(flexibility(design, "axis", stance).extremes)
    smooth, exact = kernel_geometry([geometry], True), kernel_geometry([geometry], False)
    for extreme in result.extremes:
        assert extreme.evidence.reachable
        reached, path = retreat(smooth, exact, np.array(extreme.pose), box)
        assert reached
        np.testing.assert_array_equal(path[0], extreme.pose)
        assert not path[-1].any()  # ends at the nominal stance
        points = [path[0]]
        for a, b in itertools.pairwise(path):
            steps = int(np.ceil(np.abs(b - a).max() / 1e-3))
            points += list(a + (b - a) * (np.arange(1, steps + 1) / steps)[:, None])
        margins = displaced(geometry, np.array(points))
        assert margins.min() >= -1e-9, extreme.name


def _random_designs(count, seed):
    """Fig 15-style designs (leg length 1 m) at random; every fourth stands on a tripod."""
    import numpy as np

    from hexaleg import HexapodDesign

    rng = np.random.default_rng(seed)
    designs = []
    for i in range(count):
        r1 = rng.uniform(0.03, 0.3)
        r3 = rng.uniform(0.15, 0.85 - r1)
        designs.append((HexapodDesign.from_ratios(r1, r3), "tripod" if i % 4 == 0 else "all"))
    return designs


BRUTE_SEED = 2027
"""Not the seed of the designs the search was tuned on."""
RANDOM_DESIGNS = _random_designs(12, BRUTE_SEED)


def _brute_force(geometry, locked, axis, sign, collision=None, starts=40):
    """An independent multi-start: uniform random starts (not hexaleg's Sobol set) over a
    wider box, plain SLSQP on the oracle's margins (:mod:`margin_oracle`, and coal's
    clearance), the best exactly feasible answer and its pose."""
    import numpy as np
    from margin_oracle import displaced
    from scipy import optimize

    from hexaleg.stance.constraints import displacement_poses

    value = {(e.axis, e.sign): e.value for e in locked}
    half = np.array([2.5 * max(abs(value[(a, 1)]), abs(value[(a, -1)])) for a in AXES])
    k = AXES.index(axis)

    def clearance(d):
        return collision.clearances(*displacement_poses(geometry, d))[0]

    def constraints(d):
        margins = displaced(geometry, d, smooth=True)
        return margins if collision is None else np.append(margins, clearance(d))

    rng = np.random.default_rng(BRUTE_SEED + k)
    best, pose = -np.inf, None
    bounds = [(None, None)] * 3 + [(-np.pi, np.pi), (-np.pi / 2, np.pi / 2), (-np.pi, np.pi)]
    for start in rng.uniform(-1, 1, size=(starts, 6)) * half:
        result = optimize.minimize(
            lambda d: -sign * d[k],
            start,
            method="SLSQP",
            bounds=bounds,
            constraints={"type": "ineq", "fun": constraints},
            options={"maxiter": 150, "ftol": 1e-12},
        )
        margins = displaced(geometry, result.x)
        feasible = margins.min() >= -1e-9 and (collision is None or clearance(result.x) >= -1e-7)
        if feasible and sign * result.x[k] > best:
            best, pose = sign * result.x[k], result.x
    return best, pose


def _reachable(geometry, pose, box):
    """Whether a path to ``pose`` from nominal can be shown (hexaleg's retreat, its every
    1 mm / 1 mrad checked here on the oracle's margins)."""
    import numpy as np
    from margin_oracle import displaced

    from hexaleg.stance.margin_kernel import kernel_geometry
    from hexaleg.stance.paths import retreat

    smooth, exact = kernel_geometry([geometry], True), kernel_geometry([geometry], False)
    reached, path = retreat(smooth, exact, np.asarray(pose, dtype=float), box)
    if not reached:
        return False
    for a, b in itertools.pairwise(path):
        steps = int(np.ceil(np.abs(b - a).max() / 1e-3))
        points = a + (b - a) * (np.arange(1, steps + 1) / steps)[:, None]
        if displaced(geometry, points).min() < -1e-9:
            return False
    return True


@pytest.mark.slow
@pytest.mark.parametrize(
    ("design", "stance"), RANDOM_DESIGNS, ids=lambda v: str(getattr(v, "lengths", v))
)
def test_free_extremes_are_never_short_of_a_brute_force_multistart(design, stance):
    """On designs drawn at random here: a better pose the brute force finds must be one
    no path from nominal can be shown to reach, and a converged extreme has none."""
    from hexaleg.stance import StanceGeometry, axis_locked_extremes
    from hexaleg.stance.free_coupled import search_box

    model = HexapodModel(design)
    geometry = StanceGeometry.from_model(model, stance)
    locked = axis_locked_extremes(geometry)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexibilityWarning)
        free = free_flexibility(design, stance, model)
    for extreme in free.extremes:
        brute, pose = _brute_force(geometry, locked, extreme.axis, extreme.sign)
        if brute > extreme.sign * extreme.value + 1e-6:
            assert not _reachable(geometry, pose, search_box(locked)), (extreme.name, brute)


SHORT_BODIES = [
    {"body_length": 0.11, "body_width": 0.42, "l1": 0.18, "l2": 0.42, "l3": 0.4},
    {"body_length": 0.14, "body_width": 0.5, "l1": 0.22, "l2": 0.36, "l3": 0.42},
]
"""Short bodies whose adjacent legs collide, other than :data:`COLLISION_ROWS`' own."""


@pytest.mark.slow
@pytest.mark.parametrize("fields", SHORT_BODIES, ids=str)
def test_free_extremes_with_collisions_against_a_brute_force(fields):
    from hexaleg import HexapodDesign
    from hexaleg.stance import StanceGeometry
    from hexaleg.stance.axis_locked import axis_locked_extremes
    from hexaleg.stance.collisions import SelfCollision, collision_limited

    design = HexapodDesign(**fields)
    model = HexapodModel(design)
    geometry = StanceGeometry.from_model(model)
    collision = SelfCollision(model, geometry)
    locked = collision_limited(geometry, collision, axis_locked_extremes(geometry))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FlexibilityWarning)
        free = free_flexibility(design, model=model, collisions=True)
    for extreme in free.extremes[::2]:  # the + directions: the robots are symmetric
        brute, _ = _brute_force(geometry, locked, extreme.axis, extreme.sign, collision, 16)
        assert extreme.sign * extreme.value >= brute - 1e-6 or not extreme.evidence.converged


@pytest.mark.parametrize("mode", ["axis", "free"])
def test_every_reported_pose_is_feasible_and_puts_the_feet_on_their_footholds(mode):
    import numpy as np
    import pinocchio as pin
    from margin_oracle import displaced

    from hexaleg import HexapodDesign
    from hexaleg.stance import StanceGeometry

    design = HexapodDesign(l1=0.15, l2=0.5, l3=0.35)
    model = HexapodModel(design)
    geometry = StanceGeometry.from_model(model)
    result = flexibility(design, mode, "all", model)
    for extreme in result.extremes:
        pose = np.array(extreme.pose)
        assert pose[AXES.index(extreme.axis)] == pytest.approx(extreme.value, abs=1e-15)
        if mode == "axis":  # one coordinate moves, the other five held
            assert np.count_nonzero(pose) == 1
        assert displaced(geometry, pose).min() >= -1e-9
        # Pinocchio, from the reported pose and joint angles alone: feet on the footholds
        height = np.array([0.0, 0.0, design.nominal_height])
        base = pin.SE3(pin.rpy.rpyToMatrix(*pose[3:]), pose[:3] + height)
        q = model.configuration(base, extreme.joint_angles)
        feet = model.foot_positions(q)
        np.testing.assert_allclose(feet, geometry.footholds, atol=1e-9)
        assert set(extreme.joint_angles) == set(model.leg_names)
        data = extreme.to_dict()
        assert len(data["pose"]) == 6 and set(data["joint_angles"]) == set(model.leg_names)


def test_a_search_whose_starts_disagree_is_flagged(monkeypatch):
    import warnings

    from hexaleg import HexapodDesign
    from hexaleg.stance import FlexibilityWarning, free_coupled

    monkeypatch.setattr(free_coupled, "CLIMBS", 1)  # a thin search: one box start
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = free_flexibility(HexapodDesign())
    assert not result.converged
    messages = [str(w.message) for w in caught if issubclass(w.category, FlexibilityWarning)]
    assert len(messages) == 1 and "z-: reached by 1 of" in messages[0]
    flagged = [e for e in result.extremes if not e.evidence.converged]
    assert flagged and all(f"{e.name}: " in messages[0] for e in flagged)
    assert result.to_dict()["warnings"] == list(result.doubts)


@pytest.mark.filterwarnings("ignore::hexaleg.exceptions.RobotImportWarning")
@pytest.mark.parametrize("kind", KINDS)
def test_the_table_names_the_robot_the_free_mode_and_its_evidence(capsys, monkeypatch, kind):
    small_free_search(monkeypatch)
    assert run_cli(["flexibility", *robot_argv(kind), "--mode", "free"]) == 0
    out = capsys.readouterr().out
    named = f"of {KRABY} " if kind == "kraby" else ""
    assert f"Body flexibility {named}(free, stance lf lm lr rf rm rr)" in out
    assert "evidence" in out and "extremes reached from nominal by a feasible path" in out
