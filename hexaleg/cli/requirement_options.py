"""The requirement options of ``decide`` and ``report``, over a design file's ``[requirements]``.

Each option is a key of the table (``--ground-clearance`` is ``ground_clearance``), made
from its declaration (:mod:`hexaleg.evaluation.requirement_specs`): its metavar and help are
the declaration's, each condition follows its requirement, and a key in degrees is the
alternative of its requirement's option. An option given on the command line overrides
the file's value.
"""

from __future__ import annotations

import argparse
import math
from typing import Any

from hexaleg.evaluation.requirement_specs import (
    REQUIREMENTS,
    ConditionSpec,
    RequirementSpec,
    condition_keys,
    degree_keys,
    table_keys,
)
from hexaleg.evaluation.requirements import Requirements, condition_value

GROUP = (
    "requirements (SI units, radians; each also a key of the design file's [requirements] "
    "table, which these override)"
)


def add_requirement_options(parser: argparse.ArgumentParser) -> None:
    """Add ``--payload``, ``--payload-at``, ``--slope``/``--slope-deg`` and the others."""
    group = parser.add_argument_group(GROUP)
    degrees = degree_keys()
    angles = set(degrees.values())
    alternatives: dict[str, Any] = {}
    for key in table_keys():
        target: Any = group
        if key in angles or key.name in degrees:
            requirement = degrees[key.name] if key.name in degrees else key
            if requirement.name not in alternatives:
                alternatives[requirement.name] = group.add_mutually_exclusive_group()
            target = alternatives[requirement.name]
        _add(target, key)


def _add(group: Any, key: RequirementSpec | ConditionSpec) -> None:
    if isinstance(key, RequirementSpec):
        group.add_argument(key.option, type=float, metavar=key.metavar, help=key.help)
        return
    count = len(key.metavar)
    metavar = key.metavar if count > 1 else key.metavar[0]
    group.add_argument(
        key.option, type=float, nargs=count if count > 1 else None, metavar=metavar, help=key.help
    )


def requirements_from_args(args: argparse.Namespace, base: Requirements) -> Requirements:
    """``base`` (the ``--design`` file's table) overridden by the options given."""
    changes: dict[str, Any] = {
        name: getattr(args, name) for name in REQUIREMENTS if getattr(args, name, None) is not None
    }
    degrees = degree_keys()
    for name, condition in condition_keys().items():
        given = getattr(args, name, None)
        if given is None:
            continue
        value = condition_value(condition, given)
        if name in degrees:
            changes[degrees[name].name] = math.radians(value)
        else:
            changes[name] = value
    return base.replace(**changes) if changes else base
