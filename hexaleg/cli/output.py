"""How commands print and write: JSON, aligned tables, output paths and the files written.

Every output path a command takes (``--csv``, ``--html``, ``--video``, ``-o``, ``--plot``) is
checked before computing by :func:`check_outputs`, with one rule for each: a file as
:mod:`hexaleg._io` writes it (``-`` is standard output), a plot folder as a report folder
(:mod:`hexaleg._folders`: hexaleg's marker, a folder holding anything else refused), and
no two outputs on one path.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import sys
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any, TextIO

from hexaleg._folders import check_replaceable_folder, replace_folder
from hexaleg._io import check_output_file, shown, standard_stream
from hexaleg.exceptions import HexalegError

PLOT_KIND = "figures"
"""What a plot folder's marker says it is (the figures of every command may share one)."""


def print_json(data: dict[str, Any], file: TextIO | None = None) -> None:
    """One JSON object on ``file`` (stdout), strict: never NaN or infinity.

    A number JSON cannot hold is written ``null``, and ``not_finite`` names where and what
    it was (``{"best.over_rating[0].peak": "inf"}``): the answer is still read by every
    JSON reader, and says what it could not say.
    """
    require_stdout()
    missing: dict[str, str] = {}
    found = _finite(data, "", missing)
    if missing:
        found["not_finite"] = missing
    print(json.dumps(found, indent=2, allow_nan=False), file=file)


def _finite(value: Any, where: str, missing: dict[str, str]) -> Any:
    """``value`` with every non-finite float ``None``, each recorded by its path."""
    if isinstance(value, float) and not math.isfinite(value):
        missing[where] = repr(value)
        return None
    if isinstance(value, Mapping):
        return {k: _finite(v, f"{where}.{k}".lstrip("."), missing) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v, f"{where}[{i}]", missing) for i, v in enumerate(value)]
    return value


def print_table(title: str, rows: Sequence[tuple[str, str]], file: TextIO | None = None) -> None:
    """A title and aligned ``name  value`` rows on ``file`` (stdout)."""
    require_stdout()
    width = max(len(name) for name, _ in rows)
    print(title, file=file)
    for name, value in rows:
        print(f"  {name:<{width}}  {value}", file=file)


def columns(rows: Sequence[Sequence[str]]) -> list[str]:
    """Rows of cells as aligned lines: the first column to the left, the others to the right."""
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    return [
        "  ".join(
            [row[0].ljust(widths[0])]
            + [cell.rjust(width) for cell, width in zip(row[1:], widths[1:], strict=True)]
        ).rstrip()
        for row in rows
    ]


def vector(values: Sequence[float], unit: str) -> str:
    """``(a, b, c) unit`` with four decimals."""
    return "(" + ", ".join(f"{v:.4f}" for v in values) + f") {unit}"


def lengths_title(what: str, lengths: Sequence[float]) -> str:
    """A table title naming the segment lengths, e.g. ``Manipulability, l = (0.2, 0.4, 0.4) m``."""
    return f"{what}, l = ({lengths[0]:.4g}, {lengths[1]:.4g}, {lengths[2]:.4g}) m"


def refuse_inputs_as_outputs(
    outputs: Mapping[str, str | None], inputs: Mapping[str, tuple[str, str | Path | None]]
) -> None:
    """Refuse an output file that is a file the command reads, by any name.

    The same file is the same device and inode, so a link or a ``../`` path to an input is
    caught as the input itself; an output not there yet is no input.

    Args:
        outputs: Each output option and its path (``None``: not asked for).
        inputs: What each input is (``"robot file"``) → how it was named and its path.

    Raises:
        HexalegError: ``-o r.urdf is the robot file read (--urdf r.urdf): write it elsewhere``.

    """
    read = {}
    for what, (named, path) in inputs.items():
        with contextlib.suppress(OSError):
            if path is not None:
                found = os.stat(path)
                read[(found.st_dev, found.st_ino)] = (what, named)
    for flag, target in outputs.items():
        if target is None or standard_stream(target) is not None:
            continue
        try:
            found = os.stat(target)
        except OSError:  # not there: it is none of the inputs
            continue
        if (found.st_dev, found.st_ino) in read:
            what, named = read[(found.st_dev, found.st_ino)]
            raise HexalegError(f"{flag} {target} is the {what} read ({named}): write it elsewhere")


def require_stdout() -> None:
    """Refuse to print a command's result to a closed stdout (Python would drop it)."""
    if sys.stdout is None:
        raise HexalegError("standard output is closed: nowhere to print the result")


def report_files(paths: Sequence[Path]) -> None:
    """Say on stderr which files were written (not standard output: it shows itself)."""
    for path in paths:
        if standard_stream(os.fspath(path)) is None:
            print(f"wrote {path}", file=sys.stderr)


def check_outputs(
    files: Mapping[str, str | None], folders: Mapping[str, str | None] | None = None
) -> None:
    """Refuse, before computing, the output files and plot folders asked for.

    Args:
        files: Each file option and its path (``None``: not asked for).
        folders: Each plot-folder option and its path (``None``: not asked for).

    Raises:
        HexalegError: a path that cannot be written, a plot folder holding what hexaleg
            did not write, two outputs on one path, or a file inside an output folder.

    """
    paths = {flag: path for flag, path in files.items() if path is not None}
    plots = {flag: path for flag, path in (folders or {}).items() if path is not None}
    for path in paths.values():
        check_output_file(path)
    for path in plots.values():
        check_replaceable_folder(path, PLOT_KIND, merge=True)
    seen: dict[str, tuple[str, bool]] = {}  # option → where it writes, and if a folder
    for flag, path in [*plots.items(), *paths.items()]:
        where = _where(path)
        for other, (there, folder) in seen.items():
            if where == there or (folder and Path(where).is_relative_to(there)):
                raise HexalegError(
                    f"{other} and {flag} both write to {shown(path)}: give each output its own path"
                )
        seen[flag] = (where, flag in plots)


def summary_stream(*files: str | None) -> TextIO | None:
    """Where a command prints its result: stderr when one of ``files`` is stdout (``-``)."""
    on_stdout = any(f is not None and standard_stream(f) == 1 for f in files)
    return sys.stderr if on_stdout else None


def write_plots(folder: str, write: Callable[[Path], Sequence[Path]]) -> None:
    """Write figures (``write`` into the folder it is given) into the plot folder ``folder``.

    The folder follows the rules of report folders (:func:`check_outputs`); the figures
    are brought in when all are drawn, and named on stderr.
    """
    with replace_folder(folder, PLOT_KIND, merge=True) as staging:
        written = write(staging)
    report_files([Path(folder) / path.relative_to(staging) for path in written])


def _where(path: str) -> str:
    stream = standard_stream(path)
    return f"/dev/fd/{stream}" if stream is not None else os.path.realpath(path)
