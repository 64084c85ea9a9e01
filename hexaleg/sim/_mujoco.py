"""The one place that imports MuJoCo: an optional extra, named in the error when missing."""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from contextlib import contextmanager
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


@contextmanager
def mujoco_warnings() -> Iterator[list[str]]:
    """MuJoCo's warnings, collected in a list instead of written to ``./MUJOCO_LOG.TXT``.

    MuJoCo's default handler prints each warning and appends it to a log file in the
    working folder; within this block they are only collected (the caller says what they
    mean, in one line). The handler before is put back after.
    """
    mujoco = require_mujoco()
    caught: list[str] = []
    before = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(caught.append)
    try:
        yield caught
    finally:
        mujoco.set_mju_user_warning(before)


def pass_on(caught: list[str]) -> None:
    """Say in one warning what MuJoCo warned of in a run that did not diverge (if anything)."""
    if caught:
        times = "once" if len(caught) == 1 else f"{len(caught)} times"
        warnings.warn(f"MuJoCo warned {times} in the simulation: {caught[0]}", stacklevel=3)
