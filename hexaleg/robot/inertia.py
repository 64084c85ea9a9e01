"""Every link's mass, centre of mass and rotational inertia, computed once from the design.

The Xacro templates receive these numbers and only place them; the sweeps' fast path
(:meth:`~hexaleg.robot.model.HexapodModel.with_design`) builds its Pinocchio inertias
from the same ones. Links are solids of uniform density: the coxa, femur and tibia are
cylinders along +x of their link frame (the tibia thinner, :data:`TIBIA_RADIUS_RATIO`) of
the design's ``link_linear_density``, or with a ``[structure]`` the segment's round tube
of its material (:mod:`hexaleg.leg_structure`), the foot a small sphere at the tibia tip,
the body a box or a cylinder about z.

The design's actuators and battery are point masses on the links that carry them
(:func:`with_points`): each joint's actuator at that joint's origin, on the link before
the joint (the root motors on the body at the leg mounts, the hip motor at the coxa's
end, the knee motor at the femur's end), the battery on the body at ``battery_at``.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._typing import ArrayF
from hexaleg.design import FOOT_MASS, HexapodDesign

TIBIA_RADIUS_RATIO = 0.8
"""Tibia radius over the design's ``link_radius`` [-]: the leg narrows toward the foot."""

LEG_LINKS: tuple[str, str, str, str] = ("coxa", "femur", "tibia", "foot")
"""A leg's links, from the body out."""


@dataclass(frozen=True)
class LinkInertial:
    """A link's inertial, in its own link frame.

    Attributes:
        mass: Mass [kg].
        com_x: Centre of mass along the link frame's x axis [m].
        moments: Moments of inertia (ixx, iyy, izz) about the centre of mass [kg·m²].
        com_yz: Centre of mass along y and z [m] (zero for a leg's link).
        products: Products of inertia (ixy, ixz, iyz) about the centre of mass, the
            inertia tensor's off-diagonal entries as a URDF writes them [kg·m²].

    """

    mass: float
    com_x: float
    moments: tuple[float, float, float]
    com_yz: tuple[float, float] = (0.0, 0.0)
    products: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def com(self) -> ArrayF:
        """Centre of mass (3,) in the link frame [m]."""
        return np.array([self.com_x, *self.com_yz])

    @property
    def tensor(self) -> ArrayF:
        """The inertia tensor about the centre of mass (3, 3) [kg·m²]."""
        (ixx, iyy, izz), (ixy, ixz, iyz) = self.moments, self.products
        return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])

    def xacro_arguments(self, link: str) -> dict[str, float]:
        """``<link>_mass``, ``<link>_com_x`` .. ``_com_z`` and ``_ixx`` .. ``_iyz``."""
        (ixx, iyy, izz), (ixy, ixz, iyz) = self.moments, self.products
        com_y, com_z = self.com_yz
        values = (self.mass, self.com_x, com_y, com_z, ixx, iyy, izz, ixy, ixz, iyz)
        keys = ("mass", "com_x", "com_y", "com_z", "ixx", "iyy", "izz", "ixy", "ixz", "iyz")
        return {f"{link}_{key}": value for key, value in zip(keys, values, strict=True)}


def with_points(
    inertial: LinkInertial, points: Sequence[tuple[float, Sequence[float]]]
) -> LinkInertial:
    """``inertial`` with point masses added: the whole's mass, centre and tensor.

    Args:
        inertial: The link's own inertial.
        points: (mass [kg], position (3,) in the link frame [m]) of each point mass.

    """
    points = [(float(m), p) for m, p in points if m > 0]
    if not points:
        return inertial
    masses = np.array([inertial.mass] + [m for m, _ in points])
    places = np.array([inertial.com] + [np.asarray(p, dtype=float) for _, p in points])
    total = float(masses.sum())
    com = masses @ places / total
    offsets = places - com
    tensor = inertial.tensor + sum(
        m * (d @ d * np.eye(3) - np.outer(d, d)) for m, d in zip(masses, offsets, strict=True)
    )
    return LinkInertial(
        total,
        float(com[0]),
        (float(tensor[0, 0]), float(tensor[1, 1]), float(tensor[2, 2])),
        (float(com[1]), float(com[2])),
        (float(tensor[0, 1]), float(tensor[0, 2]), float(tensor[1, 2])),
    )


