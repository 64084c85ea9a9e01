"""Workload: reading a user's hexapod from its URDF (tree, six legs, feet, general legs)."""

from __future__ import annotations

from pathlib import Path

from harness import Row, median_time

from hexaleg.robot.imported import robot_from_text

KRABY = (
    Path(__file__).resolve().parent.parent / "tests" / "data" / "robots" / "kraby" / "hexapod.urdf"
)
SIZE = 50_000
"""Bytes of URDF to read: the Kraby description padded with top-level materials."""


def bench_import(repeats: int) -> list[Row]:
    """Import of a 50 kB URDF (target ≤ 1 s)."""
    text = KRABY.read_text()
    pad = []
    while len(text) + sum(map(len, pad)) < SIZE:
        pad.append(f'  <material name="m{len(pad)}"><color rgba="0.2 0.2 0.2 1.0"/></material>\n')
    end = text.rindex("</robot>")
    text = text[:end] + "".join(pad) + text[end:]
    seconds = median_time(lambda: robot_from_text(text), repeats)
    name = f"import a hexapod URDF, {len(text) // 1000} kB"
    return [Row(name, "hexaleg robot_from_text", seconds, None, None, target="≤ 1 s")]
