"""Notes: what the harness decided for the user without being asked (a default that
changes what runs, a file found elsewhere than the scenario says). Each is printed once
per process on stderr as ``cosim: note: ...``, also under ``--quiet``: quiet hides
progress, never a decision."""

from __future__ import annotations

import sys

_said: set[str] = set()


def say(message: str) -> None:
    """Prints `message` once (a repeated one, e.g. the same scenario resolved again for
    a sweep's runs, is not printed again)."""
    if message in _said:
        return
    _said.add(message)
    print("cosim: note: " + " ".join(message.split()), file=sys.stderr)
