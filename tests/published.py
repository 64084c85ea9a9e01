"""Small hexapods written as their authors publish them: a ROS package tree, CAD-exporter style.

:func:`write_package` writes ``<root>/<folder>/package.xml`` (its ``<name>`` may differ from
the folder's), ``urdf/<robot>.urdf`` and ``meshes/*.STL`` (binary, in metres), the URDF
naming its meshes ``package://<name>/meshes/...`` as the SolidWorks exporter writes them,
with the exporter's habits on request: limits ``[0, 0]``, ``effort="0" velocity="0"``, mount
heights off by round-off, a foot-contact sensor on a prismatic joint beyond the knee.

Every leg is drawn from known numbers (:class:`Spider`): a root at ``radius`` around the body
at its ``angles``, the coxa along the root's x, the hip axis turned onto −y by a roll of π/2
(a positive hip angle lifts the femur, as hexaleg's θ2), the tibia hanging straight down at
q = 0, so that q = 0 is hexaleg's θ = (0, 0, −π/2), its feet found on the tibia mesh's tip.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

ROUND_OFF_HEIGHT = 0.97e-6
"""A mount raised by what a CAD export's round-off leaves [m] (the issue's SolidWorks file)."""


@dataclass(frozen=True)
class Spider:
    """The numbers a written hexapod is drawn from [m, rad, kg].

    Attributes:
        coxa: Yaw axis to hip axis.
        femur: Hip axis to knee axis.
        tibia: Knee axis to the foot (straight down at q = 0).
        radius: Leg roots' distance from the body's centre.
        angles: Each root's direction around the body (the coxa points the same way).
        yaws: Each coxa's direction at q = 0 (default: its root's direction).
        roots: Each root's (x, y) (default: ``radius`` along its angle).
        heights: Each root's height above the root link's origin.
        limits: (lower, upper) of every joint as written (the exporter's default [0, 0]).
        effort: Every joint's ``effort`` as written (0: the exporter's default).
        velocity: Every joint's ``velocity`` as written.
        sensor: A foot-contact sensor: a prismatic joint ±0.1 mm below each tibia.
        body: The base link's collision: ``"mesh"`` (a box STL), ``"box"``, or ``None``.
        body_size: The body box's size (x, y, z), centred on the root link.
        masses: Body, coxa, femur, tibia link masses.
        longer: Each leg's femur drawn this much longer than ``femur``.

    """

    coxa: float = 0.04
    femur: float = 0.06
    tibia: float = 0.1
    radius: float = 0.09
    angles: tuple[float, ...] = tuple(
        math.radians(a) for a in (30.0, 90.0, 150.0, -150.0, -90.0, -30.0)
    )
    yaws: tuple[float, ...] | None = None
    roots: tuple[tuple[float, float], ...] | None = None
    heights: tuple[float, ...] = (0.0,) * 6
    limits: tuple[float, float] = (0.0, 0.0)
    effort: float = 0.0
    velocity: float = 0.0
    sensor: bool = False
    body: str | None = "mesh"
    body_size: tuple[float, float, float] = (0.16, 0.12, 0.03)
    masses: tuple[float, float, float, float] = (1.2, 0.05, 0.08, 0.06)
    longer: tuple[float, ...] = (0.0,) * 6
    joint_names: tuple[str, ...] = field(default=("coxa", "femur", "tibia"))

    def root(self, k: int) -> tuple[float, float]:
        """Leg ``k``'s root (x, y) [m]."""
        if self.roots is not None:
            return self.roots[k]
        a = self.angles[k]
        return (self.radius * math.cos(a), self.radius * math.sin(a))

    def yaw(self, k: int) -> float:
        """Leg ``k``'s coxa direction at q = 0 [rad]."""
        return self.angles[k] if self.yaws is None else self.yaws[k]


def write_package(
    root: Path, spider: Spider | None = None, name: str = "spider_description", folder: str = ""
) -> Path:
    """Write the package tree of ``spider`` under ``root``; the URDF's path.

    ``name`` is the package's name (in ``package.xml`` and the ``package://`` references),
    ``folder`` its folder's (default: the name).
    """
    spider = spider or Spider()
    package = root / (folder or name)
    (package / "urdf").mkdir(parents=True, exist_ok=True)
    (package / "meshes").mkdir(exist_ok=True)
    (package / "package.xml").write_text(_manifest(name))
    _write_meshes(package / "meshes", spider)
    urdf = package / "urdf" / "spider.urdf"
    urdf.write_text(spider_urdf(spider, name))
    return urdf


def spider_urdf(spider: Spider, name: str = "spider_description") -> str:
    """The URDF text of ``spider``, its meshes in package ``name``."""
    parts = [
        '<?xml version="1.0" encoding="utf-8"?>',
        "<!-- written by hexaleg's tests in the SolidWorks to URDF Exporter's style -->",
        '<robot name="spider">',
        _link("base_link", spider.masses[0], (0.0, 0.0, 0.0), _body(spider, name)),
    ]
    for k in range(6):
        parts += _leg(spider, k, name)
    parts.append("</robot>")
    return "\n".join(parts) + "\n"


