"""One exception tree for everything hexaleg raises on purpose.

Every user mistake is a :class:`HexalegError`; the command-line interface turns
it into a one-line message and a non-zero exit status, never a traceback.
"""

from __future__ import annotations

from typing import Any


class HexalegError(Exception):
    """Base class of every error hexaleg raises deliberately."""


class DesignError(HexalegError, ValueError):
    """A design field has a value outside its valid range.

    Attributes:
        field: Name of the offending field, e.g. ``"l1"`` or ``"stance_limits.theta2"``.
        value: The value that was given.
        allowed: Human-readable statement of what is allowed, units included.

    """

    def __init__(self, field: str, value: Any, allowed: str) -> None:
        self.field = field
        self.value = value
        self.allowed = allowed
        super().__init__(f"{field} = {_format_value(value)} is not valid: {allowed}")


class TemplateError(HexalegError):
    """The Xacro templates could not be found or rendered into a valid URDF."""


class ModelError(HexalegError):
    """The Pinocchio model lacks a frame or joint hexaleg expects."""


def _format_value(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, tuple) and all(isinstance(v, float) for v in value):
        return "(" + ", ".join(f"{v:.6g}" for v in value) + ")"
    return repr(value)
