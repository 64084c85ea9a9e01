"""3-D view in meshcat: the scene (:mod:`.scene`), served on loopback (:mod:`.server`)."""

from hexaleg.output.viewer.scene import (
    HIGHLIGHT,
    build_scene,
    extreme_name,
    static_html,
    write_static_html,
)
from hexaleg.output.viewer.server import LoopbackServer, client, serve_until_stopped

__all__ = [
    "HIGHLIGHT",
    "LoopbackServer",
    "build_scene",
    "client",
    "extreme_name",
    "serve_until_stopped",
    "static_html",
    "write_static_html",
]
