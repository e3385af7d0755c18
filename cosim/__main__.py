"""``python -m cosim COMMAND ...``: the same command line as ``cosim`` (cosim.cli)."""

import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
