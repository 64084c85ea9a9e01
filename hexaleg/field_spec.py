"""The declaration of a design field: one record that validation, files, options and docs read.

Each field of :class:`~hexaleg.design.HexapodDesign` is declared once, with
:func:`declare`, as a dataclass field whose metadata holds a :class:`FieldSpec`: what the
field is, its unit, its plausible range, its shape and the command-line group that offers
it. The design validates itself from these records, the design file names its keys and
writes its comments from them, the CLI builds its options from them and the class
docstring lists them; none of these restates a field.
"""

from __future__ import annotations

import dataclasses
import textwrap
from dataclasses import dataclass
from typing import Any, Literal

from hexaleg._checks import require_finite, require_in_range, require_instance, require_numbers
from hexaleg.limits import JointLimits

FieldKind = Literal["number", "triple", "limits", "choice", "mounts", "record"]
"""A field's shape: one number, three numbers, a joint-limit set, a named choice, leg mounts,
or a record of its own keys read from a table (the actuators, the battery)."""

OptionGroup = Literal["lengths", "body", "posture", "ratings"]
"""The command-line groups of design options (a command offers only those it uses)."""

SPEC = "hexaleg"
"""Key of a field's :class:`FieldSpec` in its dataclass metadata."""


@dataclass(frozen=True)
class FieldSpec:
    """Everything said about one design field, once.

    Attributes:
        help: What the field is, in lower case, without its unit: ``"coxa length"``.
        unit: Its SI unit, as written in brackets: ``"m"``, ``"rad"``, ``"N·m"``.
        bounds: Plausible (lower, upper) of each number, in ``unit``, inclusive; ``None``
            for any finite number (or for a field that is no number).
        kind: The field's shape (:data:`FieldKind`).
        items: Names of a triple's three numbers, e.g. ``("root", "hip", "knee")``.
        applies: Where the field applies, when not always: ``"hexagon layout"``.
        option: The command-line group that offers ``--<name>``; ``None``: files only.
        record: A record field's class: a value that is set must be one.
        name: The field's name, which is also its key in a design file.
        default: The field's default value.
        optional: ``None`` is a value: not given (a robot file's unrated joints).

    """

    help: str
    unit: str = ""
    bounds: tuple[float, float] | None = None
    kind: FieldKind = "number"
    items: tuple[str, ...] = ()
    applies: str = ""
    option: OptionGroup | None = None
    record: type | None = None
    name: str = ""
    default: Any = None
    optional: bool = False

    @property
    def key(self) -> str:
        """The field's key in a design file."""
        return self.name

    @property
    def flag(self) -> str | None:
        """The command-line option setting the field (``--body-length``), if any."""
        return None if self.option is None else "--" + self.name.replace("_", "-")

    @property
    def angle(self) -> bool:
        """Whether the field is an angle [rad] (a design file also takes it in degrees)."""
        return self.unit == "rad"

    @property
    def described(self) -> str:
        """One line: where it applies, what it is, its items and unit."""
        text = self.help + (f": {', '.join(self.items)}" if self.items else "")
        text += f" [{self.unit}]" if self.unit else ""
        return f"{self.applies}: {text}" if self.applies else text

    def check(self, value: Any) -> Any:
        """``value`` checked and normalized (floats, a tuple), or a ParameterError naming it.

        Numbers, triples, limit sets and records are checked here; a layout's choice and
        mounts depend on other fields, so the design checks them.
        """
        if value is None and self.optional:
            return None
        if self.kind == "number":
            return self._number(self.name, value)
        if self.kind == "triple":
            values = require_numbers(self.name, value, self.items, f"numbers [{self.unit}]")
            return tuple(
                self._number(f"{self.name}.{item}", v)
                for item, v in zip(self.items, values, strict=True)
            )
        if self.kind == "limits":
            return require_instance(
                self.name, value, JointLimits, "a JointLimits (theta1, theta2, theta3 [rad])"
            )
        if self.kind == "record" and self.record is not None and value is not None:
            return require_instance(self.name, value, self.record, f"a {self.record.__name__}")
        return value

    def _number(self, name: str, value: Any) -> float:
        if self.bounds is None:
            return require_finite(name, value)
        return require_in_range(name, value, *self.bounds, self.unit)


def declare(default: Any, help: str, unit: str = "", bounds: Any = None, **more: Any) -> Any:
    """A dataclass field with ``default`` whose metadata holds its :class:`FieldSpec`.

    Args:
        default: The field's default value (immutable).
        help: What the field is, without its unit (:attr:`FieldSpec.help`).
        unit: Its SI unit.
        bounds: Its plausible (lower, upper) range in ``unit``.
        **more: The other :class:`FieldSpec` attributes (kind, items, applies, option).

    """
    spec = FieldSpec(help, unit, bounds, **more)
    return dataclasses.field(default=default, metadata={SPEC: spec})


def field_specs(cls: type) -> tuple[FieldSpec, ...]:
    """The :class:`FieldSpec` of every declared field of dataclass ``cls``, in order."""
    return tuple(
        dataclasses.replace(f.metadata[SPEC], name=f.name, default=f.default)
        for f in dataclasses.fields(cls)
        if SPEC in f.metadata
    )


def attributes_section(specs: tuple[FieldSpec, ...], indent: str = "    ") -> str:
    """The Google-style ``Attributes:`` section of a class docstring listing ``specs``.

    Args:
        specs: The fields to list, in order.
        indent: The docstring's own indentation (a class body's: four spaces).

    """
    lines = [f"{indent}Attributes:"]
    for spec in specs:
        text = f"{spec.name}: {spec.described[0].upper()}{spec.described[1:]}."
        lines += textwrap.wrap(text, 92, initial_indent=indent * 2, subsequent_indent=indent * 3)
    return "\n".join(lines) + "\n\n" + indent
