"""Value checks shared by every validated input: one message shape, naming field and range."""

from __future__ import annotations

import math
from typing import Any

from hexaleg.exceptions import DesignError


def require_finite(name: str, value: Any) -> float:
    """``value`` as a float if it is a finite real number (not a bool or a string)."""
    if isinstance(value, bool | str | bytes):
        raise DesignError(name, value, "must be a real number")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise DesignError(name, value, "must be a real number") from None
    if not math.isfinite(number):
        raise DesignError(name, value, "must be finite")
    return number


def require_in_range(name: str, value: Any, lower: float, upper: float, unit: str) -> float:
    """``value`` as a float if it is a real number in [lower, upper]; else a DesignError."""
    number = require_finite(name, value)
    if not lower <= number <= upper:
        raise DesignError(name, value, f"must lie in [{lower:g}, {upper:g}] [{unit}]")
    return number


def require_ratio(name: str, value: Any) -> float:
    """``value`` as a float if it lies in the open interval (0, 1); else a DesignError."""
    number = require_finite(name, value)
    if not 0 < number < 1:
        raise DesignError(name, value, "must lie in the open interval (0, 1)")
    return number
