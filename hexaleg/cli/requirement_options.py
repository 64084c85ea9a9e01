"""The requirement options of ``decide`` and ``report``, over a design file's ``[requirements]``.

Each option has the name of a key of the table (``--ground-clearance`` is
``ground_clearance``); an option given on the command line overrides the file's value.
"""

from __future__ import annotations

import argparse
import math
from typing import Any

from hexaleg._checks import require_in_range
from hexaleg.design_file import load_design_file
from hexaleg.study.requirements import KINDS, Requirements
from hexaleg.study.requirements_table import DESCRIPTIONS

METAVARS: dict[str, str] = {
    "payload": "KG",
    "slope": "RAD",
    "ground_clearance": "M",
    "min_fb": "F",
    "leg_length": "M",
    "min_coxa": "M",
    "speed": "M/S",
}
"""Each requirement option's metavar (its help is the table key's description)."""

GROUP = (
    "requirements (SI units, radians; each also a key of the design file's [requirements] "
    "table, which these override)"
)


def add_requirement_options(parser: argparse.ArgumentParser) -> None:
    """Add ``--payload``, ``--payload-at``, ``--slope``/``--slope-deg`` and the others."""
    group = parser.add_argument_group(GROUP)
    for name in KINDS:
        metavar, text = METAVARS[name], DESCRIPTIONS[name]
        option = "--" + name.replace("_", "-")
        if name == "slope":
            slope = group.add_mutually_exclusive_group()
            slope.add_argument(option, type=float, metavar=metavar, help=text)
            slope.add_argument(
                "--slope-deg", type=float, metavar="DEG", help=DESCRIPTIONS["slope_deg"]
            )
            continue
        group.add_argument(option, type=float, metavar=metavar, help=text)
        if name == "speed":
            group.add_argument(
                "--step-height", type=float, metavar="M", help=DESCRIPTIONS["step_height"]
            )
        if name == "payload":
            group.add_argument(
                "--payload-at",
                type=float,
                nargs=3,
                metavar=("X", "Y", "Z"),
                help=DESCRIPTIONS["payload_at"],
            )


def requirements_from_args(args: argparse.Namespace) -> Requirements:
    """The requirements of the ``--design`` file's table, overridden by the options given."""
    path = getattr(args, "design", None)
    base = Requirements() if path is None else load_design_file(path, Requirements.from_table)[1]
    changes: dict[str, Any] = {
        name: getattr(args, name) for name in KINDS if getattr(args, name, None) is not None
    }
    if getattr(args, "slope_deg", None) is not None:
        changes["slope"] = math.radians(require_in_range("slope_deg", args.slope_deg, 0, 90, "°"))
    if getattr(args, "payload_at", None) is not None:
        changes["payload_at"] = tuple(args.payload_at)
    if getattr(args, "step_height", None) is not None:
        changes["step_height"] = args.step_height
    return base.replace(**changes) if changes else base
