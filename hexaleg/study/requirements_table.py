"""The ``[requirements]`` table of a design file: what each key means, and an example.

:data:`DESCRIPTIONS` is the one home of each key's meaning and unit: the options of
``decide`` and ``report`` take their help from it, and ``hexaleg design init`` writes
:func:`example_table` (every key commented out, with its unit) into a new design file.
The table itself is read by :meth:`hexaleg.study.requirements.Requirements.from_table`.
"""

from __future__ import annotations

from hexaleg.design_file import REQUIREMENTS
from hexaleg.gait.spec import Gait
from hexaleg.study.requirements import DEGREE_KEYS

DESCRIPTIONS: dict[str, str] = {
    "payload": "payload the robot must carry [kg]",
    "payload_at": "where the payload sits, body frame x, y, z [m] (default: the centre of "
    "the body's top face)",
    "slope": "slope it must stand on, uphill in every heading, with the payload [rad]",
    "slope_deg": "the same slope in degrees [°]",
    "ground_clearance": "body underside above the ground at the nominal stance [m]",
    "min_fb": "least axis-locked body flexibility FB (eq 29) [-]",
    "leg_length": "largest total leg length l1+l2+l3 [m] (default: the design's)",
    "min_coxa": "least coxa length l1, for the root actuator's packaging [m]",
    "speed": f"tripod gait speed ({Gait.stride:g} m stride) within the rated torques and "
    "speeds, carrying the payload [m/s]",
    "step_height": f"step height of that gait [m] (default {Gait.step_height:g})",
}
"""What each key of the ``[requirements]`` table (and each option) means, with its unit."""

EXAMPLE: dict[str, float | list[float]] = {
    "payload": 30.0,
    "payload_at": [0.0, 0.0, 0.05],
    "slope_deg": 15.0,
    "ground_clearance": 0.25,
    "min_fb": 0.2,
    "leg_length": 1.0,
    "min_coxa": 0.08,
    "speed": 0.3,
    "step_height": 0.1,
}
"""A plausible value of every key, for the commented example table of a new design file."""


def example_table() -> str:
    """A ``[requirements]`` table for a design file, every line commented out, with units."""
    lines = [
        "# What the robot must do, for `hexaleg decide` and `hexaleg report`: uncomment the",
        "# header and the requirements you have (each is optional; the options of the same",
        "# name override them). SI units and radians; the slope also as slope_deg in degrees.",
        f"# [{REQUIREMENTS}]",
    ]
    for key, value in EXAMPLE.items():
        text = "[" + ", ".join(f"{v:g}" for v in value) + "]" if isinstance(value, list) else value
        comment = DESCRIPTIONS[key]
        if key in DEGREE_KEYS:  # the slope's own description, in degrees
            comment = DESCRIPTIONS[DEGREE_KEYS[key]].replace("[rad]", "[°] (or slope, [rad])")
        lines.append(f"# {key} = {text}  # {comment}")
    return "\n".join(lines) + "\n"
