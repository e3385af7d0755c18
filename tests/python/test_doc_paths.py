"""Every repository path that README.md and docs/*.md name exists.

What counts as a path, in the prose of a document (fenced code blocks are left out: the
ones that run are run by test_documented_commands.py, the others are examples):
- a word of two or more `/`-separated parts whose first part is an entry at the top of
  the repository as git tracks it when the test runs (`crates/fmu/fmi/src/lib.rs`,
  `scripts/`, `fmus/*/src/*.rs`), so a renamed folder is followed without editing
  this file;
- the target of a relative Markdown link (`[the layer](fmi.md)`), from the document's
  folder; its anchor (`fmi.md#the-crates`, `#usage`) must be a heading of the target,
  as GitHub makes it (lower case, punctuation dropped, spaces as hyphens).

The rule: the path exists in the checkout (a glob, or a placeholder such as `<Model>`
or `{FMI_Version}` standing for one part, matches something), unless
- git ignores it: a build output, which a documented command produces (dist/ by
  scripts/build-fmus.sh, target/ by cargo, results/ by the documented commands, .venv/
  by scripts/setup-venv.sh, release/ by scripts/release.sh);
- PLACES says it names a file somewhere else than in this checkout (in the release
  folder, in the wheel, in another project's sources), by document and pattern, each
  with its reason.
"""

import re
import subprocess
from pathlib import Path

import pytest

from markdown_prose import DOCUMENTS, ROOT, prose


# Paths that name files outside this checkout: document -> [(pattern, reason)].
PLACES = {
    "docs/release.md": [
        (r"(fmus|ssp)/", "a file of the release folder that scripts/release.sh writes"),
        (r"[a-z_]+/(data|_native)/", "package data inside the wheel (hatch_build.py)"),
    ],
    "docs/interoperability.md": [
        (r"src/", "a source file of the importer the item quotes (libcosim, ecos, fmi-sim)"),
    ],
    "docs/fmus.md": [
        (r"fmus/\d", "the cross-check tree that scripts/cross-check.sh writes under OUT"),
    ],
    "docs/verify.md": [
        (r"fmus/", "the layout of the FMI cross-check repository, not of this one"),
    ],
}

PART = r"(?:\{[^}\s/]*\}|<[^>\s/]*>|[\w.*-])"
WORD = re.compile(rf"(?<![\w./:@~-])({PART}+(?:/{PART}*)+)")
LINK = re.compile(r"\]\(([^)\s]+)\)")
PLACEHOLDER = re.compile(r"<[^>/]*>|\{[^},/]*\}")
ALTERNATIVES = re.compile(r"\{([^}/]*,[^}/]*)\}")


def tracked_tops() -> set:
    """The first part of every path git tracks (the top of the repository)."""
    files = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True,
                           check=True).stdout.split()
    return {f.split("/")[0] for f in files}


def named_paths(text: str, folder: Path, tops: set):
    """(line, path as written, path from the repository root) of each path that the
    text of a document in `folder` (relative to the root) names."""
    for number, line in prose(text):
        for target in LINK.findall(line):
            if "://" in target or target.startswith(("#", "mailto:")):
                continue
            path = target.split("#")[0]
            if path:
                yield number, target, (folder / path).as_posix()
        for word in WORD.findall(line):
            word = word.rstrip(".,;:")
            if word.split("/")[0] in tops:
                yield number, word, word


def anchors(document: Path) -> set:
    """The anchors of a Markdown document's headings, as GitHub makes them."""
    heads = (h for _, h in prose(document.read_text()) if h.startswith("#"))
    return {re.sub(r"[^\w\- ]", "", h.lstrip("#").strip().lower()).replace(" ", "-")
            for h in heads}


def dead_anchors(document: str, text: str) -> list:
    """'document:line: link' of each relative link whose anchor is no heading of its
    target (a target that does not exist is a dead path, reported by dead_paths)."""
    dead = []
    for number, line in prose(text):
        for target in LINK.findall(line):
            if "://" in target or "#" not in target or target.startswith("mailto:"):
                continue
            path, anchor = target.split("#", 1)
            doc = ROOT / document if not path else ROOT / Path(document).parent / path
            if doc.suffix == ".md" and doc.is_file() and anchor not in anchors(doc):
                dead.append(f"{document}:{number}: {target}")
    return dead


