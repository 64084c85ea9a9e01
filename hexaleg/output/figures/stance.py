"""A still of the robot at its nominal stance: the 3-D view's scene, for print."""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING

import numpy as np

from hexaleg.output.figures.canvas import COLORS, drawn, new_figure
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.geometry import body_collision_shape

if TYPE_CHECKING:
    from matplotlib.figure import Figure


@drawn
def stance_figure(model: HexapodModel) -> Figure:
    """The robot at its nominal stance in 3-D: the body, each leg's joints and foot, the ground.

    Read from the Pinocchio model (the URDF's geometry), as the 3-D view draws it.
    """
    from matplotlib.ticker import MaxNLocator

    q = model.nominal_configuration()
    chains = model.leg_chains(q)
    fig = new_figure(4.8)
    ax = fig.add_subplot(projection="3d")
    half, round_body = body_collision_shape(model)
    centre = q[:3]
    if round_body:
        angle = np.linspace(0, 2 * np.pi, 61)
        for z in (-half[2], half[2]):
            ax.plot(centre[0] + half[0] * np.cos(angle), centre[1] + half[1] * np.sin(angle),
                    centre[2] + z, color="0.3", lw=1)  # fmt: skip
    else:
        corners = np.array(list(itertools.product(*[(-h, h) for h in half])))
        for a, b in itertools.combinations(range(8), 2):
            if np.count_nonzero(corners[a] != corners[b]) == 1:  # an edge of the box
                ax.plot(*(centre + np.stack((corners[a], corners[b]))).T, color="0.3", lw=1)
    for leg, chain, color in zip(model.leg_names, chains, itertools.cycle(COLORS), strict=False):
        ax.plot(*chain.T, color=color, lw=2.2, marker="o", markersize=3, label=leg)
        ax.scatter(*chain[-1], color="k", s=14)
    feet = chains[:, -1]
    reach = np.abs(feet[:, :2]).max() * 1.15
    ground = np.array([[-reach, -reach], [reach, -reach], [reach, reach], [-reach, reach],
                       [-reach, -reach]])  # fmt: skip
    ax.plot(ground[:, 0], ground[:, 1], 0.0, color="0.6", lw=0.8)
    ax.set_box_aspect((1.0, 1.0, max(0.3, (centre[2] + half[2]) / (2 * reach))))  # true scale
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_zlim(0.0, centre[2] + half[2])
    ax.zaxis.set_major_locator(MaxNLocator(3))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    ax.view_init(elev=30, azim=-58)
    ax.legend(loc="upper left", ncols=2, title="leg", fontsize=7.5)
    ax.set_title(f"The nominal stance, body {centre[2]:.3g} m above the ground (feet in black)")
    return fig
