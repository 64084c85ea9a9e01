"""The live design explorer: a page on loopback where every length moved shows its consequences.

:mod:`.query` reads a request into a design and its conditions, :mod:`.answer` measures
it (one :func:`~hexaleg.evaluation.evaluate.evaluate`), :mod:`.cloud` measures the study's
designs around it, :mod:`.session` holds what was loaded and saves, :mod:`.server` serves
the page (``static/``) and the endpoints.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

__all__ = ["EXPLORED", "ExplorerServer", "Query", "Session", "parse_query"]

__getattr__, __dir__ = lazy_exports(__name__)

if TYPE_CHECKING:  # where each name is from: read by type checkers, the docs and lazy_exports
    from hexaleg.explore.answer import EXPLORED
    from hexaleg.explore.query import Query, parse_query
    from hexaleg.explore.server import ExplorerServer
    from hexaleg.explore.session import Session
