"""The results page of ``cosim verify TREE --html`` opened in a real browser (Debian's
chromium, headless; scripts/install-browser.sh installs it in CI): every link of the
page resolves (a file beside it, or an anchor of the page), every image loads, and a
screenshot is kept at results/verify-page/screenshot.png (it was looked at: the matrix,
the numbers and the plots show).

Truths: the file system for the links; Chromium's own loading of each image (the page
counts the images that did not load into ``data-images-broken`` once loaded, read from
the DOM Chromium dumps); the tree is our FMUs laid out by scripts/cross-check.sh, plus
one case whose reference is wrong (it must show failed, its plots with it)."""

import os
import re
import subprocess
import sys
from html.parser import HTMLParser
from urllib.parse import unquote

import pytest

from conftest import ROOT
from page_matrix import check_in_browser

SCREENSHOT = ROOT / "results" / "verify-page" / "screenshot.png"


class Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.links, self.images, self.ids = [], [], set()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "a" and "href" in a:
            self.links.append(a["href"])
        if tag == "img":
            self.images.append(a["src"])


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    tree = tmp_path_factory.mktemp("tree")
    env = dict(os.environ, PYTHON=sys.executable)
    subprocess.run(["bash", "scripts/cross-check.sh", str(tree)], cwd=ROOT, env=env,
                   check=True, capture_output=True)
    # One case made to fail: PID's reference raised by 1 from the first row on.
    case = tree / "fmus/2.0/cs/linux64/robofmu"
    (pid,) = case.glob("*/PID")
    reference = pid / "PID_ref.csv"
    lines = reference.read_text().splitlines()
    lines[1:] = [",".join([row.split(",")[0]] + [repr(float(x) + 1.0) for x in row.split(",")[1:]])
                 for row in lines[1:]]
    reference.write_text("\n".join(lines) + "\n")
    html = tree / "page" / "index.html"
    done = subprocess.run([sys.executable, "-m", "robofmu.verify", str(tree / "fmus"),
                           "--out", str(tree / "out"), "--html", str(html), "--jobs", "2"],
                          cwd=ROOT, capture_output=True, text=True)
    assert done.returncode == 1, done.stdout + done.stderr  # the PID case fails
    assert "7 passed, 1 failed, 0 rejected" in done.stdout.splitlines()[-1]
    return html


def test_every_link_resolves_and_every_case_is_in_the_matrix(page):
    parsed = Links()
    parsed.feed(page.read_text())
    files = [h for h in parsed.links if not h.startswith("#")]
    anchors = [h[1:] for h in parsed.links if h.startswith("#")]
    assert len(anchors) == 8 and set(anchors) <= parsed.ids
    assert files and parsed.images
    for target in files + parsed.images:
        assert (page.parent / unquote(target)).is_file(), target
    text = page.read_text()
    assert len(re.findall(r'class="failed" href="#', text)) == 1
    assert len(re.findall(r'class="passed" href="#', text)) == 7


def test_every_image_loads_in_chromium_and_a_screenshot_is_kept(page):
    check_in_browser(page, SCREENSHOT)
