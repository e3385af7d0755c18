"""``cosim COMMAND ...`` (also ``python -m robofmu COMMAND ...``): the harness's one command
line. COMMANDS is the one table of its commands: each is a module with
``add_arguments(parser)`` and ``run(args) -> int``, imported only when its command is
named (``cosim --help`` importing all of them took 0.58 s instead of 0.05 s: fmpy,
numpy, matplotlib; benches/bench_startup.py). The ``python -m robofmu.MODULE`` entry
points that the docs name (robofmu.bench, robofmu.demo, robofmu.animate, robofmu.verify) go
through this table (``entry``).

Exit codes: 0 success; 1 the simulation or verification ran and failed (a declared limit
exceeded, failed runs, a mismatch); 2 a user error (a bad file, field or argument), told
in one line ``cosim: FILE: FIELD: problem; what to do``. ``--debug`` shows the traceback
of an error."""

from __future__ import annotations

import argparse
import importlib
import sys
import traceback

from . import bundle
from .errors import EXTRAS, CosimError, MissingExtra, ScenarioError

COMMANDS = {
    "run": ("robofmu.run", "simulate one scenario: CSV (SI, units sidecar), plots, metrics"),
    "check": ("robofmu.check", "validate a scenario against its FMUs and the workspace, "
              "without simulating"),
    "sweep": ("robofmu.sweep.cli", "run a parameter sweep on Dask"),
    "ssp": ("robofmu.ssp", "write a scenario as an SSP archive"),
    "container": ("robofmu.container", "write a scenario as a container FMU"),
    "bench": ("robofmu.bench", "time the master against a minimal FMPy loop"),
    "demo": ("robofmu.demo", "run the six bundled PID scenarios (and each under computed "
             "torque) with plots and tables"),
    "verify": ("robofmu.verify.cli", "verify the FMUs against independent references"),
    "animate": ("robofmu.animate.cli", "draw the robot of a run moving (GIF)"),
    "fmus": ("robofmu.list_fmus", "list the bundled FMUs (--path NAME: one FMU's path)"),
    "examples": ("robofmu.list_examples", "list the bundled example scenarios and reference "
                 "cases (--path NAME: one's path)"),
}
USER_ERROR, FAILED = 2, 1
DESCRIPTION = """The co-simulation harness of the robofmu FMUs (also: python -m robofmu).
'cosim COMMAND --help' describes a command; docs/user-guide.md the scenario files.

exit codes: 0 success; 1 the run or verification failed (a declared limit exceeded,
failed runs, a mismatch); 2 a user error (bad file, field or argument), told in one line
'cosim: FILE: FIELD: problem; what to do'. --debug shows the traceback of an error."""


class Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line and exit code 2."""

    def error(self, message: str):
        self.exit(USER_ERROR, f"cosim: {self.prog}: {message}; see '{self.prog} --help'\n")


def _command(argv: list[str]) -> str | None:
    for token in argv:
        if not token.startswith("-"):
            return token
    return None


def build_parser(command: str | None) -> Parser:
    parser = Parser(prog="cosim", description=DESCRIPTION,
                    formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--debug", action="store_true",
                        help="show the traceback of an error (for bug reports)")
    parser.add_argument("--version", action="version", version=f"%(prog)s {bundle.version()}",
                        help="the version (of the FMUs too: one number for the project)")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True,
                                parser_class=Parser)
    for name, (module, text) in COMMANDS.items():
        p = sub.add_parser(name, help=text, description=text)
        if name == command:
            add = importlib.import_module(module).add_arguments
            add(p)
            p.set_defaults(module=module)
    return parser


def _types(names) -> tuple[type, ...]:
    """The exception classes (module, name) of the modules a command has imported."""
    return tuple(getattr(sys.modules[m], n) for m, n in names
                 if m in sys.modules and hasattr(sys.modules[m], n))


def user_error_types() -> tuple[type, ...]:
    """The exceptions that are the user's mistake (exit 2)."""
    return (ScenarioError, MissingExtra) + _types([("robofmu.sweep.spec", "SpecError"),
                                      ("robofmu.container", "ContainerError"),
                                      ("robofmu.verify.errors", "VerifyError"),
                                      ("robofmu.animate.errors", "AnimateError")])


def _fail(message: str, code: int) -> int:
    print("cosim: " + " ".join(str(message).split()), file=sys.stderr)
    return code


def entry(command: str, argv: list[str] | None = None) -> int:
    """``python -m robofmu.MODULE ARGS``: ``cosim COMMAND ARGS`` (the same table, errors
    and exit codes)."""
    return main([command, *(sys.argv[1:] if argv is None else argv)])


def main(argv=None) -> int:
    """Runs one command; the FMU instances it shared (robofmu.instances) are closed
    before it returns (their extracted folders removed)."""
    try:
        return _main(argv)
    finally:
        shared = sys.modules.get("robofmu.instances")
        if shared is not None:
            shared.close_all()


def _main(argv) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    debug = "--debug" in argv
    argv = [a for a in argv if a != "--debug"]
    command = _command(argv)
    if command is not None and command not in COMMANDS and command.endswith((".toml", ".json")):
        argv.insert(argv.index(command), "run")  # the former `python -m robofmu SCENARIO`
        command = "run"
    try:
        args = build_parser(command if command in COMMANDS else None).parse_args(argv)
    except SystemExit as e:  # --help (0) or an argument error (2), already printed
        return e.code if isinstance(e.code, int) else USER_ERROR
    except ModuleNotFoundError as e:
        if debug:
            traceback.print_exc()
        top = (e.name or "").split(".")[0]
        if top in EXTRAS:
            return _fail(f"cosim {command} needs {top}, which robofmu leaves optional; pip "
                         f"install 'robofmu[{EXTRAS[top]}]'", USER_ERROR)
        return _fail(f"{command}: this command is not part of this version ({e.name} is "
                     "missing)", USER_ERROR)
    args.debug = debug  # commands that report their own errors re-raise them with it
    try:
        return int(importlib.import_module(args.module).run(args))
    except KeyboardInterrupt:
        more = ("; the table keeps every finished run: the same command with --resume "
                "continues" if args.module == "robofmu.sweep.cli" else "")
        return _fail("interrupted" + more, 130)
    except BrokenPipeError:
        sys.stderr.close()  # the reader went away: end quietly
        return 0
    except Exception as e:  # noqa: BLE001 - every error becomes one line
        if debug:
            traceback.print_exc()
        return _fail(*classify(e, getattr(args, "scenario", None)))


def classify(error: Exception, scenario=None) -> tuple[str, int]:
    """(one-line message, exit code) of an error a command raised; `scenario`: the
    file the command ran, named in a simulation failure."""
    if isinstance(error, user_error_types()):
        return str(error), USER_ERROR
    if isinstance(error, CosimError) or isinstance(error, _types([("robofmu.verify.errors",
                                                                  "RunFailed")])):
        where = f"{scenario}: " if scenario is not None else ""
        return f"{where}the simulation failed: {error}", FAILED
    if isinstance(error, OSError):
        where = f"{error.filename}: " if error.filename else ""
        return f"{where}{error.strerror or error}; check the path and its permissions", \
            USER_ERROR
    return (f"internal error ({type(error).__name__}: {error}); please report it with the "
            "output of --debug", FAILED)


if __name__ == "__main__":
    sys.exit(main())
