"""Render a design's URDF, load it in Pinocchio, and check a foot against eq 7.

Run: python examples/01_urdf_and_kinematics.py
"""

import numpy as np

import hexaleg


def main() -> None:
    """Run the example and print what it shows."""
    design = hexaleg.HexapodDesign.from_ratios(l1_ratio=0.1, l3_ratio=0.45, total=1.0)
    print(
        f"segments l1, l2, l3 = {design.lengths} m; body stands {design.nominal_height:.3f} m high"
    )

    urdf = hexaleg.render_hexapod(design)
    joints = urdf.count('type="revolute"')
    print(f"URDF: {len(urdf):,} characters, {joints} revolute joints")

    leg = hexaleg.LegModel(design)  # one leg on a fixed base: its world frame is the leg root
    theta = np.array([0.2, 0.4, -1.2])  # θ1, θ2, θ3 [rad]
    pinocchio_foot = leg.foot_position(theta)
    closed_form_foot = hexaleg.foot_position(design.lengths, theta)
    print(f"foot by Pinocchio:  {np.round(pinocchio_foot, 6)} m")
    print(f"foot by eq 7:       {np.round(closed_form_foot, 6)} m")
    print(f"difference: {np.abs(pinocchio_foot - closed_form_foot).max():.1e} m")

    solution = hexaleg.inverse_kinematics(design.lengths, closed_form_foot)
    print(
        f"inverse kinematics: θ = {np.round(solution.theta, 6)} rad, "
        f"reachable = {bool(solution.reachable)}"
    )

    robot = hexaleg.HexapodModel(design)  # the whole hexapod on a free-flyer joint
    feet = robot.foot_positions(robot.nominal_configuration())
    print(f"nominal stance: highest foot at z = {feet[:, 2].max():.1e} m (on the ground)")


if __name__ == "__main__":
    main()
