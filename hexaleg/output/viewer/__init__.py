"""3-D view in meshcat: the scene, its legend beside it, served on loopback."""

from hexaleg.output.viewer.legend import HIGHLIGHT, torque_colour, with_legend
from hexaleg.output.viewer.scene import (
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
    "torque_colour",
    "with_legend",
    "write_static_html",
]
