"""Body flexibility with the feet planted: the 12 extremes, what stops each, and FB (paper §6).

Run: python examples/03_body_flexibility.py
"""

import math

import hexaleg
from hexaleg.stance import flexibility


def main() -> None:
    """Run the example and print what it shows."""
    design = hexaleg.HexapodDesign()  # the paper's 0.2 / 0.4 / 0.4 m leg on hexaleg's body
    for stance in ("all", "tripod"):
        result = flexibility(design, mode="axis", stance=stance)
        print(f"stance {stance}: FB = {result.fb:.4f}")
    result = flexibility(design, mode="axis", stance="all")
    for extreme in result.extremes:
        value = extreme.value if extreme.axis in ("x", "y", "z") else math.degrees(extreme.value)
        unit = "m" if extreme.axis in ("x", "y", "z") else "°"
        print(f"  {extreme.name:>6}: {value:+8.4f} {unit:<2} stopped by {extreme.limited_by}")
    free = flexibility(design, mode="free", stance="all")
    print(f"free-coupled (the other five coordinates help): FB = {free.fb:.4f}")


if __name__ == "__main__":
    main()
