"""How commands print: JSON, aligned name/value tables, and the files they wrote."""

from __future__ import annotations

import json
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from hexaleg.exceptions import HexalegError


def print_json(data: dict[str, Any]) -> None:
    """One JSON object on stdout; NaN and infinity are refused, never printed."""
    require_stdout()
    print(json.dumps(data, indent=2, allow_nan=False))


def print_table(title: str, rows: Sequence[tuple[str, str]]) -> None:
    """A title and aligned ``name  value`` rows on stdout."""
    require_stdout()
    width = max(len(name) for name, _ in rows)
    print(title)
    for name, value in rows:
        print(f"  {name:<{width}}  {value}")


def vector(values: Sequence[float], unit: str) -> str:
    """``(a, b, c) unit`` with four decimals."""
    return "(" + ", ".join(f"{v:.4f}" for v in values) + f") {unit}"


def lengths_title(what: str, lengths: Sequence[float]) -> str:
    """A table title naming the segment lengths, e.g. ``Manipulability, l = (0.2, 0.4, 0.4) m``."""
    return f"{what}, l = ({lengths[0]:.4g}, {lengths[1]:.4g}, {lengths[2]:.4g}) m"


def require_stdout() -> None:
    """Refuse to print a command's result to a closed stdout (Python would drop it)."""
    if sys.stdout is None:
        raise HexalegError("standard output is closed: nowhere to print the result")


def report_files(paths: Sequence[Path]) -> None:
    """Say on stderr which files were written."""
    for path in paths:
        print(f"wrote {path}", file=sys.stderr)
