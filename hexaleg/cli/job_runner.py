"""Run one hexaleg command for the explorer, its progress lines printed often.

``python -m hexaleg.cli.job_runner COMMAND [OPTIONS]`` is ``hexaleg COMMAND
[OPTIONS]`` with a progress line on stderr at every step (:data:`INTERVAL` 0) instead of
every few seconds: the page's progress bar moves with each step while a job runs, however
fast the steps are (:mod:`hexaleg.explore.jobs`).
"""

from __future__ import annotations

import sys

from hexaleg.cli.main import main as hexaleg
from hexaleg.study import progress

INTERVAL = 0.0
"""Least time between two progress lines of a job [s]: none, a line per step."""


def main(argv: list[str]) -> int:
    """Run ``hexaleg`` with ``argv``, a progress line at every step."""
    progress.INTERVAL = INTERVAL
    return hexaleg(argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
