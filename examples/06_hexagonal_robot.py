"""A hexagonal robot read from a design file: its flexibility, loads and body-radius trade-off.

The robot lives in ``hexagon_robot.toml`` next to this script (a designer keeps it in
version control); every ``hexaleg`` command reads it with ``--design``.

Run: python examples/06_hexagonal_robot.py
"""

import math
from pathlib import Path

import numpy as np

from hexaleg.design_file import load_design
from hexaleg.field_sweep import FieldSweep
from hexaleg.stance import flexibility
from hexaleg.statics.loads import analyze_loads
from hexaleg.study.sensitivity import sensitivity_table

DESIGN_FILE = Path(__file__).with_name("hexagon_robot.toml")


def main() -> None:
    """Run the example and print what it shows."""
    design = load_design(DESIGN_FILE)
    print(f"{DESIGN_FILE.name}: {design.body_description}")
    print(
        f"  legs l1, l2, l3 = {design.l1:g}, {design.l2:g}, {design.l3:g} m, "
        f"standing {design.nominal_height:.3f} m high, {design.total_mass:.1f} kg"
    )
    for mount in design.legs:
        print(f"  {mount.name}: root at ({mount.x:+.3f}, {mount.y:+.3f}) m, "
              f"pointing {math.degrees(mount.yaw):+6.1f}°")  # fmt: skip

    result = flexibility(design, mode="axis", stance="all")
    print(f"axis-locked FB = {result.fb:.4f}")
    for extreme in result.extremes[::2]:  # the + side of each axis
        print(f"  {extreme.axis:>5} +: {extreme.value:.4f}, stopped by {extreme.description}")

    loads = analyze_loads(design)
    capacity = loads.capacity
    print(
        f"payload capacity {capacity.mass:.1f} kg (limited by {capacity.limited_by}); "
        f"stability margin {loads.nominal.stability_margin:.3f} m"
    )

    box = design.replace(layout="rectangle")  # the same legs on hexaleg's default box
    print(f"the same legs on hexaleg's default box: FB = {flexibility(box).fb:.4f}")

    sweep = FieldSweep("body_radius", 0.25, 0.45, 5)
    table = sensitivity_table(
        (design.l1 / design.leg_length,),
        tuple(np.linspace(0.2, 0.6, 9)),
        design.leg_length,
        base=design,
        variants=sweep.variants(),
    )
    print("FB peak against body radius (axis-locked, coxa ratio fixed):")
    for row in table.to_dict(orient="records"):
        print(f"  {row['variant']}: peak FB {row['peak_fb']:.4f} at l3 ratio "
              f"{row['peak_l3_ratio']:.2f}")  # fmt: skip


if __name__ == "__main__":
    main()