def _manifest(name: str) -> str:
    return (
        '<?xml version="1.0"?>\n<package format="2">\n'
        f"  <name>{name}</name>\n  <version>1.0.0</version>\n"
        "  <description>hexaleg's test hexapod</description>\n"
        '  <maintainer email="tests@example.org">tests</maintainer>\n'
        "  <license>MIT</license>\n  <buildtool_depend>catkin</buildtool_depend>\n"
        "</package>\n"
    )


def _mesh(name: str, part: str) -> str:
    return f'<mesh filename="package://{name}/meshes/{part}.STL"/>'


def _body(spider: Spider, name: str) -> str:
    if spider.body is None:
        return ""
    size = " ".join(repr(v) for v in spider.body_size)
    shape = _mesh(name, "base_link") if spider.body == "mesh" else f'<box size="{size}"/>'
    geometry = f"<geometry>{shape}</geometry>"
    return (
        f'<visual><origin xyz="0 0 0" rpy="0 0 0"/>{geometry}</visual>'
        f'<collision><origin xyz="0 0 0" rpy="0 0 0"/>{geometry}</collision>'
    )


def _link(link: str, mass: float, com: tuple[float, float, float], shapes: str = "") -> str:
    moment = mass * 1e-3
    xyz = " ".join(repr(v) for v in com)
    return (
        f'<link name="{link}"><inertial><origin xyz="{xyz}" rpy="0 0 0"/>'
        f'<mass value="{mass!r}"/><inertia ixx="{moment!r}" ixy="0" ixz="0" iyy="{moment!r}" '
        f'iyz="0" izz="{moment!r}"/></inertial>{shapes}</link>'
    )


def _joint(
    joint: str,
    kind: str,
    parent: str,
    child: str,
    xyz: tuple[float, ...],
    rpy: tuple[float, ...],
    limits: tuple[float, float],
    spider: Spider,
    axis: str = "0 0 1",
) -> str:
    lower, upper = limits
    return (
        f'<joint name="{joint}" type="{kind}"><origin xyz="{" ".join(map(repr, xyz))}" '
        f'rpy="{" ".join(map(repr, rpy))}"/><parent link="{parent}"/><child link="{child}"/>'
        f'<axis xyz="{axis}"/><limit lower="{lower!r}" upper="{upper!r}" '
        f'effort="{spider.effort!r}" velocity="{spider.velocity!r}"/></joint>'
    )


def _leg(spider: Spider, k: int, name: str) -> list[str]:
    leg = f"leg{k + 1}"
    coxa, femur, tibia = (f"{leg}_{part}" for part in ("coxa", "femur", "tibia"))
    x, y = spider.root(k)
    shapes = {
        part: f"<visual><geometry>{_mesh(name, part)}</geometry></visual>"
        f"<collision><geometry>{_mesh(name, part)}</geometry></collision>"
        for part in ("coxa", "femur", "tibia")
    }
    j = spider.joint_names
    out = [
        _joint(
            f"{leg}_{j[0]}_joint",
            "revolute",
            "base_link",
            coxa,
            (x, y, spider.heights[k]),
            (0.0, 0.0, spider.yaw(k)),
            spider.limits,
            spider,
        ),
        _link(coxa, spider.masses[1], (spider.coxa / 2, 0.0, 0.0), shapes["coxa"]),
        # the hip axis: the femur frame's z, a roll of π/2 turns it onto the root's −y
        _joint(
            f"{leg}_{j[1]}_joint",
            "revolute",
            coxa,
            femur,
            (spider.coxa, 0.0, 0.0),
            (math.pi / 2, 0.0, 0.0),
            spider.limits,
            spider,
        ),
        _link(femur, spider.masses[2], (spider.femur / 2, 0.0, 0.0), shapes["femur"]),
        _joint(
            f"{leg}_{j[2]}_joint",
            "revolute",
            femur,
            tibia,
            (spider.femur + spider.longer[k], 0.0, 0.0),
            (0.0, 0.0, 0.0),
            spider.limits,
            spider,
        ),
        # the tibia hangs along the femur frame's −y (down) at q = 0
        _link(tibia, spider.masses[3], (0.0, -spider.tibia / 2, 0.0), shapes["tibia"]),
    ]
    if spider.sensor:
        sensor = f"{leg}_foot_sensor"
        out.append(
            _joint(
                f"{leg}_contact_joint",
                "prismatic",
                tibia,
                sensor,
                (0.0, -spider.tibia, 0.0),
                (0.0, 0.0, 0.0),
                (-1e-4, 1e-4),
                spider,
                "0 1 0",
            )
        )
        out.append(_link(sensor, 0.001, (0.0, 0.0, 0.0)))
    return out


def _write_meshes(folder: Path, spider: Spider) -> None:
    import trimesh

    w = 0.012
    meshes = {
        "base_link": trimesh.creation.box(extents=spider.body_size),
        "coxa": trimesh.creation.box(bounds=[(0.0, -w, -w), (spider.coxa, w, w)]),
        "femur": trimesh.creation.box(bounds=[(0.0, -w, -w), (spider.femur, w, w)]),
        # a tapered tibia whose tip, straight below the knee, is the foot
        "tibia": trimesh.convex.convex_hull(
            np.array(
                [[sx * w / 2, 0.0, sz * w / 2] for sx in (-1, 1) for sz in (-1, 1)]
                + [[0.0, -spider.tibia, 0.0]]
            )
        ),
    }
    for part, mesh in meshes.items():
        mesh.export(folder / f"{part}.STL")
