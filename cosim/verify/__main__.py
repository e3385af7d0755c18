"""``python -m cosim.verify FMU [CASE] ...``: the same as ``cosim verify`` (cosim.cli)."""

import sys

from ..cli import main

if __name__ == "__main__":
    sys.exit(main(["verify", *sys.argv[1:]]))
