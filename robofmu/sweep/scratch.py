"""The local folders holding a sweep's FMU files, one per process (this one, each Dask
worker), named after the host and the process: cosim-fmus-HOST-PID-XXXXXXXX in the
system's temporary folder.

A process removes its folder when it closes its store; a worker that dies (killed by the
OS, or by a crash inside an FMU) runs no clean-up, so every new folder and the end of every
sweep first remove the folders on this host whose process no longer exists.
"""

from __future__ import annotations

import os
import re
import shutil
import socket
import tempfile
from pathlib import Path

PREFIX = "cosim-fmus-"


def _host() -> str:
    return re.sub(r"[^A-Za-z0-9.]", "_", socket.gethostname()) or "host"


def make() -> Path:
    """A new folder of this process (after removing those of dead processes)."""
    reclaim()
    return Path(tempfile.mkdtemp(prefix=f"{PREFIX}{_host()}-{os.getpid()}-"))


def owner(folder: Path) -> int | None:
    """The process that made `folder` on this host, or None (another host's, or not ours)."""
    head, pid, _ = folder.name.rsplit("-", 2) if folder.name.count("-") >= 3 else ("", "", "")
    if head != f"{PREFIX}{_host()}" or not pid.isdigit():
        return None
    return int(pid)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    return True


def reclaim() -> None:
    """Removes this host's folders whose process has ended."""
    for folder in Path(tempfile.gettempdir()).glob(f"{PREFIX}{_host()}-*"):
        pid = owner(folder)
        if pid is not None and not _alive(pid):
            shutil.rmtree(folder, ignore_errors=True)
