"""Every link's mass, centre of mass and rotational inertia, computed once from the design.

The Xacro templates receive these numbers and only place them; the sweeps' fast path
(:meth:`~hexaleg.robot.model.HexapodModel.with_design`) builds its Pinocchio inertias
from the same ones. Links are solids of uniform density: the coxa, femur and tibia are
cylinders along +x of their link frame (the tibia thinner, :data:`TIBIA_RADIUS_RATIO`),
the foot a small sphere at the tibia tip, the body a box or a cylinder about z.
"""

from __future__ import annotations

from dataclasses import dataclass

from hexaleg.design import FOOT_MASS, HexapodDesign

TIBIA_RADIUS_RATIO = 0.8
"""Tibia radius over the design's ``link_radius`` [-]: the leg narrows toward the foot."""

LEG_LINKS: tuple[str, str, str, str] = ("coxa", "femur", "tibia", "foot")
"""A leg's links, from the body out."""


@dataclass(frozen=True)
class LinkInertial:
    """A link's inertial, in its own link frame, principal axes along the frame's.

    Attributes:
        mass: Mass [kg].
        com_x: Centre of mass along the link frame's x axis [m] (y = z = 0).
        moments: Moments of inertia (ixx, iyy, izz) about the centre of mass [kg·m²].

    """

    mass: float
    com_x: float
    moments: tuple[float, float, float]

    def xacro_arguments(self, link: str) -> dict[str, float]:
        """``<link>_mass``, ``<link>_com_x`` and ``<link>_ixx`` .. ``_izz``, as numbers."""
        ixx, iyy, izz = self.moments
        return {
            f"{link}_mass": self.mass,
            f"{link}_com_x": self.com_x,
            f"{link}_ixx": ixx,
            f"{link}_iyy": iyy,
            f"{link}_izz": izz,
        }


def rod(length: float, radius: float, density: float) -> LinkInertial:
    """A solid cylinder from the link origin along +x.

    Args:
        length: Its length [m].
        radius: Its radius [m].
        density: Its mass per length [kg/m].

    """
    mass = density * length
    side = mass * (3 * radius * radius + length * length) / 12
    return LinkInertial(mass, length / 2, (mass * radius * radius / 2, side, side))


def sphere(mass: float, radius: float) -> LinkInertial:
    """A solid sphere centred on the link origin, of ``mass`` [kg] and ``radius`` [m]."""
    moment = 0.4 * mass * radius * radius
    return LinkInertial(mass, 0.0, (moment, moment, moment))


def leg_inertials(design: HexapodDesign) -> dict[str, LinkInertial]:
    """The inertial of each of a leg's :data:`LEG_LINKS` (every leg is the same)."""
    radius, density = design.link_radius, design.link_linear_density
    return {
        "coxa": rod(design.l1, radius, density),
        "femur": rod(design.l2, radius, density),
        "tibia": rod(design.l3, TIBIA_RADIUS_RATIO * radius, density),
        "foot": sphere(FOOT_MASS, radius),
    }


def body_inertial(design: HexapodDesign) -> LinkInertial:
    """The body's inertial: a box, or for the hexagon layout a cylinder about z."""
    mass, height = design.body_mass, design.body_height
    if design.body_shape == "cylinder":
        radius = design.body_radius
        across = mass * (3 * radius * radius + height * height) / 12
        return LinkInertial(mass, 0.0, (across, across, mass * radius * radius / 2))
    length, width = design.body_length, design.body_width
    return LinkInertial(
        mass,
        0.0,
        (
            mass * (width * width + height * height) / 12,
            mass * (length * length + height * height) / 12,
            mass * (length * length + width * width) / 12,
        ),
    )
