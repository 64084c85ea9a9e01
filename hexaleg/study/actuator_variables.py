"""The actuator variables of a search: each joint type's catalog entry and gear ratio.

``--choose-actuators`` adds one categorical variable per joint type (``actuator_root``,
``actuator_hip``, ``actuator_knee``): a point's coordinate in [0, K) picks the catalog's
⌊x⌋-th of its K actuators. ``--free-gear-ratio`` adds one more per joint type
(``gear_ratio_root``, ``gear_ratio_hip``, ``gear_ratio_knee``): a coordinate u ∈ [0, 1]
that puts the chosen entry's gear ratio at N_low·(N_high/N_low)^u within its
``gear_ratio_range`` (a gear ratio is searched on a log scale; the ratings follow
:meth:`~hexaleg.actuators.Actuator.with_gear_ratio`); an entry without a range keeps its
ratio.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from hexaleg.actuators import Actuator
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import ParameterError
from hexaleg.limits import LEG_JOINTS

CHOICES = tuple(f"actuator_{joint}" for joint in LEG_JOINTS)
"""The categorical variables of ``--choose-actuators``: each joint type's catalog entry."""

GEARS = tuple(f"gear_ratio_{joint}" for joint in LEG_JOINTS)
"""The gear ratios of ``--free-gear-ratio``: each joint type's within its entry's range."""

Entries = Sequence[Actuator]
"""The actuators a choice picks from, in the catalog's order."""
Ranges = Sequence[tuple[float, float] | None]
"""Each entry's lowest and highest gear ratio [-] (None: its own only), or none at all."""


def geared_entry(entries: Entries, ranges: Ranges, pick: int, share: float | None) -> Actuator:
    """Entry ``pick``, at the gear ratio ``share`` ∈ [0, 1] of its range puts it at."""
    entry = entries[pick]
    span = ranges[pick] if ranges else None
    if span is None or share is None:
        return entry
    low, high = span
    return entry.with_gear_ratio(low * (high / low) ** min(max(share, 0.0), 1.0))


def _entry_of(entries: Entries, ranges: Ranges, design: HexapodDesign, joint: str) -> int | None:
    """The entry ``design``'s actuator of ``joint`` is, at any gear ratio (None: none)."""
    given = design.actuators
    if given is None:
        return None
    actuator = getattr(given, joint)
    if actuator in entries:
        return entries.index(actuator)
    for index, entry in enumerate(entries):
        span = ranges[index] if ranges else None
        if span is None or entry.catalog is None or entry.catalog != actuator.catalog:
            continue
        if span[0] <= actuator.gear_ratio <= span[1]:
            if entry.with_gear_ratio(actuator.gear_ratio) == actuator:
                return index
    return None


def choice_coordinate(entries: Entries, ranges: Ranges, design: HexapodDesign, name: str) -> float:
    """The coordinate that picks ``design``'s actuator (the first entry's if not one)."""
    index = _entry_of(entries, ranges, design, name.removeprefix("actuator_"))
    return 0.5 if index is None else index + 0.5


def gear_coordinate(entries: Entries, ranges: Ranges, design: HexapodDesign, name: str) -> float:
    """The coordinate of ``design``'s gear ratio within its entry's range (0.5 if none)."""
    joint = name.removeprefix("gear_ratio_")
    index = _entry_of(entries, ranges, design, joint)
    span = None if index is None else ranges[index]
    if design.actuators is None or span is None or span[0] == span[1]:
        return 0.5
    ratio = getattr(design.actuators, joint).gear_ratio
    return math.log(ratio / span[0]) / math.log(span[1] / span[0])


def ratio_spans(
    actuators: Sequence[Actuator], ranges: Sequence[tuple[float, float] | None]
) -> tuple[tuple[float, float] | None, ...]:
    """``ranges``, one per actuator, each holding its actuator's own ratio."""
    if not actuators:
        raise ParameterError("--free-gear-ratio", True, "frees the chosen actuators' ratios: "
                             "give --choose-actuators")  # fmt: skip
    if len(ranges) != len(actuators):
        raise ParameterError("ratio_ranges", len(ranges), f"one per actuator ({len(actuators)})")
    for actuator, span in zip(actuators, ranges, strict=True):
        if span is not None and not span[0] <= actuator.gear_ratio <= span[1]:
            raise ParameterError(
                "ratio_ranges", span, f"must hold the actuator's ratio {actuator.gear_ratio:g}"
            )
    return tuple(ranges)


def actuator_bounds(
    actuators: Entries, ranges: Ranges | None
) -> tuple[dict[str, tuple[float, float]], tuple[tuple[float, float] | None, ...]]:
    """The choices' bounds (and the gear ratios', given ``ranges``) by name; the ranges."""
    bounds = {name: (0.0, float(len(actuators))) for name in CHOICES} if actuators else {}
    if ranges is None:
        return bounds, ()
    spans = ratio_spans(actuators, ranges)
    if any(span is not None for span in spans):
        bounds |= {name: (0.0, 1.0) for name in GEARS}
    return bounds, spans
