"""The swing-phase analysis of one leg: workspace areas and manipulability (paper §4–5).

Run: python examples/02_workspace_and_manipulability.py
"""

import math

import hexaleg
from hexaleg.swing.manipulability import analyze_manipulability
from hexaleg.swing.workspace import analyze_workspace


def main() -> None:
    """Run the example and print what it shows."""
    design = hexaleg.HexapodDesign(l1=0.05, l2=0.475, l3=0.475)  # Table 5, first row

    area = analyze_workspace(design, samples=5000).to_dict()["area"]
    print(
        f"improved workspace area: {area['improved']:.6f} m² "
        f"(eq 16: {area['improved_closed_form']:.6f} m²)"
    )
    print(f"rectangular workspace area: {area['rectangular']:.6f} m²")

    result = analyze_manipulability(design)
    optimum = result.optimum
    print(
        f"optimum pose: θ2 = {math.degrees(optimum.theta2):.4f}°, "
        f"θ3 = {math.degrees(optimum.theta3):.4f}° (paper, Table 6: 35.6827°, -71.3655°)"
    )
    print(
        f"optimum w = {optimum.w * 1e9:.5e} mm³ "
        "(the paper prints 1.7576e+08; eq 25 at its own angles gives 1.7567e+08)"
    )
    print(
        f"average manipulability w_A: {result.average_rectangular:.5f} m³ (rectangle), "
        f"{result.average_improved:.5f} m³ (improved domain)"
    )


if __name__ == "__main__":
    main()
