"""How far a long run is: a bar on a terminal, a plain line every few seconds elsewhere.

A CI log, ``nohup`` or a redirect to a file cannot show a redrawn bar, so when stderr is
not a terminal :class:`Progress` prints ``done/total``, the elapsed time and an estimate
of the time left, at most once every :data:`INTERVAL` seconds (and a last line at the
end, if it printed any): a short run stays quiet. A run of named steps (the report's)
says which one is running: on the bar, and at the end of each line (``now: statics``).
"""

from __future__ import annotations

import contextlib
import math
import sys
import time
from collections.abc import Callable, Iterator
from typing import TextIO

from tqdm import tqdm

INTERVAL = 5.0
"""Least time between two progress lines [s]."""


class Progress:
    """Count finished items of ``total``; show it on ``stream`` (stderr by default).

    Args:
        total: Items to finish.
        done: Items already finished (a resumed run); the estimate uses only this run's.
        unit: What the items are, plural (``"designs"``).
        show: ``False`` shows nothing; otherwise a bar on a terminal, lines elsewhere.
        stream: Where to show it (default ``sys.stderr``).
        clock: Seconds from any origin (for tests).

    """

    def __init__(
        self,
        total: int,
        done: int = 0,
        unit: str = "designs",
        show: bool | None = None,
        stream: TextIO | None = None,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.total, self.done, self.unit = total, done, unit
        self._stream = sys.stderr if stream is None else stream
        self._clock = clock
        self._start = self._last = clock()
        self._first = done
        self._printed: int | None = None  # how many were done at the last line
        self.doing: str | None = None
        self._bar: tqdm[None] | None = None
        self._lines = show is not False and self._stream is not None
        if self._lines and _is_terminal(self._stream):
            self._bar = tqdm(total=total, initial=done, unit=unit[:-1], file=self._stream)
            self._lines = False

    def update(self, count: int, doing: str | None = None) -> None:
        """``count`` more items finished; ``doing`` names the one that starts, if any."""
        self.done += count
        if doing is not None:
            self.doing = doing
            if self._bar is not None:
                self._bar.set_description(doing, refresh=False)
        if self._bar is not None:
            self._bar.update(count)
        elif self._lines and self._clock() - self._last >= INTERVAL:
            self._print()

    def line(self) -> str:
        """``120/1600 designs (7.5 %), 1 min 5 s so far, about 14 min left``.

        While a named step runs (and the run is not over), ``, now: <step>`` ends it.
        """
        elapsed = self._clock() - self._start
        share = self.done / self.total if self.total else 1.0
        text = f"{self.done}/{self.total} {self.unit} ({100 * share:.1f} %), "
        text += f"{_duration(elapsed)} so far"
        finished_here = self.done - self._first
        if 0 < finished_here and self.done < self.total:
            left = (self.total - self.done) * elapsed / finished_here
            text += f", about {_duration(left)} left"
        if self.doing is not None and self.done < self.total:
            text += f", now: {self.doing}"
        return text

    def close(self) -> None:
        """End the bar, or print the last line if lines were printed (and it is news)."""
        if self._bar is not None:
            self._bar.close()
        elif self._printed is not None and self._printed != self.done:
            self._print()

    def __enter__(self) -> Progress:
        return self

    def __exit__(self, *_exc: object) -> None:
        self.close()

    def _print(self) -> None:
        print(f"hexaleg: {self.line()}", file=self._stream, flush=True)
        self._last = self._clock()
        self._printed = self.done


@contextlib.contextmanager
def progress_callback(unit: str, show: bool | None = None) -> Iterator[Callable[[int, int], None]]:
    """A ``(done, total)`` callback shown as :class:`Progress` (``unit`` plural).

    For code that learns its total only as it starts; the bar or the last line is closed
    when the block ends.
    """
    with contextlib.ExitStack() as stack:
        bars: list[Progress] = []

        def report(done: int, total: int) -> None:
            if not bars:
                bars.append(stack.enter_context(Progress(total, unit=unit, show=show)))
            bars[0].update(done - bars[0].done)

        yield report


def _is_terminal(stream: TextIO) -> bool:
    try:
        return stream.isatty()
    except (AttributeError, ValueError):  # no isatty, or closed
        return False


def _duration(seconds: float) -> str:
    """``45 s``, ``3 min 5 s``, ``2 h 10 min``."""
    seconds = max(0, math.ceil(seconds))
    hours, rest = divmod(seconds, 3600)
    minutes, secs = divmod(rest, 60)
    if hours:
        return f"{hours} h {minutes} min"
    return f"{minutes} min {secs} s" if minutes else f"{secs} s"
