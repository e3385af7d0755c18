"""Every command in README.md and docs/*.md runs as written.

The convention (README and docs): shell commands a reader should run are in fenced
blocks with the info string `sh`, one command per line, run from the repository root
with `.venv/bin` first on PATH; Python snippets in ```python blocks run whole, from the
repository root. A block ```toml results/PATH (or json, yaml, csv) is a file the
reader writes: the test writes it there before the commands that follow it in the same
document (a file block naming a path outside results/ is only shown). Blocks that must not be run use `text`.
A block ```text prints holds lines the command just before it prints: each must be a
line of its stdout, the words equal and each number equal to the printed one within
one unit of its last printed digit (so a figure quoted in the docs is what runs).

Each command is one test case named by its file and line, run in document order. It
passes when it exits 0 and wrote nothing outside results/: the repository is snapshot
(every file's path, size and modification time) before and after; target/, .venv/ and
.venv-gemseo/ (the build's and the environments', thousands of files) are left out of
the snapshot,
and only the build commands in BUILDS may write to dist/, target/ and .venv/.
"""

import os
import re
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

# Commands not run here, each with the reason.
SKIPPED = {
    "bash scripts/test.sh": "the test suite itself: CI runs it (.ci/run), and this test is part of it",
    "bash scripts/memcheck.sh": "run by scripts/test.sh in CI",
    "bash scripts/release.sh --out results/release": (
        "run into a temporary folder by tests/python/test_release.py, which compares its "
        "files with docs/release.md"
    ),
    "cargo test --release -p robofmu-hostile --test matrix": (
        "run by `cargo test --workspace --release` in scripts/test.sh"
    ),
    "ROBOFMU_HOSTILE_SEQUENCES=240000 cargo test --release -p robofmu-hostile --test sequences": (
        "the long hostile probe, 33 minutes on 2 cores; CI runs the default count"
    ),
}
# The build commands: they write the build outputs by design.
BUILDS = {"bash scripts/demo.sh", "bash scripts/build-fmus.sh"}
BUILD_OUTPUTS = ("dist", "target", ".venv", "results")
# Paths the snapshot leaves out: git's, the build's, the environment's, Python's caches.
UNWATCHED = {".git", "target", ".venv", ".venv-gemseo", "__pycache__", ".pytest_cache",
             ".mypy_cache", ".ruff_cache"}
# A hang guard, not a speed assertion: the build may compile on a fresh machine.
TIMEOUT_S = {"build": 1800, "command": 300}

FENCE = re.compile(r"^```(\S*)\s*(\S*)\s*$")
FILE_LANGUAGES = {"toml", "json", "yaml", "csv"}


@dataclass
class Block:
    document: Path
    line: int  # of the opening fence, 1-based
    language: str
    argument: str
    lines: list = field(default_factory=list)


def blocks(document):
    """The fenced blocks of a Markdown document, in order."""
    found, current = [], None
    for number, text in enumerate(document.read_text().splitlines(), start=1):
        match = FENCE.match(text)
        if current is None and match:
            current = Block(document, number, match.group(1), match.group(2))
        elif current is not None and text.strip() == "```":
            found.append(current)
            current = None
        elif current is not None:
            current.lines.append(text)
    assert current is None, f"{document}:{current.line}: a code block is never closed"
    return found


@dataclass
class Step:
    """One command (sh line or python snippet) with the files written before it."""

    document: Path
    line: int
    kind: str  # "sh" or "python"
    text: str
    files: list  # (path, content) of the document's file blocks before it
    prints: list = field(default_factory=list)  # lines its stdout must hold (```text prints)

    @property
    def name(self):
        return f"{self.document.relative_to(ROOT)}:{self.line}"


def command_of(line):
    """A shell line without its trailing comment."""
    return re.sub(r"\s+#.*$", "", line).strip()


def steps():
    found = []
    for document in DOCUMENTS:
        files = []
        for block in blocks(document):
            if block.language in FILE_LANGUAGES and block.argument.startswith("results/"):
                files.append((block.argument, "\n".join(block.lines) + "\n"))
            elif block.language == "sh":
                for offset, text in enumerate(block.lines, start=1):
                    if text.strip() and not text.lstrip().startswith("#"):
                        line = block.line + offset
                        found.append(Step(document, line, "sh", text, list(files)))
            elif block.language == "text" and block.argument == "prints":
                assert found and found[-1].document == document, (
                    f"{document}:{block.line}: a ```text prints block follows no command")
                found[-1].prints += [x for x in block.lines if x.strip()]
            elif block.language == "python":
                found.append(
                    Step(document, block.line, "python", "\n".join(block.lines), list(files))
                )
    return found


STEPS = steps()