def rod(length: float, radius: float, density: float, inner_radius: float = 0.0) -> LinkInertial:
    """A cylinder from the link origin along +x, solid or a tube of uniform wall.

    About its centre a tube of mass m, radii R and r and length l has the moment
    m·(R² + r²)/2 about its axis and m·(3·(R² + r²) + l²)/12 across it (r = 0: solid).

    Args:
        length: Its length l [m].
        radius: Its (outer) radius R [m].
        density: Its mass per length [kg/m].
        inner_radius: Its bore's radius r [m] (0: a solid rod).

    """
    mass = density * length
    squares = radius * radius + inner_radius * inner_radius
    side = mass * (3 * squares + length * length) / 12
    return LinkInertial(mass, length / 2, (mass * squares / 2, side, side))


def segment_radii(design: HexapodDesign) -> tuple[float, float, float]:
    """Each segment's radius as drawn (coxa, femur, tibia) [m].

    The outer radius of its ``[structure]`` tube; without one, ``link_radius`` (the tibia
    :data:`TIBIA_RADIUS_RATIO` of it).
    """
    tubes = (None, None, None) if design.structure is None else design.structure.tubes
    plain = (design.link_radius, design.link_radius, TIBIA_RADIUS_RATIO * design.link_radius)
    coxa, femur, tibia = (
        radius if tube is None else tube.outer_diameter / 2
        for tube, radius in zip(tubes, plain, strict=True)
    )
    return (coxa, femur, tibia)


def segment_rods(design: HexapodDesign) -> tuple[LinkInertial, ...]:
    """The coxa's, femur's and tibia's own inertials (without the actuators they carry)."""
    structure = design.structure
    tubes = (None, None, None) if structure is None else structure.tubes
    rods = []
    for length, radius, tube in zip(design.lengths, segment_radii(design), tubes, strict=True):
        if tube is None or structure is None:
            rods.append(rod(length, radius, design.link_linear_density))
        else:
            density = tube.linear_density(structure.material)
            rods.append(rod(length, radius, density, tube.inner_diameter / 2))
    return tuple(rods)


def sphere(mass: float, radius: float) -> LinkInertial:
    """A solid sphere centred on the link origin, of ``mass`` [kg] and ``radius`` [m]."""
    moment = 0.4 * mass * radius * radius
    return LinkInertial(mass, 0.0, (moment, moment, moment))


def leg_inertials(design: HexapodDesign) -> dict[str, LinkInertial]:
    """The inertial of each of a leg's :data:`LEG_LINKS` (every leg is the same).

    The coxa carries the hip's actuator at its end, the femur the knee's.
    """
    hip, knee = (0.0, 0.0) if design.actuators is None else design.actuators.masses[1:]
    coxa, femur, tibia = segment_rods(design)
    return {
        "coxa": with_points(coxa, [(hip, (design.l1, 0.0, 0.0))]),
        "femur": with_points(femur, [(knee, (design.l2, 0.0, 0.0))]),
        "tibia": tibia,
        "foot": sphere(FOOT_MASS, design.link_radius),
    }


def body_inertial(design: HexapodDesign) -> LinkInertial:
    """The body's inertial: its solid, the root joints' actuators and the battery."""
    points: list[tuple[float, Sequence[float]]] = []
    if design.actuators is not None:
        points += [(design.actuators.root.mass, (m.x, m.y, m.z)) for m in design.legs]
    if design.battery is not None:
        points.append((design.battery.mass, design.battery.battery_at))
    return with_points(body_solid(design), points)


def body_solid(design: HexapodDesign) -> LinkInertial:
    """The body's solid alone: a box, or for the hexagon layout a cylinder about z."""
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


def pinocchio_inertia(inertial: LinkInertial, offset: float = 0.0) -> pin.Inertia:
    """``inertial`` as Pinocchio's, its link frame ``offset`` [m] along x of the joint's."""
    com = inertial.com + np.array([offset, 0.0, 0.0])
    return pin.Inertia(inertial.mass, com, inertial.tensor)


def set_armature(
    model: pin.Model, legs: Iterable[npt.NDArray[np.int_]], design: HexapodDesign
) -> None:
    """Each leg joint's armature: its actuator's reflected rotor inertia N²·J [kg·m²].

    ``legs``: each leg's velocity indices (root, hip, knee). Pinocchio's dynamics (RNEA,
    CRBA, ABA) add armature·q̈ to each joint's torque; a design without actuators has none.
    """
    armatures = (0.0, 0.0, 0.0) if design.actuators is None else design.actuators.armatures
    for indices in legs:
        model.armature[indices] = armatures
