"""``python -m robofmu COMMAND ...``: the same command line as ``cosim`` (robofmu.cli)."""

import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
