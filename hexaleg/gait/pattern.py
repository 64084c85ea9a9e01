"""Gait patterns: which legs swing when, and each leg's phase at each sample.

A pattern splits the six legs into n groups that swing one after another, each for T/n:
the duty factor (the fraction of the period a foot stands) is β = 1 − 1/n.

- ``tripod`` (n = 2, β = 1/2): group A = (lf, rm, lr) swings for t ∈ [0, T/2) and stands
  for [T/2, T); group B = (rf, lm, rr) the other way round.
- ``tetrapod`` (n = 3, β = 2/3): legs opposite each other around the body swing together:
  (lf, rr) for [0, T/3), (rf, lr) for [T/3, 2T/3), (lm, rm) for [2T/3, T). In the built-in
  layouts the two legs of a pair are mirror images through the body centre, so the four
  standing feet always surround it.
- ``wave`` (n = 6, β = 5/6): one leg at a time, each for T/6, clockwise around the body
  seen from above: lf, rf, rm, rr, lr, lm.

Generally, with the legs numbered a = 0 … 5 counter-clockwise around the body from
straight ahead (lf, lm, lr, rr, rm, rf in the built-in layouts; custom layouts by their
roots' direction from the body centre, as ``--stance tripod`` picks every other leg), leg
a starts its swing at phase φ_a = ((−a) mod n) / n. Intervals are half-open: a leg
swings for t/T − φ_a ∈ [0, 1/n) (mod 1) and stands otherwise, so at every instant exactly
6·β feet stand. Sample phases are computed in integers, k·n − N·n·φ_a, hence exactly.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache
from itertools import pairwise

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF, GaitPattern, require_choice
from hexaleg.design import HexapodDesign
from hexaleg.layouts import legs_around as layout_legs_around

GROUPS: dict[str, int] = {"tripod": 2, "tetrapod": 3, "wave": 6}
"""How many groups of legs swing one after another, per pattern."""


def duty_factor(pattern: GaitPattern) -> float:
    """β = 1 − 1/n: the fraction of the period each foot stands [-]."""
    require_choice("pattern", pattern, GaitPattern)
    return 1.0 - 1.0 / GROUPS[pattern]


def legs_around(design: HexapodDesign) -> tuple[str, ...]:
    """The design's legs counter-clockwise around the body, from straight ahead.

    As :func:`~hexaleg.layouts.legs_around` orders them (and ``--stance tripod`` picks
    every other one).
    """
    return layout_legs_around(design.legs)


def swing_starts(design: HexapodDesign, pattern: GaitPattern) -> npt.NDArray[np.int_]:
    """Each leg's swing start as a whole number g of T/n (φ = g/n), in ``leg_names`` order."""
    groups = GROUPS[require_choice("pattern", pattern, GaitPattern)]
    around = legs_around(design)
    return np.array([(-around.index(leg)) % groups for leg in design.leg_names])


@dataclass(frozen=True, eq=False)  # compared and hashed by identity: one per pattern and N
class GaitPhases:
    """Where each leg is in its cycle at each of the N samples.

    Attributes:
        groups: n, the number of groups that swing in turn.
        swing: Whether each leg swings (N, 6), ``leg_names`` order.
        phase: Within the swing, s ∈ [0, 1); within the stance, σ ∈ [0, 1) (N, 6) [-].

    """

    groups: int
    swing: npt.NDArray[np.bool_]
    phase: ArrayF

    @property
    def duty_factor(self) -> float:
        """β = 1 − 1/n [-]."""
        return 1.0 - 1.0 / self.groups

    @property
    def stance(self) -> npt.NDArray[np.bool_]:
        """Whether each leg stands (N, 6)."""
        return ~self.swing

    @cached_property
    def runs(self) -> tuple[slice, ...]:
        """The runs of consecutive samples with the same standing legs, in order.

        Standing feet do not move on the ground during a run: one support polygon, and one
        set of balance rows about a point fixed on the ground, serve all its samples.
        """
        changes = np.flatnonzero((self.swing[1:] != self.swing[:-1]).any(axis=1)) + 1
        bounds = [0, *(int(k) for k in changes), len(self.swing)]
        return tuple(slice(start, end) for start, end in pairwise(bounds))


def gait_phases(design: HexapodDesign, pattern: GaitPattern, samples: int) -> GaitPhases:
    """Each leg's phase at t_k = k·T/N, k = 0 … N−1, exactly (integer arithmetic).

    With u = k·n − N·g (mod N·n) the leg's time since its swing started, in units of
    T/(N·n): it swings while u < N, at s = u/N, and stands after, at σ = (u − N)/(N·(n − 1)).
    """
    starts = tuple(int(g) for g in swing_starts(design, pattern))
    return _phases(starts, GROUPS[pattern], samples)


@lru_cache(maxsize=32)
def _phases(starts: tuple[int, ...], groups: int, samples: int) -> GaitPhases:
    """:func:`gait_phases`, shared (read-only) by every design of a study."""
    k = np.arange(samples)[:, None]
    since = np.mod(k * groups - samples * np.array(starts)[None, :], samples * groups)
    swing = since < samples
    phase = np.where(swing, since / samples, (since - samples) / (samples * (groups - 1)))
    swing.flags.writeable = phase.flags.writeable = False
    return GaitPhases(groups, swing, phase)
