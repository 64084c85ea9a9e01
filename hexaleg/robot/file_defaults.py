"""What a robot file leaves unsaid, and what hexaleg does about it, said once.

CAD exporters write what they were not told as zeros: the SolidWorks exporter's
``<limit lower="0" upper="0" effort="0" velocity="0"/>``. Read as facts, those zeros lock
every joint and rate every motor at nothing. hexaleg reads them as "not given":

- a leg joint whose limits are ``[0, 0]`` (or upper < lower) has no limits in the file:
  it gets hexaleg's joint-limit sets (:data:`HEXALEG_RANGE`, the envelope of the paper's
  sets, on hexaleg's angles θ, mapped to the file's q = s·θ + o), written into the text
  every model is built from, with one warning listing the joints;
- a joint locked at its zero (one beyond a leg's knee that is not the leg's, or one the
  user locks) is written as a fixed joint, with one warning naming those found;
- an ``effort`` or ``velocity`` of 0 or absent is no rating: the design's ratings are then
  not given (:func:`~hexaleg.robot.robot_design.robot_design`), and every result that
  needs one says so instead of inventing a number.
"""

from __future__ import annotations

import re
import warnings
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence

import numpy as np

from hexaleg.exceptions import RobotImportError, RobotImportWarning
from hexaleg.limits import (
    IMPROVED_LIMITS,
    MANIPULABILITY_LIMITS,
    STANCE_LIMITS,
    WORKSPACE_LIMITS,
    JointLimits,
)
from hexaleg.robot.chains import LegChain
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.legs import LegReading

__all__ = [
    "HEXALEG_RANGE",
    "locked_as_fixed",
    "missing_ratings",
    "refuse_reversed",
    "unlimited_joints",
    "warn_locked",
    "warn_unlimited",
]

HEXALEG_RANGE: JointLimits = (
    WORKSPACE_LIMITS.envelope(IMPROVED_LIMITS)
    .envelope(MANIPULABILITY_LIMITS)
    .envelope(STANCE_LIMITS)
)
"""The limits a leg joint without limits in its file gets: the envelope of hexaleg's four
joint-limit sets (workspace, improved, manipulability, stance) on θ [rad]."""

RATING_FIELDS = ("effort", "velocity")
"""The URDF ``<limit>`` attributes that rate a joint: torque [N·m] and speed [rad/s]."""


def unlimited_joints(
    legs: Sequence[tuple[LegChain, LegReading]],
) -> dict[str, tuple[float, float]]:
    """The leg joints whose file gives no limits, and hexaleg's limits for them on q.

    A revolute joint with upper ≤ lower (the exporter's ``[0, 0]``) has none; each gets
    :data:`HEXALEG_RANGE` on its θ, as the file's q = s·θ + o (lower, upper) [rad].
    """
    found = {}
    for chain, reading in legs:
        lower, upper = np.array(HEXALEG_RANGE.lower), np.array(HEXALEG_RANGE.upper)
        ends = reading.joint_map.to_file(np.stack([lower, upper]))
        for k, joint in enumerate(chain.joints):
            if joint.kind == "revolute" and not joint.upper > joint.lower:
                a, b = float(ends[0, k]), float(ends[1, k])
                found[joint.name] = (min(a, b), max(a, b))
    return found


def warn_unlimited(limits: Mapping[str, tuple[float, float]]) -> None:
    """Say once which joints got hexaleg's limits because their file gives none."""
    if not limits:
        return
    names = ", ".join(list(limits)[:6]) + (
        f" and {len(limits) - 6} more" if len(limits) > 6 else ""
    )
    warnings.warn(
        f"joints {names} have no limits in the file (lower = upper, an exporter's default): "
        f"hexaleg's joint-limit sets are used for them (θ1 within ±{HEXALEG_RANGE.upper[0]:.4g}, "
        f"θ2 within ±{HEXALEG_RANGE.upper[1]:.4g}, θ3 in [{HEXALEG_RANGE.lower[2]:.4g}, "
        f"{HEXALEG_RANGE.upper[2]:.4g}] rad); write the robot's own to use them",
        RobotImportWarning,
        stacklevel=4,
    )


def warn_locked(beyond: Sequence[str], description: RobotDescription) -> None:
    """Say once which joints beyond a leg's knee were locked at their zero, and why."""
    if not beyond:
        return
    kinds = {description.joints[name].kind for name in beyond}
    why = "prismatic" if kinds == {"prismatic"} else "prismatic or of a range below 1 mm / 0.01 rad"
    names = _listed(beyond)
    warnings.warn(
        f"joints {names} beyond the legs' knees ({why}) are no leg joints: locked at their "
        f"zero as parts of the tibias (--lock-joint NAME locks any other)",
        RobotImportWarning,
        stacklevel=4,
    )


def locked_as_fixed(
    text: str, locked: Sequence[str], limits: Mapping[str, tuple[float, float]]
) -> str:
    """URDF ``text`` with the ``locked`` joints fixed and ``limits`` written on q [rad].

    The rest of the file (comments included) is kept; a comment says what was changed.
    """
    parser = ET.XMLParser(target=ET.TreeBuilder(insert_comments=True))
    try:
        root = ET.fromstring(text, parser=parser)
    except ET.ParseError as err:
        raise RobotImportError(f"the robot's URDF is not XML: {err}") from None
    for joint in root.findall("joint"):
        name = str(joint.get("name"))
        if name in locked:
            joint.set("type", "fixed")
        elif name in limits:
            limit = joint.find("limit")
            if limit is None:  # pragma: no cover - a revolute joint has one (description)
                limit = ET.SubElement(joint, "limit")
            limit.set("lower", repr(limits[name][0]))
            limit.set("upper", repr(limits[name][1]))
    said = []
    if locked:
        said.append(f"joints locked at their zero (fixed): {', '.join(locked)}")
    if limits:
        said.append(f"hexaleg's joint limits for joints the file gives none: {', '.join(limits)}")
    note = re.sub("-(?=-)", "- ", " ".join("; ".join(said).split()))  # no "--" ends it
    root.insert(0, ET.Comment(f" hexaleg: {note} "))
    return ET.tostring(root, encoding="unicode") + "\n"


def missing_ratings(
    chains: Sequence[LegChain],
) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The leg joints without an ``effort``, and without a ``velocity`` (0 or absent)."""
    efforts = tuple(
        j.name for c in chains for j in c.joints if j.effort is None or not j.effort > 0
    )
    speeds = tuple(
        j.name for c in chains for j in c.joints if j.velocity is None or not j.velocity > 0
    )
    return efforts, speeds


def refuse_reversed(description: RobotDescription, legs: Sequence[str]) -> None:
    """Refuse a movable joint, other than a leg's, whose lower limit exceeds its upper."""
    for joint in description.joints.values():
        bounded = joint.kind in ("revolute", "prismatic")
        if bounded and joint.name not in legs and joint.lower > joint.upper:
            raise RobotImportError(
                f"joint {joint.name!r} has lower limit {joint.lower:g} > upper limit "
                f"{joint.upper:g}"
            )


def _listed(names: Sequence[str], most: int = 6) -> str:
    """Names for a message: the first ``most``, then how many more."""
    more = f" and {len(names) - most} more" if len(names) > most else ""
    return ", ".join(names[:most]) + more
