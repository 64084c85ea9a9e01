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
from typing import Any

import numpy as np

from hexaleg.design import BODY_RANGE, HexapodDesign
from hexaleg.exceptions import RobotImportWarning
from hexaleg.layouts import LegMount
from hexaleg.robot.file_defaults import missing_ratings
from hexaleg.robot.imported import ImportedLeg, ImportedRobot
from hexaleg.robot.standing import standing_posture

MIN_BODY_MASS = 1e-3
"""A lighter body is a placeholder (a ``<mass value="0.0001"/>``), not a body [kg]."""

SEGMENTS_DIFFER = 1e-4
"""Legs whose segments differ by more than this are said to differ [m]: a CAD export's
round-off (micrometres) is not a different leg."""

LEVEL_MOUNTS = 1e-3
"""Leg roots within this of one height are on one plane, the design's [m]; their offsets
from it are reported, the model keeps each at its own height."""

ROUND_OFF = 1e-10
"""Mount heights that differ by less than this are equal, not reported [m]."""

NO_MASSES = "the file gives no masses"
"""How a warning about a robot file without any mass (a kinematics-only file) begins."""


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
    _warn_different_legs(robot)
    mounts = level_mounts(robot)
    hip = robot.legs[0].reading.geometry.hip_height
    changes: dict[str, Any] = {
        "l1": first[0],
        "l2": first[1],
        "l3": first[2],
        "layout": "custom",
        "mounts": mounts,
        **_body_extent(robot, mounts),
        "body_height": min(base.body_height, max(first[2] - hip, 1e-3)),
    }
    given = _given(base)
    changes.update(_body_mass(robot, base, given))
    return base.replace(**changes, **file_ratings(robot, given))


def file_ratings(robot: ImportedRobot, given: set[str]) -> dict[str, Any]:
    """The ratings the robot file gives (``None``: not given), for those ``given`` does not.

    A joint's ``effort`` or ``velocity`` of 0 or absent is no rating (an exporter's
    default): the design's rating of that kind is then ``None`` — never a number from
    nowhere — and one warning names the joints and how to give the ratings.
    """
    efforts, speeds = robot.legs[0].ratings
    unrated = missing_ratings([leg.chain for leg in robot.legs])
    ratings: dict[str, Any] = {}
    for field, values, missing in zip(RATINGS, (efforts, speeds), unrated, strict=True):
        if field in given:
            continue
        ratings[field] = None if missing else tuple(float(v or 0.0) for v in values)
    said = [
        (field, names)
        for field, names in zip(RATINGS, unrated, strict=True)
        if names and field not in given
    ]
    if said:
        _warn_unrated(said)
    return ratings


RATINGS = ("rated_torques", "rated_speeds")
"""The design's rating fields, read from each URDF joint's ``effort`` and ``velocity``."""


def _warn_unrated(missing: list[tuple[str, tuple[str, ...]]]) -> None:
    """One warning: which joints have no rating, what needs one, how to give them."""
    attribute = {"rated_torques": "effort", "rated_speeds": "velocity"}
    said = "; ".join(
        f"joints {_listed(names)} have no {attribute[field]}" for field, names in missing
    )
    fields = " and ".join(field for field, _ in missing)
    options = " and ".join(
        "--" + field.replace("_", "-") + " ROOT HIP KNEE" for field, _ in missing
    )
    warnings.warn(
        f"{said} (0 or absent in the file): the payload capacities, the max speed and the "
        f"checks against ratings need a rating; give them as {fields} in the design file or "
        f"{options}",
        RobotImportWarning,
        stacklevel=4,
    )


def _listed(names: tuple[str, ...], most: int = 4) -> str:
    more = f" and {len(names) - most} more" if len(names) > most else ""
    return ", ".join(names[:most]) + more


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


def _body_extent(robot: ImportedRobot, mounts: tuple[LegMount, ...]) -> dict[str, float]:
    """The design's body length and width [m]: the file's body box (else the roots' span)."""
    if robot.body_shape is not None:
        length, width, _ = robot.body_shape.size
    else:
        length, width = 2 * max(abs(m.x) for m in mounts), 2 * max(abs(m.y) for m in mounts)
    return {"body_length": max(length, BODY_RANGE[0]), "body_width": max(width, BODY_RANGE[0])}


