"""Value checks shared by every validated input: one message shape, naming field and range.

Each check returns the value in its checked form (a float, an int, a tuple of floats)
or raises :class:`~hexaleg.exceptions.ParameterError` naming the field, the value and
what is allowed. None of them lets a Python error (OverflowError, TypeError...) through.
"""

from __future__ import annotations

import math
import operator
from collections.abc import Sequence
from typing import Any, TypeVar

import numpy as np

from hexaleg.exceptions import ParameterError

T = TypeVar("T")


def require_finite(name: str, value: Any) -> float:
    """``value`` as a float if it is a finite real number (not a bool or a string)."""
    number = _real(name, value)
    if number is None or not math.isfinite(number):
        raise ParameterError(name, value, "must be finite")
    return number


def require_in_range(name: str, value: Any, lower: float, upper: float, unit: str) -> float:
    """``value`` as a float if it is a real number in [lower, upper]; else a ParameterError."""
    number = _real(name, value)
    if number is not None and not math.isfinite(number):
        raise ParameterError(name, value, "must be finite")
    if number is None or not lower <= number <= upper:  # None: an int too large for a float
        raise ParameterError(name, value, f"must lie in [{lower:g}, {upper:g}] [{unit}]")
    return number


def require_ratio(name: str, value: Any) -> float:
    """``value`` as a float if it lies in the open interval (0, 1); else a ParameterError."""
    number = require_finite(name, value)
    if not 0 < number < 1:
        raise ParameterError(name, value, "must lie in the open interval (0, 1)")
    return number


def require_int(name: str, value: Any, lower: int, upper: int) -> int:
    """``value`` as an int if it is an integer (not a bool, float or string) in lower..upper."""
    if isinstance(value, bool):
        raise ParameterError(name, value, "must be an integer")
    try:
        number = operator.index(value)  # ints and NumPy integers; never floats or text
    except TypeError:
        raise ParameterError(name, value, "must be an integer") from None
    if not lower <= number <= upper:
        raise ParameterError(name, value, f"must lie in {lower:,}..{upper:,}")
    return number


def require_numbers(name: str, value: Any, items: Sequence[str], what: str) -> tuple[Any, ...]:
    """``value`` as a tuple if it is a sequence (not a string) of one value per item.

    Args:
        name: The field's name.
        value: What was given.
        items: The items' names, e.g. ``("root", "hip", "knee")``.
        what: What each item is, with its unit, for the message (``"angles [rad]"``).

    """
    count = len(items)
    shape = f"must be {count} {what}: {', '.join(items)}"
    if isinstance(value, str | bytes) or not isinstance(value, Sequence | np.ndarray):
        raise ParameterError(name, value, shape)
    if (isinstance(value, np.ndarray) and value.ndim != 1) or len(value) != count:
        raise ParameterError(name, value, shape)
    return tuple(value)


def require_instance(name: str, value: Any, kind: type[T], what: str) -> T:
    """``value`` if it is a ``kind``; else a ParameterError saying ``what`` is wanted."""
    if not isinstance(value, kind):
        raise ParameterError(name, value, f"must be {what}")
    return value


def require_distinct(name: str, values: Sequence[float]) -> None:
    """Refuse a value given twice (a study would compute and list it twice)."""
    seen: set[float] = set()
    for value in values:
        if value in seen:
            raise ParameterError(name, value, "each value once (it is given twice)")
        seen.add(value)


def _real(name: str, value: Any) -> float | None:
    """``float(value)`` for a real number, ``None`` for an int beyond a float's range."""
    if isinstance(value, bool | str | bytes):
        raise ParameterError(name, value, "must be a real number")
    try:
        return float(value)
    except OverflowError:
        return None
    except (TypeError, ValueError):
        raise ParameterError(name, value, "must be a real number") from None
