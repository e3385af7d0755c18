"""``python -m robofmu.animate RESULT.csv [options]``: the same as ``cosim animate``."""

import sys

from .cli import main

sys.exit(main())
