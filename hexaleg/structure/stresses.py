"""A round tube's stresses under the wrench at a section, and their ratio to what is allowed.

A section carrying the wrench (force f, moment m) in the segment's frame (x along the
segment) carries the axial force N = f_x, the bending moment M_b = √(m_y² + m_z²) (the
moment's part across the axis) and the torsion T = m_x. On a tube of outer diameter D,
area A and second moment I (the polar moment 2I) the largest normal stress is
σ = |N|/A + |M_b|·(D/2)/I and the torsion's shear stress τ = |T|·(D/2)/(2I), both at the
outer fibre; von Mises combines them, √(σ² + 3τ²). The shear forces' own shear stress
(zero at the outer fibre where σ peaks) is left out.

The ratio is von Mises over the strength the safety factor allows, strength / safety
factor; a material with a shear strength (a composite, weak across its fibres) also has
τ over its shear strength / safety factor, and the ratio is the larger. Above 1 the tube
is over its strength.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF
from hexaleg.leg_structure import Structure

LOAD_NAMES = ("axial", "bending", "torsion")
"""The section loads, in order: N [N], M_b [N·m], T [N·m]."""


def section_loads(wrenches: npt.ArrayLike) -> ArrayF:
    """(N, M_b, T) (..., 3) [N, N·m, N·m] of wrenches (..., 6): force, then moment."""
    w = np.asarray(wrenches, dtype=float)
    return np.stack((w[..., 0], np.hypot(w[..., 4], w[..., 5]), w[..., 3]), axis=-1)


def tube_stresses(
    loads: npt.ArrayLike,
    outer_diameter: npt.ArrayLike,
    area: npt.ArrayLike,
    second_moment: npt.ArrayLike,
) -> tuple[ArrayF, ArrayF, ArrayF]:
    """σ, τ and von Mises [Pa] of section loads (..., 3) on tubes broadcast against them.

    Args:
        loads: (N, M_b, T) (..., 3) [N, N·m, N·m].
        outer_diameter: D [m], broadcast against ``loads[..., 0]``.
        area: A [m²], likewise.
        second_moment: I [m⁴], likewise.

    """
    magnitude = np.abs(np.asarray(loads, dtype=float))
    fibre = np.asarray(outer_diameter, dtype=float) / 2
    moment = np.asarray(second_moment, dtype=float)
    sigma = magnitude[..., 0] / np.asarray(area, dtype=float) + magnitude[..., 1] * fibre / moment
    tau = magnitude[..., 2] * fibre / (2 * moment)
    return sigma, tau, np.sqrt(sigma**2 + 3 * tau**2)


def stress_ratio(von_mises: npt.ArrayLike, tau: npt.ArrayLike, structure: Structure) -> ArrayF:
    """The ratio [-]: von Mises over strength / safety factor, or τ over shear strength / it."""
    ratio = np.asarray(von_mises, dtype=float) / structure.allowed_stress
    shear = structure.material.shear_strength
    if shear is None:
        return ratio
    return np.maximum(ratio, np.asarray(tau, dtype=float) * structure.safety_factor / shear)
