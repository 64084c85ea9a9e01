"""The legs' tubes checked under a set of load cases: stresses, ratios, the foot's deflection.

A :class:`StructureCheck` holds, for each load case (a standing pose, or a time of the
walking period), leg and segment, the section loads at the segment's proximal joint
(:mod:`.wrenches`, :mod:`.stresses`) and, standing, each foot's deflection
(:mod:`.deflection`); its properties give the stresses, the ratios to what the material
allows, the worst of them, and whether the structure holds: every ratio at most 1 and
every standing foot's deflection within the limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.leg_structure import LEG_SEGMENTS, Structure, segment_masses
from hexaleg.structure.stresses import LOAD_NAMES, section_loads, stress_ratio, tube_stresses


@dataclass(frozen=True)
class OverStrength:
    """One leg segment whose stress exceeds what its material allows.

    Attributes:
        leg: Leg name.
        segment: ``"coxa"``, ``"femur"`` or ``"tibia"``.
        ratio: Its worst ratio [-] (above 1).
        von_mises: The von Mises stress there [Pa].
        allowed: Strength / safety factor [Pa].
        at: The load case where it peaks (``"nominal"``, ``"x+"``, ``"t = 0.420 s"``).

    """

    leg: str
    segment: str
    ratio: float
    von_mises: float
    allowed: float
    at: str

    def __str__(self) -> str:
        return (
            f"{self.leg} {self.segment} stress ratio {self.ratio:.3f}: von Mises "
            f"{self.von_mises / 1e6:.4g} MPa over the {self.allowed / 1e6:.4g} MPa allowed "
            f"({self.at})"
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (Pa)."""
        return {**vars(self), "description": str(self)}


