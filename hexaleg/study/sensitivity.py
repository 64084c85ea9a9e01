"""How the FB peak moves with what the paper leaves open: posture, body size, any body field.

Each variant changes the base design: by default the posture and body changes of
:func:`relative_variants`, or one body field swept over a range (:func:`field_variants`,
``--sweep body_width=0.4:0.8:9``); the study of that variant is run in this
process with the vectorized axis-locked kernel (~5 ms per design) and reduced to
its peak tibia ratio and FB per coxa ratio.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import pandas as pd

from hexaleg._typing import StanceSet
from hexaleg.design import DEFAULT_LEG_LENGTH, HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.field_sweep import Variant
from hexaleg.study.progress import Progress
from hexaleg.study.rows import Key, StudyRow
from hexaleg.study.sweep import StudySpec, peak_table, sweep_in_process


def relative_variants(base: HexapodDesign) -> tuple[Variant, ...]:
    """Posture and body changes the paper leaves open, each relative to ``base``.

    The hip raised or lowered by 0.2 rad (the knee compensating so the tibia keeps its
    direction), the knee bent or opened by 0.3 rad, and the body 20 % longer, shorter,
    wider or narrower, with the legs following the body's corners (a hexagonal body: its
    radius 20 % smaller or larger).
    """
    t1, t2, t3 = base.nominal_angles
    length, width = base.body_length, base.body_width
    if base.layout == "hexagon":
        radius = base.body_radius
        body: tuple[Variant, ...] = (
            (f"body 20 % smaller ({0.8 * radius:.3g} m radius)", {"body_radius": 0.8 * radius}),
            (f"body 20 % larger ({1.2 * radius:.3g} m radius)", {"body_radius": 1.2 * radius}),
        )
    else:
        body = (
            (f"body 20 % shorter ({0.8 * length:.3g} m)", {"body_length": 0.8 * length}),
            (f"body 20 % longer ({1.2 * length:.3g} m)", {"body_length": 1.2 * length}),
            (f"body 20 % narrower ({0.8 * width:.3g} m)", {"body_width": 0.8 * width}),
            (f"body 20 % wider ({1.2 * width:.3g} m)", {"body_width": 1.2 * width}),
        )
    return (
        ("your design", {}),
        ("hip raised 0.2 rad", {"nominal_angles": (t1, t2 + 0.2, t3 - 0.2)}),
        ("hip lowered 0.2 rad", {"nominal_angles": (t1, t2 - 0.2, t3 + 0.2)}),
        ("knee bent 0.3 rad more", {"nominal_angles": (t1, t2, t3 - 0.3)}),
        ("knee opened 0.3 rad", {"nominal_angles": (t1, t2, t3 + 0.3)}),
        *body,
    )


def sensitivity_table(
    l1_ratios: Sequence[float],
    l3_ratios: Sequence[float],
    total: float = DEFAULT_LEG_LENGTH,
    stance: StanceSet = "all",
    base: HexapodDesign | None = None,
    variants: Sequence[Variant] | None = None,
    progress: bool | None = None,
    known: pd.DataFrame | None = None,
) -> pd.DataFrame:
    """Peak tibia ratio and FB per coxa ratio for each posture/body variant (axis-locked).

    Runs in this process with the vectorized kernel: ~5 ms per design. A variant whose
    posture leaves the stance limits or cannot stand gives NaN peaks and says why.

    Args:
        l1_ratios: Coxa ratios [-].
        l3_ratios: Tibia ratios [-].
        total: Total leg length [m].
        stance: Stance legs.
        base: The design the variants change (default: hexaleg's default design).
        variants: Names and changes; by default :func:`relative_variants` of ``base``.
        progress: ``False`` shows nothing; otherwise a bar on stderr if it is a terminal,
            else a line every few seconds, naming the variant being swept.
        known: Rows of ``base`` itself already measured the same way (a study's table,
            axis-locked on ``stance``, without collisions): a variant that changes nothing
            takes its designs' FB from them instead of measuring them again.

    """
    base = HexapodDesign() if base is None else base
    chosen = list(relative_variants(base) if variants is None else variants)
    total_designs = len(chosen) * len(l1_ratios) * len(l3_ratios)
    rows: list[dict[str, object]] = []
    with Progress(total_designs, unit="designs", show=progress) as shown:
        for variant in chosen:
            rows += _variant_rows(variant, l1_ratios, l3_ratios, total, stance, base, shown, known)
    return pd.DataFrame(rows)


def _known(spec: StudySpec, table: pd.DataFrame | None) -> dict[Key, StudyRow]:
    """The rows of ``table`` at the keys of ``spec``, by ``spec``'s own key."""
    if table is None or table.empty:
        return {}
    found = {}
    r1, r3 = table["l1_ratio"].to_numpy(float), table["l3_ratio"].to_numpy(float)
    records = table.to_dict(orient="records")
    for key in spec.keys():
        at = np.flatnonzero(np.isclose(r1, key[0], rtol=0, atol=1e-12)
                            & np.isclose(r3, key[1], rtol=0, atol=1e-12))  # fmt: skip
        if at.size:
            found[key] = replace(StudyRow.from_dict(records[at[0]]), l1_ratio=key[0],
                                 l3_ratio=key[1])  # fmt: skip
    return found


def _variant_rows(
    variant: Variant,
    l1_ratios: Sequence[float],
    l3_ratios: Sequence[float],
    total: float,
    stance: StanceSet,
    base: HexapodDesign,
    shown: Progress,
    known: pd.DataFrame | None,
) -> list[dict[str, object]]:
    """The sensitivity table's rows of one variant: its peak per coxa ratio.

    Only FB is measured (no statics, no gait); a variant that changes nothing takes the
    rows of ``known`` on its grid.
    """
    name, changes = variant
    shown.update(0, doing=f"sensitivity, {name}")
    try:
        changed = base.replace(**changes)
    except HexalegError as err:
        shown.update(len(l1_ratios) * len(l3_ratios))
        return [
            {
                "variant": name,
                "l1_ratio": r1,
                "peak_l3_ratio": math.nan,
                "peak_fb": math.nan,
                "failed_designs": len(l3_ratios),
                "note": str(err),
            }
            for r1 in l1_ratios
        ]
    spec = StudySpec(
        tuple(l1_ratios),
        tuple(l3_ratios),
        total,
        "axis",
        stance,
        changed,
        statics=False,
        gait=False,
    )
    table = sweep_in_process(spec, _known(spec, known) if not changes else None)
    shown.update(len(l1_ratios) * len(l3_ratios))
    rows: list[dict[str, object]] = []
    for peak in peak_table(table).to_dict(orient="records"):
        failed = int(((table["l1_ratio"] == peak["l1_ratio"]) & (table["error"] != "")).sum())
        rows.append({"variant": name, **peak, "failed_designs": failed, "note": ""})
    return rows
