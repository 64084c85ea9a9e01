"""Design files written: a :class:`~hexaleg.design.HexapodDesign` as commented TOML.

:func:`design_toml` writes every field of the design with its unit in a comment, the
tables of its actuators and battery when it has them, and the mounts when they are placed
by hand; :func:`~hexaleg.design_file.load_design` reads the file back to the same design.
"""

from __future__ import annotations

import math
from typing import Any

import tomli_w

from hexaleg.actuators import ACTUATOR_FIELDS, TEMPERATURE_KEY, TEMPERATURE_TEXT
from hexaleg.battery import BATTERY_FIELDS
from hexaleg.design import DESIGN_FIELDS, HexapodDesign
from hexaleg.design_file import ANGLES, MOUNT_KEYS
from hexaleg.field_spec import FieldSpec
from hexaleg.limits import JOINT_NAMES, LEG_JOINTS, JointLimits


def design_toml(design: HexapodDesign) -> str:
    """The design as a commented TOML design file (every field; mounts when custom)."""
    lines = [
        "# hexaleg design file: SI units (m, kg, N·m) and radians.",
        "# Any angle key also takes degrees as <key>_deg, e.g. first_leg_angle_deg = 30.",
        "# Every command reads it with --design FILE; options given beside it override it.",
        "",
    ]
    for spec in DESIGN_FIELDS:  # keys first: TOML puts the tables after them
        derived = design.actuators is not None and spec.name in ("rated_torques", "rated_speeds")
        if spec.kind in ("number", "triple", "choice") and not derived:
            value = getattr(design, spec.name)
            lines.append(
                _line(spec.key, list(value) if spec.kind == "triple" else value, spec.described)
            )
    for spec in DESIGN_FIELDS:
        if spec.kind == "limits":
            lines += _limits_table(spec, getattr(design, spec.name))
    lines += _record_tables(design)
    if design.layout == "custom":
        for mount in design.legs:
            lines += ["", "[[mount]]"]
            lines += [_line(k, getattr(mount, k), c) for k, c in MOUNT_KEYS.items()]
    else:
        lines += ["", '# layout = "custom" places each leg by hand, with six tables like:']
        lines += ["# [[mount]]"] + [
            "# " + _line(k, getattr(design.legs[0], k), c) for k, c in MOUNT_KEYS.items()
        ]
    return "\n".join(lines) + "\n"


def _record_tables(design: HexapodDesign) -> list[str]:
    """The ``[actuators.<joint>]`` and ``[battery]`` tables the design holds, commented."""
    lines: list[str] = []
    comments = {s.name: s.described for s in (*ACTUATOR_FIELDS, *BATTERY_FIELDS)}
    tables = {} if design.actuators is None else design.actuators.to_table()
    if TEMPERATURE_KEY in tables:  # the [actuators] table's own key, beside the joints'
        temperature = tables.pop(TEMPERATURE_KEY)
        lines += ["", "[actuators]", _line(TEMPERATURE_KEY, temperature, TEMPERATURE_TEXT)]
    tables = {f"actuators.{joint}": table for joint, table in tables.items()}
    if design.battery is not None:
        tables["battery"] = design.battery.to_table()
    for name, table in tables.items():
        lines += ["", f"[{name}]"]
        lines += [_line(key, value, comments[key]) for key, value in table.items()]
    return lines


def _limits_table(spec: FieldSpec, limits: JointLimits) -> list[str]:
    lines = ["", f"[{spec.key}]  # {spec.described}"]
    for joint, what in zip(JOINT_NAMES, LEG_JOINTS, strict=True):
        lines.append(_line(joint, list(getattr(limits, joint)), f"{what}: lower, upper [rad]"))
    lines.append(_line("coupled_knee", limits.coupled_knee, "also θ3 ≥ −θ2 − π/2 (Table 4)"))
    lines.append(_line("name", limits.name, "label in reports"))
    return lines


def _line(key: str, value: Any, comment: str) -> str:
    """``key = value  # comment`` on one line; angles also shown in degrees."""
    items = value if isinstance(value, list) else [value]
    texts = [tomli_w.dumps({"v": item}).strip().removeprefix("v = ") for item in items]
    text = f"[{', '.join(texts)}]" if isinstance(value, list) else texts[0]
    if key in ANGLES:
        comment += " (" + ", ".join(f"{math.degrees(v):.6g}°" for v in items) + ")"
    return f"{key} = {text}  # {comment}"
