"""Every `cosim` command is in the one command table (robofmu.cli.COMMANDS): `cosim --help`
lists each, `cosim NAME --help` reaches its module's arguments, the `python -m robofmu.X`
entry points that the docs name go through the same table, and no module builds an
argument parser of its own. The expected commands are written out here from the
command list of docs/user-guide.md ("The command line"), not read from the table."""

from __future__ import annotations

import ast
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from robofmu.cli import main  # noqa: E402

# docs/user-guide.md, "The command line": one row per command, in this order.
DOCUMENTED = ["run", "check", "sweep", "ssp", "container", "bench", "demo", "verify",
              "animate", "fmus", "examples"]
# `python -m robofmu.X` entry points named in the docs and module docstrings.
ENTRY_POINTS = {"robofmu.bench": "bench", "robofmu.demo": "demo", "robofmu.animate": "animate",
                "robofmu.verify": "verify"}


def test_the_user_guide_lists_the_commands_written_here():
    text = (ROOT / "docs" / "user-guide.md").read_text()
    listed = re.findall(r"^\| `cosim ([a-z]+)\b", text, flags=re.MULTILINE)
    assert listed == DOCUMENTED


def test_cosim_help_lists_every_documented_command(capsys):
    assert main(["--help"]) == 0
    out = capsys.readouterr().out
    section = out.split("COMMAND\n", 1)[1].split("\noptions:", 1)[0]
    listed = re.findall(r"^    ([a-z]+)\b", section, flags=re.MULTILINE)
    assert listed == DOCUMENTED


@pytest.mark.parametrize("command", DOCUMENTED)
def test_each_command_help_reaches_its_module(command, capsys):
    assert main([command, "--help"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"usage: cosim {command} [-h]")
    # beyond -h: the module's own arguments were added (every command has some)
    assert re.search(r"^  (--[a-z]|[a-z])", out.split("\n\n", 2)[2], flags=re.MULTILINE)


@pytest.mark.parametrize("module, command", sorted(ENTRY_POINTS.items()))
def test_documented_python_m_entry_points_go_through_the_table(module, command):
    run = subprocess.run([sys.executable, "-m", module, "--help"], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith(f"usage: cosim {command} [-h]")


def test_no_module_builds_its_own_argument_parser():
    # the table's parser (robofmu/cli.py) is the one place that parses a command line
    builders = []
    for path in sorted((ROOT / "robofmu").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Call) and getattr(node.func, "attr",
                                                      getattr(node.func, "id", None)) \
                    == "ArgumentParser":
                builders.append(str(path.relative_to(ROOT)))
    assert builders == []


def test_every_module_with_a_command_interface_is_in_the_table():
    # a module with add_arguments(parser) and run(args) is a command: the table names it
    from robofmu.cli import COMMANDS
    commands = set()
    for path in sorted((ROOT / "robofmu").rglob("*.py")):
        tree = ast.parse(path.read_text())
        defined = {n.name for n in tree.body if isinstance(n, ast.FunctionDef)}
        if {"add_arguments", "run"} <= defined:
            parts = path.relative_to(ROOT).with_suffix("").parts
            commands.add(".".join(parts))
    table = {module for module, _ in COMMANDS.values()}
    assert len(commands) == len(DOCUMENTED)
    assert commands == table
