"""Design → URDF text, through the Xacro templates in ``urdf/``.

The templates are the single description of the robot's geometry; this module
only turns a :class:`~hexaleg.design.HexapodDesign` into Xacro arguments and
runs the ``xacro`` package in-process. Every argument is formatted here as a
number (or a validated identifier), so no user string ever reaches Xacro's
``${...}`` evaluator.
"""

from __future__ import annotations

import io
import logging
import os
import threading
from importlib import resources
from pathlib import Path

from hexaleg._checks import require_instance
from hexaleg._io import write_text
from hexaleg._version import __version__
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import TemplateError
from hexaleg.leg_structure import LEG_SEGMENTS
from hexaleg.limits import JOINT_NAMES, LEG_JOINTS
from hexaleg.ratings import as_written
from hexaleg.robot.inertia import body_inertial, leg_inertials, segment_radii

HEXAPOD_TEMPLATE = "hexapod.urdf.xacro"
LEG_TEMPLATE = "leg.urdf.xacro"
SINGLE_LEG_NAME = "leg"
"""Prefix of the links and joints of the single fixed-base leg."""


def template_dir() -> Path:
    """Folder holding the Xacro templates.

    Installed packages carry them as ``hexaleg/urdf``; a source checkout (or an
    editable install) uses the repository's top-level ``urdf/``.
    """
    packaged = Path(str(resources.files("hexaleg") / "urdf"))
    if (packaged / HEXAPOD_TEMPLATE).is_file():
        return packaged
    checkout = Path(__file__).resolve().parents[2] / "urdf"
    if (checkout / HEXAPOD_TEMPLATE).is_file():
        return checkout
    raise TemplateError(f"Xacro templates not found in {packaged} or {checkout}")


def render_hexapod(design: HexapodDesign, validate: bool = True) -> str:
    """URDF of the whole hexapod (root link ``base_link``) for ``design``."""
    mappings = _common_arguments(design)
    body = {
        "body_length": design.body_length,
        "body_width": design.body_width,
        "body_radius": design.body_radius,
        "body_height": design.body_height,
        **body_inertial(design).xacro_arguments("body"),
    }
    mappings |= {name: _number(value) for name, value in body.items()}
    mappings["body_shape"] = design.body_shape  # a validated literal: "box" or "cylinder"
    for i, mount in enumerate(design.legs, start=1):
        mappings[f"leg{i}_name"] = mount.name  # validated identifier, see LegMount
        for axis in ("x", "y", "z", "yaw"):
            mappings[f"leg{i}_{axis}"] = _number(getattr(mount, axis))
    return _render(HEXAPOD_TEMPLATE, mappings, validate)


def render_leg(design: HexapodDesign, validate: bool = True) -> str:
    """URDF of one leg on a fixed base: ``base_link`` is the leg-root frame of eq 7."""
    mappings = _common_arguments(design) | {"leg_name": SINGLE_LEG_NAME}
    return _render(LEG_TEMPLATE, mappings, validate)


def write_urdf(design: HexapodDesign, path: str | os.PathLike[str]) -> Path:
    """Render the hexapod URDF and write it to ``path`` atomically."""
    return write_text(path, render_hexapod(design))


def validate_urdf(xml: str) -> None:
    """Check ``xml`` with yourdfpy; raise :class:`TemplateError` if it is not a valid URDF."""
    import yourdfpy

    try:
        model = yourdfpy.URDF.load(
            io.BytesIO(xml.encode("utf-8")), build_scene_graph=False, load_meshes=False
        )
    except Exception as err:  # yourdfpy raises many types on malformed input
        raise TemplateError(f"yourdfpy could not load the rendered URDF: {err}") from err
    logger = logging.getLogger("yourdfpy")
    previous = logger.level
    logger.setLevel(logging.CRITICAL)
    try:
        valid = model.validate()
    finally:
        logger.setLevel(previous)
    if not valid:
        raise TemplateError("yourdfpy rejected the rendered URDF")


def _common_arguments(design: HexapodDesign) -> dict[str, str]:
    """The leg's arguments, the same for every leg: lengths, limits, ratings, inertials."""
    require_instance("design", design, HexapodDesign, "a HexapodDesign")
    limits = design.joint_range
    numbers = {
        "l1": design.l1,
        "l2": design.l2,
        "l3": design.l3,
        "link_radius": design.link_radius,
    }
    for segment, radius in zip(LEG_SEGMENTS, segment_radii(design), strict=True):
        numbers[f"{segment}_radius"] = radius
    for joint in JOINT_NAMES:
        numbers[f"{joint}_lower"], numbers[f"{joint}_upper"] = getattr(limits, joint)
    for joint, effort, speed in zip(
        LEG_JOINTS, as_written(design.rated_torques), as_written(design.rated_speeds), strict=True
    ):
        numbers[f"{joint}_effort"], numbers[f"{joint}_velocity"] = effort, speed
    for link, inertial in leg_inertials(design).items():
        numbers |= inertial.xacro_arguments(link)
    return {name: _number(value) for name, value in numbers.items()}


def _number(value: float) -> str:
    """Shortest text that round-trips the float exactly; never an expression."""
    return repr(float(value))


_XACRO = threading.Lock()
"""xacro keeps the substitution arguments of the file it processes in module globals:
one rendering at a time, whichever thread asks (the explorer answers in several)."""


def _render(template: str, mappings: dict[str, str], validate: bool) -> str:
    import xacro

    path = template_dir() / template
    try:
        with _XACRO:
            document = xacro.process_file(str(path), mappings=mappings)
    except Exception as err:  # xacro raises XacroException and plain errors alike
        raise TemplateError(f"xacro failed on {path.name}: {err}") from err
    for node in list(document.childNodes):  # xacro's banner names this machine's paths
        if node.nodeType == node.COMMENT_NODE:
            document.removeChild(node)
    banner = document.createComment(
        f" generated by hexaleg {__version__} from {template}: edit the design, not this file "
    )
    document.insertBefore(banner, document.documentElement)
    xml = document.toprettyxml(indent="  ")
    if validate:
        validate_urdf(xml)
    return xml
