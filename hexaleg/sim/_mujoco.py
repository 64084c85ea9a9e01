"""The one place that imports MuJoCo: an optional extra, named in the error when missing."""

from __future__ import annotations

from typing import Any

from hexaleg.exceptions import HexalegError

EXTRA = "hexaleg[sim]"
"""The optional extra that installs MuJoCo."""


def require_mujoco() -> Any:
    """The ``mujoco`` module; a one-line :class:`HexalegError` naming the extra if missing."""
    try:
        import mujoco
    except ImportError:
        raise HexalegError(f"MuJoCo is not installed: pip install '{EXTRA}' to simulate") from None
    return mujoco
