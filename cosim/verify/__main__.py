"""``python -m cosim.verify FMU [CASE] ...``: the verify subcommand on its own."""

import argparse
import sys

from .cli import add_arguments, run


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="cosim verify", description=__doc__)
    add_arguments(parser)
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    return run(parser.parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
