"""``python -m cosim.verify FMU [CASE] ...``: the same as ``cosim verify`` (cosim.cli)."""

import sys

from ..cli import entry

if __name__ == "__main__":
    sys.exit(entry("verify"))
