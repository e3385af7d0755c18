"""Writing the outputs all or nothing: every file is first written in full beside its
target under a temporary name, then all are renamed over their targets; when one cannot
be written, the temporary files and the folders made for them are removed."""

from __future__ import annotations

import errno
import os
import tempfile
from pathlib import Path


def _make_parents(folder: Path, made: list[Path]) -> None:
    missing = []
    while not folder.exists():
        missing.append(folder)
        folder = folder.parent
    for path in reversed(missing):
        path.mkdir()
        made.append(path)


def _stage(path: Path, data: bytes, mode: int) -> Path:
    handle, temporary = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    try:
        os.fchmod(handle, mode)
        with os.fdopen(handle, "wb") as f:
            f.write(data)
    except BaseException:
        os.unlink(temporary)
        raise
    return Path(temporary)


def write_all(files: dict[Path, bytes]) -> None:
    """Writes every file or, raising OSError, none."""
    umask = os.umask(0)
    os.umask(umask)
    made: list[Path] = []
    staged: dict[Path, Path] = {}
    path = None
    try:
        for path, data in files.items():
            if Path(path).is_dir():  # os.replace cannot put a file over a folder
                raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), str(path))
            _make_parents(Path(path).parent, made)
            staged[Path(path)] = _stage(Path(path), data, 0o666 & ~umask)
    except BaseException as e:
        for temporary in staged.values():
            temporary.unlink()
        for folder in reversed(made):
            folder.rmdir()
        if isinstance(e, OSError):
            raise OSError(e.errno, e.strerror, str(path)) from e
        raise
    for path, temporary in staged.items():
        os.replace(temporary, path)
