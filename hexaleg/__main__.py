"""``python -m hexaleg``: the command line."""

import sys

from hexaleg.cli import main

sys.exit(main())
