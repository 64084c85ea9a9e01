"""Spread starts for the free-coupled search with self-collision (:mod:`.free_coupled`).

The climbs see the stance margins only, and with the clearance as one more margin
their basins can lie inside two parts: pulled back clear (or from the axis-locked
extreme) they give the polish starts near the axis or a plane of symmetry, where
the clearance of two mirror-image pairs forms a corner that SLSQP does not leave.
Optima that go round the touching parts (a body pitched so that two coxae pass one
above the other, say) lie off those planes. These starts are drawn over the search
box instead: the draws free of every exact margin and of collision are each pushed
along the direction until the first that is not (a cheap screen: no SLSQP), and the
furthest pushed are polished.
"""

from __future__ import annotations

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.numerics.multistart import box_starts
from hexaleg.stance.free_problem import FreeProblem

COLLISION_DRAWS = 64
"""Scrambled-Sobol draws screened per direction."""
COLLISION_BOX = 0.5
"""The draws fill the search box scaled by this: most of them clear."""
COLLISION_STARTS = 8
"""The furthest-pushed draws polished per direction."""
PUSH_STEPS = 40
"""Steps of the push along the direction, up to twice the search box's half width."""


def spread_starts(problem: FreeProblem, k: int, sign: int, box: ArrayF, seed: int) -> list[ArrayF]:
    """The :data:`COLLISION_STARTS` furthest-pushed clear draws (6,) [m, rad], furthest first.

    Args:
        problem: The direction's program, with self-collision.
        k: The pushed coordinate.
        sign: +1 or −1, its direction.
        box: The search box's half widths (6,) [m, rad].
        seed: The draws' seed.

    """
    draws = np.array(box_starts(COLLISION_BOX * box, COLLISION_DRAWS, seed=seed))
    steps = np.linspace(0.0, 2.0 * box[k], PUSH_STEPS + 1)[1:]
    pushed = []
    for draw in draws[problem.clear(draws)]:
        line = np.repeat(draw[None], len(steps), axis=0)
        line[:, k] += sign * steps
        clear = problem.clear(line)
        reach = len(steps) if clear.all() else int(np.argmin(clear))
        pushed.append(line[reach - 1] if reach else draw)
    pushed.sort(key=lambda d: -sign * d[k])
    return pushed[:COLLISION_STARTS]
