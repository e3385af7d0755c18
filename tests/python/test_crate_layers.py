"""No crate depends on one of a later layer (docs/architecture.md, "Layers").

The layers, by the folder a crate sits in, from the bottom:
  0 fmu:   crates/fmu/*, fmus/*, and the robot library `robofmu` (the repository root):
           what is linked into an FMU, or the library beside it;
  1 build: crates/build/*: what builds and checks FMUs;
  2 test:  crates/test/* and the test crates still at the top of crates/: test time;
  3 tools: crates/tools/*, benches/: what ships beside the FMUs, and the benchmarks.
A crate's normal and build dependencies stay in its layer or below. Its dev-dependencies
(test time only) may reach the build and test layers: an FMU crate's tests use the
test host over the linked model and the description writers, never the tools. Truth:
the crate graph as cargo reads it from the manifests (`cargo metadata`).
"""

import json
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LAYERS = {"fmu": 0, "build": 1, "test": 2, "tools": 3}
# Folders of one crate each, and folders whose every child is a crate, -> layer.
FOLDERS = {
    ".": "fmu", "crates/fmu": "fmu", "fmus": "fmu", "crates/build": "build",
    "crates/test": "test", "crates/tools": "tools", "benches": "tools",
}


def layer_of(folder: str) -> str:
    """The layer of a crate in `folder` (relative to the root, '.' for the root)."""
    if folder in FOLDERS:
        return FOLDERS[folder]
    parent = folder.rsplit("/", 1)[0] if "/" in folder else "."
    if parent != "." and parent in FOLDERS:
        return FOLDERS[parent]
    raise AssertionError(f"{folder}: no layer; put the crate under crates/fmu, "
                         "crates/build, crates/test or crates/tools")


def violations(packages: list, root: str) -> list:
    """(crate, dependency, kind) of every dependency on a crate of a later layer, among
    cargo metadata's `packages` of a workspace at `root`."""
    layer = {}
    for p in packages:
        folder = str(Path(p["manifest_path"]).parent.relative_to(root))
        layer[p["name"]] = layer_of(folder)
    found = []
    for p in packages:
        for d in p["dependencies"]:
            if d["name"] not in layer:
                continue
            kind = d["kind"] or "normal"
            allowed = LAYERS[layer[p["name"]]]
            if kind == "dev":
                allowed = max(allowed, LAYERS["test"])
            if LAYERS[layer[d["name"]]] > allowed:
                found.append((p["name"], d["name"], kind))
    return found


def metadata() -> dict:
    out = subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"],
                         cwd=ROOT, capture_output=True, text=True, check=True).stdout
    return json.loads(out)


def test_no_crate_depends_on_a_later_layer():
    m = metadata()
    names = {p["name"] for p in m["packages"]}
    assert {"robofmu", "robofmu-fmi", "robofmu-fmi-loader", "robofmu-packager",
            "robofmu-cli"} <= names
    assert violations(m["packages"], m["workspace_root"]) == []


def test_an_upward_dependency_is_found():
    # Written here, its answer known by construction: an FMU-layer crate that links a
    # tool, a build crate that links a test crate, and a dev-dependency of an FMU crate
    # on the test host (allowed).
    def package(name, folder, deps):
        return {"name": name, "manifest_path": f"/w/{folder}/Cargo.toml",
                "dependencies": [{"name": n, "kind": k} for n, k in deps]}
    packages = [
        package("model", "crates/fmu/model", [("tool", None)]),
        package("writer", "crates/build/writer", [("host", None)]),
        package("fmu", "fmus/fmu", [("host", "dev"), ("model", None)]),
        package("host", "crates/test/host", []),
        package("tool", "crates/tools/tool", [("model", None)]),
    ]
    assert violations(packages, "/w") == [("model", "tool", "normal"),
                                          ("writer", "host", "normal")]
