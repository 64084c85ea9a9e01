"""Run one hexaleg command for the explorer, its progress lines printed often.

``python -m hexaleg.cli.job_runner COMMAND [OPTIONS]`` is ``hexaleg COMMAND
[OPTIONS]`` with a progress line on stderr every :data:`INTERVAL` seconds instead of
every few: the page's progress bar moves while a job runs (:mod:`hexaleg.explore.jobs`).
"""

from __future__ import annotations

import sys

INTERVAL = 0.5
"""Least time between two progress lines of a job [s]."""


def main(argv: list[str]) -> int:
    """Run ``hexaleg`` with ``argv``, progress lines every :data:`INTERVAL` seconds."""
    from hexaleg.cli.main import main as hexaleg
    from hexaleg.study import progress

    progress.INTERVAL = INTERVAL
    return hexaleg(argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
