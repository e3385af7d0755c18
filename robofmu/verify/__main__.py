"""``python -m robofmu.verify FMU [CASE] ...``: the same as ``cosim verify`` (robofmu.cli)."""

import sys

from ..cli import entry

if __name__ == "__main__":
    sys.exit(entry("verify"))
