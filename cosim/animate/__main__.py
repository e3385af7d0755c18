"""``python -m cosim.animate RESULT.csv [options]`` until the dispatcher ``cosim animate``."""

import sys

from .cli import main

sys.exit(main())
