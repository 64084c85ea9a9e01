"""One exception tree for everything hexaleg raises on purpose.

Every user mistake is a :class:`HexalegError`; the command-line interface turns
it into a one-line message and a non-zero exit status, never a traceback. A value
that is out of its range or of the wrong type is a :class:`ParameterError`, which
carries the field, the value and what is allowed, and says them in one line of
bounded length (:func:`shorten` is the one place that shortens a value for it).
"""

from __future__ import annotations

import reprlib
from typing import Any


class HexalegError(Exception):
    """Base class of every error hexaleg raises deliberately."""


class ParameterError(HexalegError, ValueError):
    """A parameter (a design field, an option, an argument) has a value it cannot take.

    Attributes:
        field: Name of the offending field, e.g. ``"l1"``, ``"stance_limits.theta2"``
            or ``"samples"``.
        value: The value that was given, as given.
        allowed: Human-readable statement of what is allowed, units included.

    """

    def __init__(self, field: str, value: Any, allowed: str) -> None:
        self.field = field
        self.value = value
        self.allowed = allowed
        super().__init__(f"{field} = {shorten(value)} is not valid: {allowed}")

    def __reduce__(self) -> tuple[Any, ...]:  # picklable across process pools
        return (type(self), (self.field, self.value, self.allowed))


DesignError = ParameterError
"""The name of :class:`ParameterError` before it served every parameter (hexaleg ≤ 0.2)."""


class TemplateError(HexalegError):
    """The Xacro templates could not be found or rendered into a valid URDF."""


class ModelError(HexalegError):
    """The Pinocchio model lacks a frame or joint hexaleg expects."""


class RobotImportError(HexalegError):
    """A robot file (URDF or Xacro) could not be read, or its legs are not hexaleg's kind.

    The message is one line naming what was found: the file's problem, or the legs,
    joints and axes that do not make six yaw–pitch–pitch legs.
    """


class RobotImportWarning(UserWarning):
    """A robot file was imported, but something in it deserves a look (an inertia, an axis)."""


MAX_MESSAGE_CHARS = 300
"""Longest library message quoted in a refusal [characters] (xacro nests its contexts)."""


def one_line(err: BaseException) -> str:
    """A library's exception as one line of at most :data:`MAX_MESSAGE_CHARS` characters.

    Its lines joined (coal, assimp and MuJoCo write several), its type's name if it says
    nothing.
    """
    text = " ".join(str(err).split()) or type(err).__name__
    return text if len(text) <= MAX_MESSAGE_CHARS else text[: MAX_MESSAGE_CHARS - 3] + "..."


MAX_VALUE_CHARS = 80
"""Longest text of a value in a message: a million-element list still gives one short line."""


class _Shortener(reprlib.Repr):
    """``reprlib`` with floats at 6 significant digits and huge integers by their size."""

    def __init__(self) -> None:
        super().__init__()
        self.maxlevel = 2
        self.maxtuple = self.maxlist = self.maxarray = self.maxdict = 6
        self.maxset = self.maxfrozenset = self.maxdeque = 6
        self.maxstring = self.maxother = MAX_VALUE_CHARS

    def repr_float(self, x: float, level: int) -> str:
        return f"{x:.6g}"

    repr_float64 = repr_float

    def repr_int(self, x: int, level: int) -> str:
        if x.bit_length() > 64:  # str() of a 5000-digit int raises; its size says enough
            digits = int(x.bit_length() * 0.30103) + 1
            return f"{'-' if x < 0 else ''}<an integer of about {digits} digits>"
        return str(x)


_SHORTENER = _Shortener()


def shorten(value: Any) -> str:
    """``value`` as text for a one-line message: floats to 6 digits, long ones elided.

    Containers show their first items and ``...``, nesting past two levels is elided,
    strings and other objects are cut at :data:`MAX_VALUE_CHARS` characters, and
    nothing raises (a value whose ``repr`` fails shows its type).
    """
    try:
        text = _SHORTENER.repr(value)
    except Exception:  # a hostile __repr__ must not hide the real error
        text = f"<{type(value).__name__}>"
    text = " ".join(text.split())  # one line, whatever the value held
    if len(text) > MAX_VALUE_CHARS:
        text = text[: MAX_VALUE_CHARS - 3] + "..."
    return text