def _warn_different_legs(robot: ImportedRobot) -> None:
    """Warn once if a leg's segments differ from the first leg's by more than 0.1 mm."""
    first = robot.legs[0].reading.geometry.lengths
    for leg in robot.legs[1:]:
        lengths = leg.reading.geometry.lengths
        apart = max(abs(a - b) for a, b in zip(lengths, first, strict=True))
        if apart > SEGMENTS_DIFFER:
            digits = max(2, math.ceil(-math.log10(1000 * apart)) + 1)
            warnings.warn(
                f"leg {leg.name}'s segments {_mm(lengths, digits)} differ from leg "
                f"{robot.legs[0].name}'s {_mm(first, digits)}: the design's l1 l2 l3 are leg "
                f"{robot.legs[0].name}'s; the whole robot's analyses take each leg's own",
                RobotImportWarning,
                stacklevel=3,
            )
            return


def mount_plane(robot: ImportedRobot) -> float:
    """The mean height of the leg roots in the root link's frame [m]: the design's body plane."""
    return float(np.mean([leg.reading.mount[2, 3] for leg in robot.legs]))


def level_mounts(robot: ImportedRobot) -> tuple[LegMount, ...]:
    """The six mounts in the design's body frame: on the roots' mean plane (z = 0).

    Roots at different heights are said so, each leg's offset from the mean named: within
    :data:`LEVEL_MOUNTS` they are one plane up to the file's round-off; farther apart the
    feet must still stand level (the model keeps every root where the file puts it).
    """
    plane = mount_plane(robot)
    offsets = {leg.name: float(leg.reading.mount[2, 3]) - plane for leg in robot.legs}
    spread = max(offsets.values()) - min(offsets.values())
    if spread > ROUND_OFF:
        unit, scale = ("µm", 1e6) if spread < LEVEL_MOUNTS else ("mm", 1e3)
        listed = ", ".join(f"{name} {scale * dz:+.3g}" for name, dz in offsets.items())
        within = (
            f"within {1000 * LEVEL_MOUNTS:g} mm"
            if spread <= LEVEL_MOUNTS
            else f"more than {1000 * LEVEL_MOUNTS:g} mm apart (the feet must still stand level)"
        )
        warnings.warn(
            f"the leg roots' heights differ by {scale * spread:.3g} {unit}, {within}: their "
            f"mean is the body's plane, each leg's offset from it ({unit}): {listed}",
            RobotImportWarning,
            stacklevel=3,
        )
    return tuple(_mount(leg, 0.0) for leg in robot.legs)


def _mount(leg: ImportedLeg, z: float) -> LegMount:
    x, y, _ = (float(v) for v in leg.reading.mount[:3, 3])
    return LegMount(leg.name, x, y, z, leg.reading.mount_yaw)


def _mm(lengths: tuple[float, ...], digits: int = 2) -> str:
    return "(" + ", ".join(f"{1000 * v:.{digits}f}" for v in lengths) + ") mm"


def nominal_postures(robot: ImportedRobot, nominal: tuple[float, float, float]) -> list[dict]:
    """Each leg's nominal posture: the design's angles where they stand (:mod:`.standing`).

    Per leg ``joint_angles`` (hexaleg's θ [rad]), ``urdf_joint_angles`` (the file's q
    [rad]), ``moved_into_limits`` (the joints whose design angle lay outside the leg's
    limits) and ``chosen`` (why another posture was chosen; ``None`` if the design's stands).
    """
    standing = standing_posture(robot, nominal, body_depth(robot))
    return [
        {
            "joint_angles": _list(theta),
            "urdf_joint_angles": _list(leg.reading.joint_map.to_file(theta)),
            "moved_into_limits": list(moved),
            "chosen": standing.chosen,
        }
        for leg, theta, moved in zip(robot.legs, standing.angles, standing.moved, strict=True)
    ]


def body_depth(robot: ImportedRobot) -> float:
    """How far the body's box reaches below the roots' plane [m] (0 without one)."""
    return 0.0 if robot.body_shape is None else float(robot.body_shape.half_extents[2])


def robot_record(
    robot: ImportedRobot, nominal: tuple[float, float, float] | None = None
) -> dict[str, Any]:
    """What was read from the robot file, JSON-ready (SI units, radians).

    With the design's ``nominal`` angles, each leg also gives its nominal posture in
    hexaleg's angles and in the file's (:func:`nominal_postures`).
    """
    legs = [leg_record(leg) for leg in robot.legs]
    if nominal is not None:
        for record, posture in zip(legs, nominal_postures(robot, nominal), strict=True):
            record["nominal"] = posture
    return {
        "source": None if robot.source is None else str(robot.source),
        "name": robot.description.name,
        "body_links": list(robot.body),
        "body_box": None if robot.body_shape is None else robot.body_shape.as_dict(),
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
