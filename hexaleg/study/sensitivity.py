"""How the FB peak moves with what the paper leaves open: posture and body size.

Each variant changes the base design; the study of that variant is run in this
process with the vectorized axis-locked kernel (~5 ms per design) and reduced to
its peak tibia ratio and FB per coxa ratio.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import pandas as pd

from hexaleg._typing import StanceSet
from hexaleg.design import HexapodDesign
from hexaleg.study.sweep import StudySpec, peak_table, sweep_in_process

SENSITIVITY_VARIANTS: tuple[tuple[str, dict[str, Any]], ...] = (
    ("default", {}),
    ("hip raised 0.2 rad", {"nominal_angles": (0.0, 0.2, -math.pi / 2 - 0.2)}),
    ("hip lowered 0.2 rad", {"nominal_angles": (0.0, -0.2, -math.pi / 2 + 0.2)}),
    ("knee bent 0.3 rad more", {"nominal_angles": (0.0, 0.0, -math.pi / 2 - 0.3)}),
    ("knee opened 0.3 rad", {"nominal_angles": (0.0, 0.0, -math.pi / 2 + 0.3)}),
    ("body 0.8 m long", {"body_length": 0.8, "mounts": None}),
    ("body 1.2 m long", {"body_length": 1.2, "mounts": None}),
    ("body 0.8 m wide", {"body_width": 0.8, "mounts": None}),
)
"""Posture and body changes the paper leaves open, each against the default design."""


def sensitivity_table(
    l1_ratios: Sequence[float],
    l3_ratios: Sequence[float],
    total: float = 1.0,
    stance: StanceSet = "all",
    base: HexapodDesign | None = None,
    variants: Sequence[tuple[str, dict[str, Any]]] = SENSITIVITY_VARIANTS,
) -> pd.DataFrame:
    """Peak tibia ratio and FB per coxa ratio for each posture/body variant (axis-locked).

    Runs in this process with the vectorized kernel: ~5 ms per design.
    """
    base = HexapodDesign() if base is None else base
    rows = []
    for name, changes in variants:
        variant = base.replace(**changes)
        spec = StudySpec(tuple(l1_ratios), tuple(l3_ratios), total, "axis", stance, variant)
        table = sweep_in_process(spec)
        for peak in peak_table(table).to_dict(orient="records"):
            rows.append(
                {"variant": name, **peak, "failed_designs": int((table["error"] != "").sum())}
            )
    return pd.DataFrame(rows)