def exists(path: str) -> bool:
    """The path (a glob, placeholders standing for one part, `{a,b}` for both a and
    b) names something here."""
    alternatives = ALTERNATIVES.search(path)
    if alternatives:
        start, end = alternatives.span()
        return all(exists(path[:start] + a + path[end:]) for a in alternatives[1].split(","))
    pattern = PLACEHOLDER.sub("*", path.rstrip("/"))
    if not any(c in pattern for c in "*?["):
        target = ROOT / pattern
        return target.is_dir() if path.endswith("/") else target.exists()
    return any(True for _ in ROOT.glob(pattern))


def ignored(paths: list) -> set:
    """The paths git ignores (build outputs), asked once for all."""
    if not paths:
        return set()
    run = subprocess.run(["git", "check-ignore", "--no-index", "--stdin"], cwd=ROOT,
                         input="\n".join(paths), capture_output=True, text=True)
    return set(run.stdout.split("\n")) - {""}


def elsewhere(document: str, path: str) -> bool:
    """PLACES says that the path names a file outside this checkout."""
    return any(re.match(pattern, path) for pattern, _ in PLACES.get(document, []))


def dead_paths(document: str, text: str) -> list:
    """'document:line: path' of each named path that the rule does not accept."""
    folder = Path(document).parent
    named = [(n, w, p) for n, w, p in named_paths(text, folder, tracked_tops())
             if not elsewhere(document, p)]
    missing = [(n, w, PLACEHOLDER.sub("x", p)) for n, w, p in named if not exists(p)]
    outputs = ignored([p for _, _, p in missing])
    return [f"{document}:{n}: {w}" for n, w, p in missing if p not in outputs]


@pytest.mark.parametrize("document", DOCUMENTS, ids=lambda d: d.relative_to(ROOT).as_posix())
def test_every_path_a_document_names_exists(document):
    dead = dead_paths(document.relative_to(ROOT).as_posix(), document.read_text())
    assert not dead, "paths that do not exist (fix the path, or the text):\n" + "\n".join(dead)


@pytest.mark.parametrize("document", DOCUMENTS, ids=lambda d: d.relative_to(ROOT).as_posix())
def test_every_anchor_a_document_links_to_exists(document):
    dead = dead_anchors(document.relative_to(ROOT).as_posix(), document.read_text())
    assert not dead, "links to headings that do not exist:\n" + "\n".join(dead)


def test_the_rule_finds_dead_paths_and_passes_outputs_globs_links_and_places():
    # A document of known content, read as if it were docs/release.md: dead are the
    # missing source file (line 1) and the missing link (line 3); the existing file,
    # the build output, the glob, the placeholder, the link that resolves from docs/,
    # the release folder's file (PLACES) and the fenced command are not reported.
    text = ("`crates/nothing/here.rs` and `crates/fmu/fmi/src/lib.rs`, `dist/nothing.fmu`,\n"
            "`fmus/*/src/lib.rs`, `fmus/<model>/Cargo.toml`, [guide](user-guide.md),\n"
            "[gone](gone.md), `fmus/fmi3/PID.fmu`; units rad/s, N.m/rad\n"
            "```sh\nbash scripts/not-checked-here.sh\n```\n")
    assert dead_paths("docs/release.md", text) == [
        "docs/release.md:1: crates/nothing/here.rs", "docs/release.md:3: gone.md"]
    # The same release-folder path in another document is this checkout's, and dead.
    assert dead_paths("docs/fmus.md", "`fmus/fmi3/PID.fmu`") == ["docs/fmus.md:1: fmus/fmi3/PID.fmu"]
    # `{a,b}` names both: a missing alternative is dead.
    assert dead_paths("docs/x.md", "`fmus/{pid,planner}/src/`") == []
    assert dead_paths("docs/x.md", "`fmus/{pid,nothing}/src/`") == ["docs/x.md:1: fmus/{pid,nothing}/src/"]
    # A renamed top-level folder is followed: a word whose first part git does not
    # track is no path of this repository (units, another project's owner/name).
    assert dead_paths("README.md", "rad/s, modelica/Reference-FMUs") == []
    # Anchors: a heading of the target (GitHub's form), of the document itself for `#x`.
    links = ("[a](fmi-layer.md#the-crates) [b](fmi-layer.md#no-such-heading) "
             "[c](#no-heading-here) [d](architecture.md#repository-layout)")
    assert dead_anchors("docs/release.md", links) == [
        "docs/release.md:1: fmi-layer.md#no-such-heading", "docs/release.md:1: #no-heading-here"]
    assert dead_anchors("docs/release.md", "[w](#the-wheel)") == []
