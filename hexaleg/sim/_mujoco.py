"""The one place that imports MuJoCo (an optional extra, named when missing), its errors worded."""

from __future__ import annotations

import re
import warnings
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from hexaleg.exceptions import HexalegError, RobotImportError, one_line

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


def compiled(spec: Any) -> Any:
    """``spec`` compiled (a link without mass, an inertia no body has: one line, the link named).

    Raises:
        RobotImportError: MuJoCo refuses the model.

    """
    try:
        return spec.compile()
    except ValueError as err:
        raise refusal(err) from None


def refusal(err: Exception) -> RobotImportError:
    """MuJoCo's error as one line: ``MuJoCo cannot simulate link 'x': <its reason>``."""
    lines = str(err).strip().splitlines() or [type(err).__name__]
    reason = lines[0].removeprefix("Error:").split("; use '")[0]  # its compiler's options: not ours
    named = re.search(r"Element name '([^']+)'", str(err))
    if named is None:
        return RobotImportError(f"MuJoCo cannot simulate the robot: {one_line(Exception(reason))}")
    return RobotImportError(
        f"MuJoCo cannot simulate link {named[1]!r}: {one_line(Exception(reason))} (its "
        "<inertial> in the robot file)"
    )
