"""A design file's ``[robot]`` table: the imported robot that ``hexaleg design import`` wrote."""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any

from hexaleg.design_file import ROBOT, DesignFileError, read_design_text

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib


def load_robot_table(path: str | os.PathLike[str]) -> dict[str, Any] | None:
    """A TOML design file's ``[robot]`` table, or ``None`` if it has none (or is JSON)."""
    path = Path(path)
    if path.suffix.lower() != ".toml":
        return None
    try:
        table = tomllib.loads(read_design_text(path)).get(ROBOT)
    except (tomllib.TOMLDecodeError, ValueError, RecursionError):
        return None  # the design's own reading reports it
    if table is not None and not isinstance(table, dict):
        raise DesignFileError(f"{path}: robot must be a [robot] table")
    return table
