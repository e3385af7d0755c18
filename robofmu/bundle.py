"""What the `robofmu` wheel bundles with the harness: the FMUs (FMI 2.0, FMI 3.0, FMI 3.0
scalars only), the reference cases of `cosim verify` and the example scenarios, under
robofmu/data/ (hatch_build.py puts them there). Run from a checkout (an editable install,
or `python -m robofmu` in the repository), the same come from the repository: dist/,
tests/references/ and scenarios/ (after scripts/build-fmus.sh).

A bundled FMU's name is its model name, with fmi3/ or fmi3-scalar/ in front for the FMI 3.0
builds: "Pss3Plant", "fmi3/PID", "fmi3-scalar/Planner". Scenario files name them so
(``plant = "Pss3Plant"``): any FMU path without the .fmu suffix is such a name."""

from __future__ import annotations

import tomllib
from functools import lru_cache
from importlib.metadata import PackageNotFoundError, version as distribution_version
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent
DATA = PACKAGE / "data"
CHECKOUT = PACKAGE.parent
# name prefix -> (folder under the FMU folder, what it holds)
VARIANTS = {"": ("", "FMI 2.0"), "fmi3/": ("fmi3", "FMI 3.0"),
            "fmi3-scalar/": ("fmi3-scalar", "FMI 3.0, scalars only")}


def installed() -> bool:
    """Whether this package carries its data (an installed wheel), not a checkout."""
    return (DATA / "fmus").is_dir()


def fmu_dir() -> Path:
    """The folder of the bundled FMUs (dist/'s layout)."""
    return DATA / "fmus" if installed() else CHECKOUT / "dist"


def references_dir() -> Path:
    """The reference cases: <Model>/<case>/ folders."""
    return DATA / "references" if installed() else CHECKOUT / "tests" / "references"


def scenarios_dir() -> Path:
    """The example scenarios."""
    return DATA / "scenarios" if installed() else CHECKOUT / "scenarios"


def is_name(text: str) -> bool:
    """Whether a scenario's FMU entry names a bundled FMU (no .fmu suffix) rather than a
    file."""
    return not text.lower().endswith(".fmu")


def fmus() -> dict[str, Path]:
    """Bundled name -> path of every bundled FMU, FMI 2.0 first."""
    found = {}
    for prefix, (folder, _) in VARIANTS.items():
        for path in sorted((fmu_dir() / folder).glob("*.fmu")):
            found[prefix + path.stem] = path
    return found


def fmu(name: str) -> Path | None:
    """The bundled FMU `name`, or None."""
    return fmus().get(name)


def where_fmus_come_from() -> str:
    """For messages: which FMUs are bundled and where they are, or how to get them."""
    names = ", ".join(fmus())
    if names:
        return f"bundled: {names}"
    return ("none bundled here: this checkout's dist/ is empty; run 'bash "
            "scripts/build-fmus.sh' or install the robofmu wheel")


def scenarios() -> dict[str, Path]:
    """Name -> path of every example scenario."""
    return {p.stem: p for p in sorted(scenarios_dir().glob("*.toml"))}


def references() -> dict[str, Path]:
    """"<Model>/<case>" -> folder of every reference case."""
    return {f"{p.parent.parent.name}/{p.parent.name}": p.parent
            for p in sorted(references_dir().glob("*/*/*_ref.csv"))}


@lru_cache(maxsize=1)
def version() -> str:
    """The version: in a checkout, the workspace's (Cargo.toml), else the installed
    distribution's (the same number, written into the wheel when it was built)."""
    cargo = CHECKOUT / "Cargo.toml"
    if not installed() and cargo.is_file():
        with cargo.open("rb") as f:
            return str(tomllib.load(f)["workspace"]["package"]["version"])
    try:
        return distribution_version("robofmu")
    except PackageNotFoundError:
        return "unknown (neither installed nor in a checkout)"
