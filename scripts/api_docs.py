"""The API reference: pdoc renders the docstrings of the public API (the names of
robofmu.__all__: robofmu.api and robofmu.errors, as `import robofmu` shows them) into
HTML, and fails on any warning (a name that does not resolve, a docstring pdoc cannot
read, an annotation it cannot evaluate). Run by scripts/test.sh (CI):

    .venv/bin/python scripts/api_docs.py target/api-docs
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import pdoc

import robofmu


def main(out: Path) -> None:
    # robofmu imports its API on first use (module __getattr__, so that `cosim` starts
    # without numpy); pdoc reads a module's names from its namespace: import them there.
    for name in robofmu.__all__:
        setattr(robofmu, name, getattr(robofmu, name))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pdoc.render.configure(docformat="restructuredtext", show_source=False)
        pdoc.pdoc("robofmu", output_directory=out)
    pages = sorted(p.relative_to(out).as_posix() for p in out.rglob("*.html"))
    page = (out / "robofmu.html").read_text(encoding="utf-8")
    missing = [n for n in robofmu.__all__ if f'id="{n}"' not in page]
    if missing:
        raise SystemExit(f"api_docs: {out / 'robofmu.html'} lacks {', '.join(missing)}")
    print(f"api_docs: {len(robofmu.__all__)} public names documented in {out} ({', '.join(pages)})")


if __name__ == "__main__":
    main(Path(sys.argv[1]))