def snapshot():
    """Every watched file under the repository: path -> (size, modification time)."""
    state = {}
    for directory, subdirectories, files in os.walk(ROOT):
        subdirectories[:] = [d for d in subdirectories if d not in UNWATCHED]
        for name in files:
            path = Path(directory, name)
            stat = path.lstat()
            state[path.relative_to(ROOT).as_posix()] = (stat.st_size, stat.st_mtime_ns)
    return state


def environment():
    env = dict(os.environ)
    venv = ROOT / ".venv"
    env["PATH"] = f"{venv / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env["VIRTUAL_ENV"] = str(venv)
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    return env


def write_files(step):
    for relative, content in step.files:
        path = ROOT / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(content)


def run(step, build):
    timeout = TIMEOUT_S["build" if build else "command"]
    if step.kind == "sh":
        argv = ["bash", "-c", step.text]
    else:
        argv = [str(ROOT / ".venv" / "bin" / "python"), "-c", step.text]
    return subprocess.run(
        argv,
        cwd=ROOT,
        env=environment(),
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def test_every_document_has_its_commands_found():
    # Truth: the README holds the two commands and the first scenario by design.
    names = {command_of(s.text) for s in STEPS if s.kind == "sh"}
    assert {"bash scripts/demo.sh", "bash scripts/test.sh"} <= names
    assert any("cosim run results/first.toml" in n for n in names)


README_MAX_LINES = 200  # the front door, not the manual (developers' guide, README contract)
README_FIRST_SCREEN = 40  # the wheel install and the two commands must be read first


def test_readme_is_a_front_door():
    # Truth: the README contract: at most 200 lines; the wheel install and the two
    # commands (build and demo, whole test suite) within its first 40 lines.
    lines = (ROOT / "README.md").read_text().splitlines()
    assert len(lines) <= README_MAX_LINES, f"README.md has {len(lines)} lines"

    def line_of(wanted):
        return next((n for n, x in enumerate(lines, 1) if wanted(x)), None)

    where = {
        "wheel install": line_of(lambda x: x.startswith("pip install robofmu-")),
        "bash scripts/demo.sh": line_of(lambda x: x == "bash scripts/demo.sh"),
        "bash scripts/test.sh": line_of(lambda x: x == "bash scripts/test.sh"),
    }
    late = {k: v for k, v in where.items() if v is None or v > README_FIRST_SCREEN}
    assert not late, f"README.md: not within its first {README_FIRST_SCREEN} lines: {late}"


def test_sh_lines_are_one_command_each():
    # The convention: no line continuations, so that each line runs alone.
    broken = [s.name for s in STEPS if s.kind == "sh" and s.text.rstrip().endswith("\\")]
    assert not broken, f"sh lines continued with a backslash: {broken}"


@pytest.mark.parametrize("step", STEPS, ids=[s.name for s in STEPS])
def test_documented_command(step):
    command = command_of(step.text) if step.kind == "sh" else None
    if command in SKIPPED:
        pytest.skip(SKIPPED[command])
    write_files(step)
    build = command in BUILDS
    before = snapshot()
    result = run(step, build)
    after = snapshot()
    allowed = BUILD_OUTPUTS if build else ("results",)
    written = sorted(
        path
        for path in set(after) | set(before)
        if after.get(path) != before.get(path) and path.split("/")[0] not in allowed
    )
    assert result.returncode == 0, (
        f"{step.name}: `{step.text}` exited {result.returncode}\n"
        f"stdout:\n{result.stdout[-3000:]}\nstderr:\n{result.stderr[-3000:]}"
    )
    assert not written, f"{step.name}: `{step.text}` wrote outside results/: {written[:20]}"
    printed = result.stdout.splitlines()
    for quoted in step.prints:
        assert any(same_figures(quoted, line) for line in printed), (
            f"{step.name}: the docs quote\n{quoted}\nbut `{step.text}` printed\n"
            f"{result.stdout[-3000:]}")


NUMBER = re.compile(r"[-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?")


def same_figures(quoted: str, line: str) -> bool:
    """Whether `line` is `quoted` with each number within one unit of the quoted one's
    last digit (0.1178 matches 0.11781 and 0.1179, not 0.118 printed as 0.1172)."""
    words, numbers = NUMBER.split(quoted.strip()), NUMBER.findall(quoted)
    got_words, got = NUMBER.split(line.strip()), NUMBER.findall(line)
    if words != got_words or len(numbers) != len(got):
        return False
    for text, value in zip(numbers, got):
        mantissa = text.lower().split("e")[0]
        decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
        exponent = int(text.lower().split("e")[1]) if "e" in text.lower() else 0
        if abs(float(value) - float(text)) > 10.0 ** (exponent - decimals) * 1.0001:
            return False
    return True


if __name__ == "__main__":
    for s in STEPS:
        print(f"{s.name}: {s.text if s.kind == 'sh' else '(python snippet)'}")
    sys.exit(0)