@dataclass(frozen=True, eq=False)
class StructureCheck:
    """The legs' tubes under load cases.

    Attributes:
        structure: The structure checked (every segment has its tube).
        lengths: Segment lengths (l1, l2, l3) [m].
        legs: Leg names, in the model's order.
        cases: Each load case's name (K).
        wrenches: The wrench at each segment's proximal joint (K, legs, 3, 6): the force [N]
            then the moment [N·m] the proximal side exerts, in the segment's frame (x along
            it; :mod:`.wrenches`).
        deflections: Each foot's deflection (K, legs) [m] in a standing case; ``None`` for
            a walk (deflection is checked standing).
        limit: The foot's deflection limit [m].

    """

    structure: Structure
    lengths: tuple[float, float, float]
    legs: tuple[str, ...]
    cases: tuple[str, ...]
    wrenches: ArrayF
    deflections: ArrayF | None
    limit: float

    @cached_property
    def loads(self) -> ArrayF:
        """Section loads (K, legs, 3, 3): axial force N [N], bending M_b and torsion T [N·m]."""
        return section_loads(self.wrenches)

    @cached_property
    def stresses(self) -> tuple[ArrayF, ArrayF, ArrayF]:
        """σ, τ and von Mises (K, legs, 3) [Pa] at each segment's proximal section."""
        tubes = [tube for tube in self.structure.tubes if tube is not None]
        if len(tubes) != 3:
            raise ValueError("a StructureCheck needs every segment's tube")
        return tube_stresses(
            self.loads,
            [tube.outer_diameter for tube in tubes],
            [tube.area for tube in tubes],
            [tube.second_moment for tube in tubes],
        )

    @cached_property
    def ratios(self) -> ArrayF:
        """Stress over what is allowed (K, legs, 3) [-] (:func:`~.stresses.stress_ratio`)."""
        _, tau, von_mises = self.stresses
        return stress_ratio(von_mises, tau, self.structure)

    @property
    def worst_ratio(self) -> float:
        """The largest ratio over every case, leg and segment [-]."""
        return float(self.ratios.max())

    @property
    def worst(self) -> dict[str, Any]:
        """Where the worst ratio is: ``case``, ``leg``, ``segment`` and the ``ratio``."""
        case, leg, segment = np.unravel_index(int(self.ratios.argmax()), self.ratios.shape)
        return {
            "case": self.cases[case],
            "leg": self.legs[leg],
            "segment": LEG_SEGMENTS[segment],
            "ratio": self.worst_ratio,
        }

    @property
    def deflection(self) -> float:
        """The largest foot deflection over the standing cases [m] (nan for a walk)."""
        return math.nan if self.deflections is None else float(self.deflections.max())

    @property
    def deflection_at(self) -> dict[str, str] | None:
        """The case and leg of the largest deflection (None for a walk)."""
        if self.deflections is None:
            return None
        case, leg = np.unravel_index(int(self.deflections.argmax()), self.deflections.shape)
        return {"case": self.cases[case], "leg": self.legs[leg]}

    @property
    def over_deflection(self) -> bool:
        """Whether a standing foot deflects beyond the limit."""
        return self.deflections is not None and self.deflection > self.limit

    @property
    def feasible(self) -> bool:
        """Every ratio at most 1, and every standing foot within the deflection limit."""
        return self.worst_ratio <= 1 and not self.over_deflection

    @property
    def over_strength(self) -> tuple[OverStrength, ...]:
        """Each leg segment whose ratio exceeds 1 somewhere, with its worst case."""
        von_mises, allowed = self.stresses[2], self.structure.allowed_stress
        worst = self.ratios.argmax(axis=0)  # (legs, 3)
        return tuple(
            OverStrength(
                leg,
                segment,
                float(self.ratios[worst[i, j], i, j]),
                float(von_mises[worst[i, j], i, j]),
                allowed,
                self.cases[worst[i, j]],
            )
            for i, leg in enumerate(self.legs)
            for j, segment in enumerate(LEG_SEGMENTS)
            if self.ratios[worst[i, j], i, j] > 1
        )

    def case_dict(self, case: int) -> dict[str, dict[str, dict[str, float]]]:
        """One case's loads, von Mises and ratio per leg and segment (N, N·m, Pa, -)."""
        von_mises = self.stresses[2]
        return {
            leg: {
                segment: {
                    **{name: float(self.loads[case, i, j, n]) for n, name in enumerate(LOAD_NAMES)},
                    "von_mises": float(von_mises[case, i, j]),
                    "ratio": float(self.ratios[case, i, j]),
                }
                for j, segment in enumerate(LEG_SEGMENTS)
            }
            for i, leg in enumerate(self.legs)
        }

    def tubes_dict(self) -> dict[str, dict[str, float]]:
        """Each segment's tube [m] and mass [kg]."""
        masses = segment_masses(self.structure, self.lengths, math.nan)
        return {
            segment: {**tube.as_dict(), "mass": mass}
            for segment, tube, mass in zip(LEG_SEGMENTS, self.structure.tubes, masses, strict=True)
            if tube is not None
        }

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (SI: N, N·m, Pa, m, kg).

        A standing check adds ``nominal`` (its first case) and the deflection.
        """
        out: dict[str, Any] = {
            "material": self.structure.material.name,
            "safety_factor": self.structure.safety_factor,
            "allowed_stress": self.structure.allowed_stress,
            "worst": self.worst,
            "worst_ratio": self.worst_ratio,
        }
        if self.deflections is not None:
            out = {"nominal": self.case_dict(0), **out}
            out |= {
                "deflection": self.deflection,
                "deflection_at": self.deflection_at,
                "deflection_limit": self.limit,
            }
        return out | {
            "feasible": self.feasible,
            "over_strength": [o.to_dict() for o in self.over_strength],
            "tubes": self.tubes_dict(),
            "units": {
                "axial": "N",
                "bending, torsion": "N·m",
                "von_mises, allowed_stress": "Pa",
                "ratio, safety_factor": "1",
                "deflection, outer_diameter, wall": "m",
                "mass": "kg",
            },
        }
