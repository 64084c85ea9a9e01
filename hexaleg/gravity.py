"""Gravity, as every analysis takes it: g along −z of the ground frame (tilted on a slope)."""

from __future__ import annotations

import math

import numpy as np

from hexaleg._typing import ArrayF

GRAVITY = 9.81
"""Gravitational acceleration g [m/s²]: the standard acceleration due to gravity,
g_n = 980.665 cm/s² (BIPM, Resolution of the 3rd CGPM (1901), Comptes Rendus p. 70),
to three significant digits. The statics, the gait, the leg frames' gravity torques and the
MuJoCo model all take this one value."""


def slope_gravity(angle: float, heading: float, gravity: float = GRAVITY) -> ArrayF:
    """Gravity [m/s²] in the ground frame of a slope α uphill toward heading ψ (g [m/s²]).

    g·(−sin α cos ψ, −sin α sin ψ, −cos α): on level ground (α = 0), :data:`LEVEL_GRAVITY`.
    """
    return gravity * np.array(
        [
            -math.sin(angle) * math.cos(heading),
            -math.sin(angle) * math.sin(heading),
            -math.cos(angle),
        ]
    )


LEVEL_GRAVITY: ArrayF = slope_gravity(0.0, 0.0)
"""Gravity on level ground [m/s²]: (0, 0, −g), read-only (a default argument's value)."""
LEVEL_GRAVITY.setflags(write=False)
