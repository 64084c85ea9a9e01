"""A robot file's collision geometry as Pinocchio's geometry model, its meshes found on disk.

Pinocchio reads a URDF's ``<collision>`` shapes itself; what it cannot do is find the
meshes as hexaleg finds them (:func:`~hexaleg.robot.source.resolve_resource`: relative to
the robot file's folder, ``package://NAME/`` in the given package folders). So each
mesh reference is replaced by the file it names before Pinocchio reads the text, and a
``<collision>`` whose mesh names no file is left out, and reported: those parts are then
not checked for contact.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import pinocchio as pin

from hexaleg.exceptions import RobotImportError
from hexaleg.robot.source import Packages, resolve_resource


def resolved_collisions(
    text: str, base_dir: Path | None, packages: Packages
) -> tuple[str, tuple[str, ...]]:
    """URDF ``text`` with every collision mesh named by its local path.

    Returns:
        The text, and the mesh references that name no file (their ``<collision>``
        left out), in the order the file gives them.

    """
    try:
        root = ET.fromstring(text)
    except ET.ParseError as err:
        raise RobotImportError(f"the robot's URDF is not XML: {err}") from None
    missing: list[str] = []
    for link in root.iter("link"):
        for collision in list(link.findall("collision")):
            mesh = collision.find("geometry/mesh")
            if mesh is None:
                continue
            reference = mesh.get("filename", "")
            path = resolve_resource(reference, base_dir, packages)
            if path is None:
                missing.append(reference)
                link.remove(collision)
            else:
                mesh.set("filename", str(path.resolve()))
    return ET.tostring(root, encoding="unicode"), tuple(missing)


def collision_geometry(
    model: pin.Model, text: str, base_dir: Path | None, packages: Packages
) -> tuple[pin.GeometryModel, tuple[str, ...]]:
    """The collision geometry of URDF ``text`` on ``model`` (built from the same text).

    Returns:
        The geometry model, and the mesh references left out (:func:`resolved_collisions`).

    """
    resolved, missing = resolved_collisions(text, base_dir, packages)
    try:
        geometry = pin.buildGeomFromUrdfString(model, resolved, pin.GeometryType.COLLISION)
    except (RuntimeError, ValueError) as err:
        raise RobotImportError(f"the file's collision geometry cannot be read: {err}") from None
    return geometry, missing
