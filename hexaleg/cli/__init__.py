"""Command-line interface: ``hexaleg <command> [design options]``.

Every command takes the same design options (see ``hexaleg urdf --help``); lengths
are in metres and angles in radians. User mistakes end with one line on stderr and
exit status 2, never a traceback.
"""

from hexaleg.cli.main import COMMANDS, build_parser, main

__all__ = ["COMMANDS", "build_parser", "main"]
