"""Reading a user's input file: a regular file only, looked at before it is opened, within a cap.

A FIFO waits for a writer forever, a device never ends (``/dev/zero``, ``/dev/urandom``) or
acts when opened (a watchdog), a folder is no file: :func:`check_input_file` refuses each
by ``os.stat`` before anything opens it, and a regular file larger than the caller's cap by
its size, so that no library is handed a file it would hang on or read whole.
:func:`read_input_file` then reads at most the cap (a file in ``/proc`` says it holds 0
bytes: what it gives beyond the cap is refused too), without waiting, even if the name
was replaced by a FIFO in between. Every refusal is one line naming the file.
"""

from __future__ import annotations

import errno
import os
import stat

from hexaleg.exceptions import HexalegError

_KINDS = (
    (stat.S_ISFIFO, "a FIFO"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISDIR, "a folder"),
    (stat.S_ISSOCK, "a socket"),
)
"""What a name that is not a regular file is, in words."""


def check_input_file(
    path: str | os.PathLike[str], limit: int, name: str, error: type[HexalegError] = HexalegError
) -> int:
    """The size [bytes] of the regular file ``path``, refused if it is none or over ``limit``.

    Args:
        path: The file (symbolic links followed).
        limit: The most bytes the caller reads of it.
        name: How messages name it (``"robot.urdf"``, ``"--design d.toml"``).
        error: The exception raised.

    Raises:
        HexalegError: (``error``) no such file, not a regular file, larger than ``limit``.

    """
    try:
        found = os.stat(path)
    except OSError as err:
        if err.errno == errno.ENOENT:
            raise error(f"{name}: no such file") from None
        raise error(f"{name} cannot be read: {err.strerror or err}") from None
    _refuse_irregular(found, limit, name, error)
    return found.st_size


def read_input_file(
    path: str | os.PathLike[str], limit: int, name: str, error: type[HexalegError] = HexalegError
) -> bytes:
    """The bytes of the regular file ``path``, at most ``limit`` (see :func:`check_input_file`).

    Raises:
        HexalegError: (``error``) as :func:`check_input_file`, or the system refuses the read.

    """
    check_input_file(path, limit, name, error)
    try:  # never waits: a FIFO swapped in after the check opens at once, and is refused
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC)
    except OSError as err:
        raise error(f"{name} cannot be read: {err.strerror or err}") from None
    try:
        _refuse_irregular(os.fstat(fd), limit, name, error)
        with os.fdopen(fd, "rb", closefd=False) as file:
            data = file.read(limit + 1)
    except OSError as err:
        raise error(f"{name} cannot be read: {err.strerror or err}") from None
    finally:
        os.close(fd)
    if len(data) > limit:
        raise error(f"{name} is larger than {size_text(limit)}, the most hexaleg reads of it")
    return data


def size_text(size: int) -> str:
    """A size in bytes for a message: ``16 MiB``, ``3 GiB``, ``512 bytes``."""
    for unit, scale in (("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if size >= scale:
            return f"{size / scale:.3g} {unit}"
    return f"{size} bytes"


def _refuse_irregular(
    found: os.stat_result, limit: int, name: str, error: type[HexalegError]
) -> None:
    kind = next((words for test, words in _KINDS if test(found.st_mode)), None)
    if kind is not None or not stat.S_ISREG(found.st_mode):
        raise error(f"{name} is {kind or 'no regular file'}, not a regular file: name a file")
    if found.st_size > limit:
        raise error(
            f"{name} is {size_text(found.st_size)}, larger than {size_text(limit)}, "
            "the most hexaleg reads of it"
        )
