"""Design files written: a :class:`~hexaleg.design.HexapodDesign` as commented TOML.

:func:`design_toml` writes every field of the design with its unit in a comment, the
tables of its actuators, battery and structure when it has them, and the mounts when they
are placed by hand; :func:`~hexaleg.design_file.load_design` reads the file back to the same design.
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
from hexaleg.leg_structure import STRUCTURE_FIELDS, TABLE, TUBE_FIELDS, Structure, Tube
from hexaleg.limits import JOINT_NAMES, LEG_JOINTS, JointLimits
from hexaleg.materials import MATERIAL_FIELDS, TEXT_KEYS, shipped_materials

EXAMPLE_MATERIAL = "aluminium_6061_t6"
"""The material of a new design file's example ``[structure]``."""


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
            if value is None:  # a rating not given: named, left for the user to write
                lines.append(_not_given(spec))
                continue
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


def _not_given(spec: FieldSpec) -> str:
    """A rating the design does not give, as a commented line to fill in."""
    items = ", ".join(item.upper() for item in spec.items)
    return f"# {spec.key} = [{items}]  # not given (a robot file's 0): the actuators' [{spec.unit}]"


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
    return lines + ([] if design.structure is None else structure_lines(design.structure))


def structure_lines(structure: Structure, prefix: str = "") -> list[str]:
    """The ``[structure]`` table and its sub-tables, commented, each line after ``prefix``.

    ``prefix = "# "`` comments every line out (a new file's example).
    """
    comments = {s.name: s.described for s in (*STRUCTURE_FIELDS, *TUBE_FIELDS, *MATERIAL_FIELDS)}
    comments |= TEXT_KEYS
    table = structure.to_table()
    lines = ["", f"[{TABLE}]"]
    subtables = {key: value for key, value in table.items() if isinstance(value, dict)}
    lines += [
        _line(key, value, comments[key]) for key, value in table.items() if key not in subtables
    ]
    for key, values in subtables.items():
        lines += ["", f"[{TABLE}.{key}]  # {comments[key]}"]
        lines += [_line(name, value, comments[name]) for name, value in values.items()]
    return [prefix + line if line else line for line in lines]


def structure_example() -> str:
    """A ``[structure]`` table for a new design file, every line commented out."""
    tube = Tube(0.04, 0.002)
    material = shipped_materials().material(EXAMPLE_MATERIAL)
    example = Structure(material, tube, tube, tube, deflection_limit=0.01)
    lines = [
        "# The legs' own structure: each segment a round tube of a catalog material",
        "# (hexaleg materials lists them) whose mass replaces link_linear_density, its",
        "# stresses and the foot's deflection checked by loads and gait; size = true",
        "# chooses the lightest tubes that hold. Uncomment to use it.",
    ]
    return "\n".join(lines + structure_lines(example, "# ")[1:]) + "\n"


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
