"""Shared fixtures: models are rendered once per session (rendering costs ~50 ms)."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg import HexapodDesign, HexapodModel, LegModel
from hexaleg.stance import collision_starts, free_coupled


@pytest.fixture(scope="session")
def default_design() -> HexapodDesign:
    return HexapodDesign()


@pytest.fixture(scope="session")
def hexapod_model(default_design: HexapodDesign) -> HexapodModel:
    return HexapodModel(default_design)


@pytest.fixture(scope="session")
def leg_model(default_design: HexapodDesign) -> LegModel:
    return LegModel(default_design)


def small_free_search(patch: pytest.MonkeyPatch) -> None:
    """The free-coupled search with small budgets (a few climbs and collision starts): for
    oracles that check what an answer is, not that it is the best."""
    patch.setattr(free_coupled, "CLIMBS", 8)
    patch.setattr(free_coupled, "COLLISION_BASINS", 2)
    patch.setattr(collision_starts, "COLLISION_DRAWS", 16)
    patch.setattr(collision_starts, "COLLISION_STARTS", 2)


def random_designs(count: int, seed: int) -> list[HexapodDesign]:
    """Designs with random segment lengths, body sizes and nominal postures."""
    rng = np.random.default_rng(seed)
    designs = []
    while len(designs) < count:
        l1, l2, l3 = rng.uniform(0.02, 0.8, size=3)
        try:
            designs.append(
                HexapodDesign(
                    l1=l1,
                    l2=l2,
                    l3=l3,
                    body_length=rng.uniform(0.3, 1.5),
                    body_width=rng.uniform(0.2, 1.0),
                    body_height=rng.uniform(0.01, 0.1),
                    nominal_angles=(
                        rng.uniform(-0.7, 0.7),
                        rng.uniform(-0.5, 0.5),
                        rng.uniform(-2.3, -0.3),
                    ),
                )
            )
        except ValueError:  # posture with the feet above the body: draw again
            continue
    return designs


def random_angles(rng: np.random.Generator, count: int) -> np.ndarray:
    """Joint angles (count, 3) spread over [-π, π] [rad]."""
    return rng.uniform(-np.pi, np.pi, size=(count, 3))


def run_cli(argv: list[str]) -> int:
    """Exit status of ``hexaleg argv``, whether main returns it or argparse exits with it."""
    from hexaleg.cli import main

    try:
        return main(argv)
    except SystemExit as exit_:
        return int(exit_.code or 0)


def kill_hexaleg_when(argv: list[str], ready, what: str, timeout: float = 120.0) -> None:
    """Run ``hexaleg argv`` in a session of its own; SIGKILL the whole group once
    ``ready()`` is true (fail if it never is, or if the command ends first)."""
    import os
    import signal
    import subprocess
    import sys
    import time

    process = subprocess.Popen(
        [sys.executable, "-m", "hexaleg", *argv],
        start_new_session=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    deadline = time.monotonic() + timeout
    try:
        while not ready():
            if process.poll() is not None:
                pytest.fail(
                    f"{what} ended before it could be killed: {process.stderr.read().decode()}"
                )
            if time.monotonic() > deadline:
                pytest.fail(f"{what} was not ready to be killed within {timeout:g} s")
            time.sleep(0.01)
    finally:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait(timeout=30)
