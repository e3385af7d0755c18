"""README.md and docs/*.md describe the present; the history lives in CHANGELOG.md.

A document says what the FMUs and tools do, what the tests check and today's figures;
what was found, what changed and what it cost before and after belong to CHANGELOG.md,
which may name commits and issues. So, outside fenced code blocks (command output,
example files and GUIDs there are left alone), a document must not name

- a commit: a word of 7 to 40 lower-case hexadecimal digits with at least one digit and
  one letter (`5e2ab5d`, `e030f9a`), standing alone (not part of a longer word, of a
  hyphenated GUID such as `{5d0c3a52-8f0e-...}`, nor after `0x`); a word of letters a-f
  only (`defaced`) or of digits only is English or a number, not taken for a hash;
- an issue: `issue 12`, `issues 40 and 41`, `issue-12`, `issue #12`, or a bare `#12`
  (an issue number is the steering's bookkeeping, not something a reader can use; a
  reference into another project, `owner/name#42`, is a reader's link and allowed).

FOREIGN lists, by document, the hexadecimal words that name another project's commit
(the provenance of data taken from it, which a reader needs to reproduce it), each with
its reason.
"""

import re

from markdown_prose import DOCUMENTS, ROOT, prose


# Another project's commits a document names on purpose: document -> {word: reason}.
FOREIGN = {
    "docs/verify.md": {
        "5e3aaf4": "the Reference-FMUs commit (v0.0.20) its cross-check files were built from",
    },
}

HEX = re.compile(r"(?<![\w-])(?<!0x)[0-9a-f]{7,40}(?![\w-])")
ISSUE = re.compile(r"\bissues?[\s-]+#?\d+|(?<![\w/&#])#\d+\b", re.IGNORECASE)


def history(document: str, text: str) -> list:
    """'document:line: word' of each commit hash and issue reference in the prose."""
    allowed = FOREIGN.get(document, {})
    found = []
    for number, line in prose(text):
        for word in HEX.findall(line):
            if re.search(r"\d", word) and re.search(r"[a-f]", word) and word not in allowed:
                found.append(f"{document}:{number}: {word}")
        found += [f"{document}:{number}: {m.group(0)}" for m in ISSUE.finditer(line)]
    return found


def test_documents_name_no_commit_and_no_issue():
    found = [x for d in DOCUMENTS for x in history(d.relative_to(ROOT).as_posix(), d.read_text())]
    assert not found, (
        "history in the docs (say what is true today; move what was found, and when, to "
        "CHANGELOG.md):\n" + "\n".join(found))


def test_the_rule_finds_commits_and_issues_and_passes_guids_numbers_and_code():
    # A text of known content: the commit and the issue references are found (in the
    # order of the line), the rest are not history.
    text = ("Found on main (issue 42, commit 5e2ab5d); see issues 40 and #41,\n"
            "the issue-12 probe, Issue #7.\n"
            "GUID {5d0c3a52-8f0e-4d6b-9a51-3c2b7e41a901}, 0x5eedf0f0, 1234567, defaced,\n"
            "srenevey/ode-solvers#42, a heading\n"
            "# Title 1\n"
            "```text\ncommit 5e2ab5d (issue 42)\n```\n")
    assert history("docs/x.md", text) == [
        "docs/x.md:1: 5e2ab5d", "docs/x.md:1: issue 42", "docs/x.md:1: issues 40",
        "docs/x.md:1: #41", "docs/x.md:2: issue-12", "docs/x.md:2: Issue #7"]
    # Another project's commit passes only in the document FOREIGN names it for.
    line = "Reference-FMUs v0.0.20, commit 5e3aaf4"
    assert history("docs/verify.md", line) == []
    assert history("docs/fmus.md", line) == ["docs/fmus.md:1: 5e3aaf4"]
