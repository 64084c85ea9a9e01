"""3-D view in meshcat: the scene, its legend beside it, served on loopback.

:mod:`.stage` sets every scene up (ground, robot copies, camera); :mod:`.scene` draws the
body's extremes, :mod:`.gait` a walking period; :mod:`.legend` says what their colours
mean, beside the scene; :mod:`.server` serves a scene on loopback or writes its static
page. A lazy front door (:mod:`hexaleg._lazy`): meshcat and the analyses load on use.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

__all__ = [
    "GAIT_LEGEND",
    "HIGHLIGHT",
    "Legend",
    "LoopbackServer",
    "STATICS_LEGEND",
    "Stage",
    "build_gait_scene",
    "build_scene",
    "client",
    "extreme_name",
    "serve_until_stopped",
    "static_html",
    "static_page",
    "torque_colour",
    "with_legend",
    "write_gait_html",
    "write_static_html",
]

__getattr__, __dir__ = lazy_exports(__name__)

if TYPE_CHECKING:  # where each name is from: read by type checkers, the docs and lazy_exports
    from hexaleg.output.viewer.gait import build_gait_scene, write_gait_html
    from hexaleg.output.viewer.legend import (
        GAIT_LEGEND,
        HIGHLIGHT,
        STATICS_LEGEND,
        Legend,
        torque_colour,
        with_legend,
    )
    from hexaleg.output.viewer.scene import (
        build_scene,
        extreme_name,
        static_html,
        write_static_html,
    )
    from hexaleg.output.viewer.server import (
        LoopbackServer,
        client,
        serve_until_stopped,
        static_page,
    )
    from hexaleg.output.viewer.stage import Stage
