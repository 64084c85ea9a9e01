"""Ratings a design may not give: what each result that needs one says instead of a number.

A robot file whose joints carry ``effort="0"`` or ``velocity="0"`` (an exporter's default),
or none, gives no rating: its design's ``rated_torques`` / ``rated_speeds`` are ``None``.
Every result within ratings — the payload capacities standing and walking, the max speed,
the max slope held by the motors, the checks against ratings — is then ``None`` in JSON and
:data:`NEEDS_RATING` in text, never a number from nowhere. What only weighs the torques
(the min-torque force split) weighs them alike (:func:`torque_scale`).
"""

from __future__ import annotations

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.exceptions import ParameterError

__all__ = [
    "DEFAULT_RATED_SPEEDS",
    "DEFAULT_RATED_TORQUES",
    "NEEDS_RATING",
    "NOT_GIVEN",
    "SPEED_RANGE",
    "TORQUE_RANGE",
    "UNRATED_SCALE",
    "as_written",
    "ratings_text",
    "require_ratings",
    "torque_scale",
]

DEFAULT_RATED_TORQUES: tuple[float, float, float] = (60.0, 150.0, 120.0)
"""Rated torques (root, hip, knee) [N·m] of the default 60 kg body's actuators: well above
what the nominal stance asks of each joint (``hexaleg loads``), with room for the body's
extremes and a payload."""

TORQUE_RANGE = (1e-3, 1e6)
"""Plausible rated torque [N·m]."""

DEFAULT_RATED_SPEEDS: tuple[float, float, float] = (3.0, 3.0, 3.0)
"""Rated joint speeds (root, hip, knee) [rad/s]: about 29 rpm at the output, typical of
geared actuators of the default ratings; written to each URDF joint's ``velocity``."""

SPEED_RANGE = (1e-3, 1e4)
"""Plausible rated joint speed [rad/s]."""

NEEDS_RATING = "needs a rating"
"""What a result that needs a rating the design does not give says instead of a number."""

NOT_GIVEN = (0.0, 0.0, 0.0)
"""What a URDF writes for ratings not given: an ``effort``/``velocity`` of 0 (read back as
not given, as an exporter's default is)."""

UNRATED_SCALE = (1.0, 1.0, 1.0)
"""What the min-torque forces weigh the torques by when the design gives no ratings [N·m]:
each joint alike, so that they minimize Σ τ² itself."""

Ratings = tuple[float, float, float] | None
"""A design's ratings (root, hip, knee), or ``None``: not given."""


def as_written(values: Ratings) -> tuple[float, float, float]:
    """Ratings as a URDF's ``effort``/``velocity`` writes them: 0 where not given."""
    return NOT_GIVEN if values is None else values


def ratings_text(values: Ratings, unit: str) -> str:
    """Ratings for a line of text: ``60, 150, 120 N·m``, or that they are not given."""
    if values is None:
        return f'not given: each result that needs one says "{NEEDS_RATING}"'
    return ", ".join(f"{v:g}" for v in values) + f" {unit}"


def torque_scale(rated_torques: Ratings) -> ArrayF:
    """The torques (root, hip, knee) the min-torque forces weigh by (3,) [N·m].

    The rated torques; :data:`UNRATED_SCALE` when none are given (no rating is read from
    them: the capacities and checks that need one say so instead).
    """
    return np.array(UNRATED_SCALE if rated_torques is None else rated_torques, dtype=float)


def require_ratings(rated_torques: Ratings, rated_speeds: Ratings, what: str) -> None:
    """Refuse, naming the field and the option, ``what`` needs ratings that are not given."""
    for field, given in (("rated_torques", rated_torques), ("rated_speeds", rated_speeds)):
        if given is None:  # a robot file's efforts or velocities of 0
            flag = "--" + field.replace("_", "-")
            raise ParameterError(
                field,
                "not given",
                f"{what} {NEEDS_RATING} of every joint: give {field} (root, hip, knee) in the "
                f"design file or {flag} ROOT HIP KNEE",
            )
