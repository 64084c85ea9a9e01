"""An imported robot as hexaleg's design, and as a JSON-ready record of what was read.

:func:`robot_design` gives the :class:`~hexaleg.design.HexapodDesign` that the swing-phase
analyses take: the legs' segments (a1, l2, l3), the six mounts (custom layout; heights
measured from the mounts' mean plane, which the design's body frame sits in), a body box
spanning the mounts and no taller than the tibia (so the nominal posture stands), the
file's body mass and joint ratings. :func:`robot_record` lists, per leg, the file's joint
names, the mount, the dimensions and offsets, the joint map, the foot rule, the limits,
ratings and segment masses — what ``design show --urdf FILE --json`` prints as
``design.legs`` and ``design import`` records — and the segments changed from the file's
(:mod:`hexaleg.robot.resize`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from typing import Any

import numpy as np

from hexaleg.design import HexapodDesign
from hexaleg.exceptions import RobotImportWarning
from hexaleg.layouts import LegMount
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.imported import ImportedLeg, ImportedRobot

MIN_BODY_MASS = 1e-3
"""A lighter body is a placeholder (a ``<mass value="0.0001"/>``), not a body [kg]."""

NO_MASSES = "the file gives no masses"
"""How a warning about a robot file without any mass (a kinematics-only file) begins."""

SAME_LENGTH = 1e-9
"""Segments that differ by less than this are one length [m]."""


def robot_design(robot: ImportedRobot, base: HexapodDesign | None = None) -> HexapodDesign:
    """The design of ``robot``: its segments, mounts, body mass and ratings over ``base``.

    ``base``'s own body mass, rated torques and rated speeds (those other than hexaleg's
    defaults: a design file's, edited) override the file's (:data:`OVERRIDDEN`).

    Legs whose segments differ (a file drawn so, or per-leg ``[robot.segments]``) are
    warned about: the design's ``l1 l2 l3`` are then the first leg's, which is what the
    design-level numbers (workspace area, w_A, leg length) describe, while every analysis
    of the whole robot takes each leg's own general leg.
    """
    base = HexapodDesign() if base is None else base
    first = robot.legs[0].reading.geometry.lengths
    for leg in robot.legs[1:]:
        lengths = leg.reading.geometry.lengths
        if max(abs(a - b) for a, b in zip(lengths, first, strict=True)) > SAME_LENGTH:
            warnings.warn(
                f"leg {leg.name}'s segments {_mm(lengths)} differ from leg "
                f"{robot.legs[0].name}'s {_mm(first)}: the design's l1 l2 l3 are leg "
                f"{robot.legs[0].name}'s; the whole robot's analyses take each leg's own",
                RobotImportWarning,
                stacklevel=2,
            )
            break
    mounts = [_mount(leg) for leg in robot.legs]
    plane = sum(m.z for m in mounts) / len(mounts)
    hip = robot.legs[0].reading.geometry.hip_height
    changes: dict[str, Any] = {
        "l1": max(first[0], 1e-9),
        "l2": first[1],
        "l3": first[2],
        "layout": "custom",
        "mounts": tuple(replace(m, z=m.z - plane) for m in mounts),
        "body_length": 2 * max(abs(m.x) for m in mounts),
        "body_width": 2 * max(abs(m.y) for m in mounts),
        "body_height": min(base.body_height, max(first[2] - hip, 1e-3)),
    }
    given = _given(base)
    changes.update(_body_mass(robot, base, given))
    efforts, speeds = robot.legs[0].ratings
    if "rated_torques" not in given and all(e is not None and e > 0 for e in efforts):
        changes["rated_torques"] = tuple(float(e) for e in efforts if e is not None)
    if "rated_speeds" not in given and all(v is not None and v > 0 for v in speeds):
        changes["rated_speeds"] = tuple(float(v) for v in speeds if v is not None)
    return base.replace(**changes)


def _body_mass(robot: ImportedRobot, base: HexapodDesign, given: set[str]) -> dict[str, float]:
    """The design's ``body_mass`` [kg]: the file's body's, else (with a warning) the design's.

    ``base``'s own (``given``) goes over the file's; a body lighter than
    :data:`MIN_BODY_MASS` is a placeholder, and a file without any mass is kinematics only.
    """
    if "body_mass" in given:
        return {}  # the design file's own body mass, over the file's
    if robot.body_mass.mass >= MIN_BODY_MASS:
        return {"body_mass": robot.body_mass.mass}
    if robot.mass <= 0.0:
        message = (
            f"{NO_MASSES}: kinematics only (statics, walking and simulation are refused); "
            f"body_mass {base.body_mass:g} kg is the design's placeholder"
        )
    else:
        message = (
            f"the file's body weighs {robot.body_mass.mass:.3g} kg: kept the design's "
            f"body_mass {base.body_mass:g} kg"
        )
    warnings.warn(message, RobotImportWarning, stacklevel=3)
    return {}


OVERRIDDEN = ("body_mass", "rated_torques", "rated_speeds")
"""The file's values a design overrides: its own, where they are not hexaleg's defaults."""


def _given(base: HexapodDesign) -> set[str]:
    """Which of :data:`OVERRIDDEN` ``base`` sets itself (a value other than the default's).

    A design file written by ``design import`` holds the robot file's values, so it
    overrides nothing until one is edited; ``--urdf`` alone goes over the default design.
    """
    default = HexapodDesign()
    return {name for name in OVERRIDDEN if getattr(base, name) != getattr(default, name)}


def _mount(leg: ImportedLeg) -> LegMount:
    x, y, z = (float(v) for v in leg.reading.mount[:3, 3])
    return LegMount(leg.name, x, y, z, leg.reading.mount_yaw)


def _mm(lengths: tuple[float, ...]) -> str:
    return "(" + ", ".join(f"{1000 * v:.2f}" for v in lengths) + ") mm"


def nominal_posture(leg: ImportedLeg, nominal: tuple[float, float, float]) -> dict[str, Any]:
    """The design's nominal angles on ``leg``, moved inside the file's limits where they are not.

    Returns ``joint_angles`` (hexaleg's θ [rad]), ``urdf_joint_angles`` (the file's q [rad])
    and ``moved``, the joints whose nominal angle lay outside the file's limits.
    """
    lower, upper = leg.theta_limits
    wanted = np.asarray(nominal, dtype=float)
    theta = np.clip(wanted, lower, upper)
    moved = [LEG_JOINTS[i] for i in range(3) if theta[i] != wanted[i]]
    return {
        "joint_angles": _list(theta),
        "urdf_joint_angles": _list(leg.reading.joint_map.to_file(theta)),
        "moved_into_limits": moved,
    }


def robot_record(
    robot: ImportedRobot, nominal: tuple[float, float, float] | None = None
) -> dict[str, Any]:
    """What was read from the robot file, JSON-ready (SI units, radians).

    With the design's ``nominal`` angles, each leg also gives its nominal posture in
    hexaleg's angles and in the file's (:func:`nominal_posture`).
    """
    legs = [leg_record(leg) for leg in robot.legs]
    if nominal is not None:
        for record, leg in zip(legs, robot.legs, strict=True):
            record["nominal"] = nominal_posture(leg, nominal)
    return {
        "source": None if robot.source is None else str(robot.source),
        "name": robot.description.name,
        "body_links": list(robot.body),
        "body_mass": robot.body_mass.mass,
        "legs": legs,
        "changed_segments": [change.as_dict() for change in robot.changes],
        "units": {"lengths": "m", "angles": "rad", "mass": "kg", "effort": "N·m"},
    }


def leg_record(leg: ImportedLeg) -> dict[str, Any]:
    """One leg's record: joints, mount, dimensions, offsets, joint map, foot, limits, masses."""
    reading = leg.reading
    geometry = reading.geometry
    lower, upper = leg.file_limits
    theta_lower, theta_upper = leg.theta_limits
    efforts, speeds = leg.ratings
    x, y, z = (float(v) for v in reading.mount[:3, 3])
    return {
        "name": leg.name,
        "joints": list(leg.joint_names),
        "mount": {"x": x, "y": y, "z": z, "yaw": reading.mount_yaw},
        **geometry.as_dict(),
        "theta_at_file_zero": _list(reading.joint_map.from_file(np.zeros(3))),
        "joint_signs": list(reading.joint_map.signs),
        "joint_offsets": list(reading.joint_map.offsets),
        "foot": {"rule": reading.foot.rule, "source": reading.foot.source},
        "foot_point": list(reading.foot.point),
        "file_limits": {"lower": _list(lower), "upper": _list(upper)},
        "theta_limits": {"lower": _list(theta_lower), "upper": _list(theta_upper)},
        "effort": list(efforts),
        "velocity": list(speeds),
        "segment_masses": [m.mass for m in leg.masses],
    }


def _list(values: np.ndarray) -> list[float | None]:
    """Floats for JSON; an infinite limit (continuous joint) becomes ``None``."""
    return [float(v) if math.isfinite(v) else None for v in values]
