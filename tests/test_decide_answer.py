"""decide's printed answer is a design a workshop builds and every command confirms.

The oracle is the single-design commands themselves, run as a user would at the numbers
decide printed (``loads``, ``gait``, ``flexibility``: their own analyses, no search), on
seeded random requirement sets: the standing payload and slope with the motors' safety
factor, the speed walked up, down and across the walking slope, and the flexibility. The
printed lengths lie on the 1 mm grid and the angles on the 0.001 rad grid, by arithmetic.
"""

from __future__ import annotations

import itertools
import json
import math

import numpy as np
import pytest

from hexaleg.cli import main as run_cli

pytestmark = pytest.mark.slow


def _json(capsys, argv):
    assert run_cli([*argv, "--json"]) == 0, capsys.readouterr().err
    return json.loads(capsys.readouterr().out)


def _requirements(seed):
    """A random requirement set the template's legs can meet (seeded)."""
    rng = np.random.default_rng(seed)
    return {
        "payload": round(float(rng.uniform(10, 40)), 3),
        "slope_deg": round(float(rng.uniform(5, 20)), 3),
        "speed": round(float(rng.uniform(0.1, 0.25)), 4),
        "walking_slope_deg": round(float(rng.uniform(2, 10)), 3),
        "motor_safety_factor": round(float(rng.uniform(1.0, 1.3)), 3),
        "min_fb": round(float(rng.uniform(0.1, 0.2)), 4),
    }


def _on_grid(value, step):
    return abs(value / step - round(value / step)) < 1e-6


@pytest.mark.parametrize("seed", [1, 2])
def test_decide_s_printed_answer_meets_every_requirement_in_every_command(capsys, seed):
    required = _requirements(seed)
    options = [x for name, value in required.items()
               for x in (f"--{name.replace('_', '-')}", repr(value))]  # fmt: skip
    answer = _json(capsys, ["decide", *options, "--evaluations", "150", "--workers", "2"])
    assert answer["feasible"], answer["requirements"]
    best = answer["best"]["design"]
    lengths, angles = (best["l1"], best["l2"], best["l3"]), best["nominal_angles"]
    assert all(_on_grid(length, 1e-3) for length in lengths), lengths
    assert all(_on_grid(angle, 1e-3) for angle in angles), angles
    design = ["--l1", repr(lengths[0]), "--l2", repr(lengths[1]), "--l3", repr(lengths[2]),
              "--nominal-angles", *map(repr, angles)]  # fmt: skip
    factor = ["--motor-safety-factor", repr(required["motor_safety_factor"])]
    payload = ["--payload", repr(required["payload"])]

    loads = _json(capsys, ["loads", *design, *payload, *factor])
    assert loads["safety_factor"] == required["motor_safety_factor"]
    assert loads["payload_capacity"]["mass"] >= required["payload"]
    steepest = min(slope["max_slope"] for slope in loads["slopes"])  # every heading printed
    assert steepest >= math.radians(required["slope_deg"]) * (1 - 1e-12)

    flex = _json(capsys, ["flexibility", *design])
    assert flex["fb"] >= required["min_fb"]

    walking = required["walking_slope_deg"]
    grounds = (  # up, down and across the walking slope, the gait's heading 0
        ["--slope-deg", repr(walking)],
        ["--slope-deg", repr(-walking)],
        ["--slope-deg", repr(walking), "--slope-heading", repr(math.pi / 2)],
    )
    for ground in grounds:
        gait = _json(capsys, ["gait", *design, *payload, *factor, *ground,
                              "--speed", repr(required["speed"])])  # fmt: skip
        assert gait["feasible"], (ground, gait["infeasible_because"])
        assert gait["max_speed"]["value"] >= required["speed"], ground


def _sized_file(tmp_path, payload, lengths=None):
    """The template's legs of printed PLA tubes sized for ``payload`` (and these lengths)."""
    path = tmp_path / ("robot.toml" if lengths is None else "point.toml")
    given = (
        ""
        if lengths is None
        else "".join(
            f"{name} = {value!r}\n" for name, value in zip(("l1", "l2", "l3"), lengths, strict=True)
        )
    )
    path.write_text(f'{given}\n[structure]\nmaterial = "pla_printed"\nsize = true\n\n'
                    f"[requirements]\npayload = {payload!r}\n")  # fmt: skip
    return str(path)


@pytest.mark.parametrize("seed", [4])
def test_decide_with_sized_tubes_beats_a_brute_force_grid(tmp_path, capsys, seed):
    """Largest standing payload capacity with FB ≥ f, every candidate's PLA tubes sized.

    The brute force: every point of a grid of lengths (on the millimetre grid decide answers
    on, leg length at most the template's 1 m) measured by ``loads`` (its tubes sized for
    the payload, their mass in the capacity, the tubes holding) and ``flexibility``.
    """
    rng = np.random.default_rng(seed)
    payload, min_fb = round(float(rng.uniform(5, 30)), 3), round(float(rng.uniform(0.15, 0.25)), 4)
    robot = _sized_file(tmp_path, payload)
    argv = ["decide", "--design", robot, "--fixed-posture", "--min-fb", repr(min_fb),
            "--maximize", "payload_capacity", "--evaluations", "300", "--workers", "2"]  # fmt: skip
    answer = _json(capsys, argv)
    assert answer["feasible"], answer["requirements"]
    best = answer["best"]["design"]
    lengths = (best["l1"], best["l2"], best["l3"])
    assert best["structure"]["size"] and all(_on_grid(length, 1e-3) for length in lengths)

    def measured(point):
        design = _sized_file(tmp_path, payload, point)
        loads = _json(capsys, ["loads", "--design", design])
        fb = _json(capsys, ["flexibility", "--design", design])["fb"]
        holds = loads["structure"]["feasible"] and loads["structure"]["sizing"]["found"]
        return loads["payload_capacity"]["mass"], fb, holds

    capacity, fb, holds = measured(lengths)  # decide's answer, measured as a user would
    assert holds and fb >= min_fb and capacity >= payload
    assert answer["best"]["objective"]["value"] == pytest.approx(capacity, rel=1e-9)
    grid_best = -math.inf
    for point in itertools.product((0.05, 0.1, 0.15, 0.2), (0.25, 0.3, 0.35, 0.4),
                                   (0.3, 0.35, 0.4, 0.45)):  # fmt: skip
        if sum(point) > 1.0 + 1e-12:
            continue
        found, fb, holds = measured(point)
        if holds and fb >= min_fb and found >= payload:
            grid_best = max(grid_best, found)
    assert grid_best > -math.inf, "the grid has a point meeting these requirements"
    assert capacity >= grid_best * (1 - 1e-9), (capacity, grid_best)
