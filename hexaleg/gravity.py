"""Gravity, as every analysis takes it: g along −z of the ground frame (tilted on a slope)."""

from __future__ import annotations

GRAVITY = 9.81
"""Gravitational acceleration g [m/s²]: the standard acceleration due to gravity,
g_n = 980.665 cm/s² (BIPM, Resolution of the 3rd CGPM (1901), Comptes Rendus p. 70),
to three significant digits. The statics, the gait, the leg frames' gravity torques and the
MuJoCo model all take this one value."""
