"""Reads the results page (robofmu/verify/page.py) as a reader sees it: its matrix, the
text of each cell by row and column heading, and its links and images, with Python's
own HTML parser (a second reading, not the page's code); and opens it in a real browser
(Debian's chromium, headless; scripts/install-browser.sh installs it in CI)."""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote

import pytest


class _Page(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.tables: list[list[list[str]]] = []
        self.cell: list[str] | None = None
        self.links: list[str] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self.tables[-1].append([])
        elif tag in ("td", "th"):
            self.cell = []
        elif tag == "br" and self.cell is not None:
            self.cell.append("\n")
        elif tag == "a" and "href" in a:
            self.links.append(a["href"])
        elif tag == "img":
            self.links.append(a["src"])

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self.cell is not None:
            lines = "".join(self.cell).split("\n")
            self.tables[-1][-1].append("\n".join(line.strip() for line in lines))
            self.cell = None

    def handle_data(self, data):
        if self.cell is not None:
            self.cell.append(re.sub(r"\s+", " ", data))


def matrix(page: Path) -> dict[str, dict[str, str]]:
    """The page's first table: each row's heading -> each column's heading -> the cell's
    text, its interfaces' verdicts one a line."""
    parsed = _Page()
    parsed.feed(page.read_text())
    head, *rows = parsed.tables[0]
    return {row[0]: dict(zip(head[1:], row[1:])) for row in rows}


def unresolved(page: Path) -> list[str]:
    """Every link or image of the page that names neither a file beside it nor an anchor
    of the page."""
    parsed = _Page()
    parsed.feed(page.read_text())
    return [h for h in parsed.links
            if (h[1:] not in parsed.ids if h.startswith("#")
                else not (page.parent / unquote(h)).is_file())]


def chromium(*args) -> str:
    """Headless Chromium's stdout with `args`."""
    browser = shutil.which("chromium")
    if browser is None:
        pytest.fail("chromium is missing: run bash scripts/install-browser.sh")
    # A profile of its own per call: two test processes may run Chromium at once.
    with tempfile.TemporaryDirectory() as profile:
        done = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu",
                               "--hide-scrollbars", f"--user-data-dir={profile}", *args],
                              capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout


def check_in_browser(page: Path, screenshot: Path) -> None:
    """Every image of `page` loads in Chromium (the page counts those that did not into
    ``data-images-broken`` once loaded, read from the DOM Chromium dumps); a screenshot
    kept at `screenshot`."""
    dom = chromium("--virtual-time-budget=5000", "--dump-dom", page.as_uri())
    assert 'data-images-broken="0"' in dom, re.findall(r"data-images-broken=\"[^\"]*\"", dom)
    screenshot.parent.mkdir(parents=True, exist_ok=True)
    chromium(f"--screenshot={screenshot}", "--window-size=1280,1600", page.as_uri())
    data = screenshot.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20_000
