"""The ``[requirements]`` table of a new design file: every key commented out, with its unit.

Each key's meaning, unit and example value come from its declaration
(:mod:`hexaleg.evaluation.requirement_specs`); the table itself is read by
:meth:`hexaleg.evaluation.requirements.Requirements.from_table`.
"""

from __future__ import annotations

from hexaleg import design_file
from hexaleg.evaluation.requirement_specs import degree_keys, table_keys


def example_table() -> str:
    """A ``[requirements]`` table for a design file, every line commented out, with units.

    A requirement that also has a key in degrees is written in degrees.
    """
    degrees = degree_keys()
    angles = " and ".join(f"the {spec.name} also as {key}" for key, spec in degrees.items())
    lines = [
        "# What the robot must do, for `hexaleg decide` and `hexaleg report`: uncomment the",
        "# header and the requirements you have (each is optional; the options of the same",
        f"# name override them). SI units and radians; {angles} in degrees.",
        f"# [{design_file.REQUIREMENTS}]",
    ]
    in_degrees = set(degrees.values())
    for key in table_keys():
        if key in in_degrees:
            continue  # written in degrees, by the key that follows it
        example = key.example
        text = (
            f"[{', '.join(f'{v:g}' for v in example)}]" if isinstance(example, tuple) else example
        )
        comment = key.help
        if key.name in degrees:
            requirement = degrees[key.name]
            comment = requirement.help.replace("[rad]", f"[°] (or {requirement.name}, [rad])")
        lines.append(f"# {key.name} = {text}  # {comment}")
    return "\n".join(lines) + "\n"
