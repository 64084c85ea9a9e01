"""A robot file's visual or collision geometry as Pinocchio's geometry model, meshes on disk.

Pinocchio reads a URDF's ``<visual>`` and ``<collision>`` shapes itself; what it cannot do
is find the meshes as hexaleg finds them (:func:`~hexaleg.robot.packages.resolve_resource`:
relative to the robot file's folder, ``package://NAME/`` in the given package folders). So
each mesh reference is replaced by the file it names before Pinocchio reads the text, and
a shape whose mesh names no file is left out and reported: a viewer does not draw it, the
collision check does not test it. A mesh file over
:data:`~hexaleg.robot.source.MAX_MESH_BYTES` is refused by its size before Pinocchio (coal,
assimp) reads it.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Literal

import pinocchio as pin

from hexaleg.exceptions import RobotImportError, one_line
from hexaleg.robot.packages import PackageFolders, missing_packages_note, resolve_resource
from hexaleg.robot.source import Packages, check_mesh_file

__all__ = ["GeometryKind", "file_geometry", "missing_meshes_note", "with_resolved_meshes"]

GeometryKind = Literal["visual", "collision"]
"""Which of a link's shapes: what is drawn, or what touches."""

_PINOCCHIO_KIND = {"visual": pin.GeometryType.VISUAL, "collision": pin.GeometryType.COLLISION}


def with_resolved_meshes(
    text: str, kind: GeometryKind, base_dir: Path | None, packages: Packages
) -> tuple[str, tuple[str, ...]]:
    """URDF ``text`` with every ``kind`` shape's mesh named by its local file's path.

    Returns:
        The text, and the mesh references that name no file (their shapes left out), each
        once, in the order the file gives them.

    """
    try:
        root = ET.fromstring(text)
    except ET.ParseError as err:
        raise RobotImportError(f"the robot's URDF is not XML: {err}") from None
    missing: dict[str, None] = {}
    for link in root.iter("link"):
        for shape in list(link.findall(kind)):
            mesh = shape.find("geometry/mesh")
            if mesh is None:
                continue
            reference = mesh.get("filename", "")
            path = resolve_resource(reference, base_dir, packages)
            if path is None:
                missing[reference] = None
                link.remove(shape)
            else:
                check_mesh_file(path, reference)  # over the cap: refused, never read
                mesh.set("filename", str(path.resolve()))
    return ET.tostring(root, encoding="unicode"), tuple(missing)


def file_geometry(
    model: pin.Model, text: str, kind: GeometryKind, base_dir: Path | None, packages: Packages
) -> tuple[pin.GeometryModel, tuple[str, ...]]:
    """The ``kind`` geometry of URDF ``text`` on ``model`` (built from the same text).

    Returns:
        The geometry model, and the mesh references left out (:func:`with_resolved_meshes`).

    Raises:
        RobotImportError: Pinocchio cannot read a shape (a mesh file it cannot parse).

    """
    resolved, missing = with_resolved_meshes(text, kind, base_dir, packages)
    try:
        geometry = pin.buildGeomFromUrdfString(model, resolved, _PINOCCHIO_KIND[kind])
    except (RuntimeError, ValueError) as err:
        raise RobotImportError(
            f"the file's {kind} geometry cannot be read: {_reason(err)}"
        ) from None
    return geometry, missing


def missing_meshes_note(missing: tuple[str, ...], packages: PackageFolders, what: str) -> str:
    """One sentence: how many mesh files were not found, ``what`` follows, how to give them.

    ``what``: what that means, e.g. "those visuals are not drawn". Packages found nowhere
    are named once (:func:`~hexaleg.robot.packages.missing_packages_note`), not per mesh.
    """
    listed = ", ".join(missing[:3]) + (f" and {len(missing) - 3} more" if len(missing) > 3 else "")
    unfound = packages.missing(missing)
    how = missing_packages_note(unfound) if unfound else "check the paths"
    return f"{len(missing)} mesh file(s) not found, {what}: {listed}; {how}"


def _reason(err: Exception) -> str:
    """A mesh loader's error in one line: coal's message without its source location and hint."""
    text = one_line(err)
    return text.split(" message: ", 1)[-1].split(" Hint: ", 1)[0]
