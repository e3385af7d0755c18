"""scripts/module_cycles.py: the FMI layer's modules import no module that imports them
back (issue 18), and the checker finds a cycle where there is one (a crate written here,
its cycle known by construction)."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SPEC = importlib.util.spec_from_file_location("module_cycles", ROOT / "scripts" / "module_cycles.py")
module_cycles = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(module_cycles)


def graph_of(src):
    return module_cycles.edges(module_cycles.modules(src))


def test_the_fmi_layer_has_no_import_cycle():
    graph = graph_of(ROOT / "crates" / "fmu" / "fmi" / "src")
    assert len(graph) > 40, "every file of the layer is a module"
    assert module_cycles.cycles(graph) == []


def test_a_cycle_through_use_paths_and_groups_is_found(tmp_path):
    # core/a -> core/b (grouped super:: import), core/b -> core/c (crate:: path in
    # code), core/c -> core/a: one cycle of three; core -> its child a and d -> its
    # parent core are no edges.
    files = {
        "lib.rs": "pub mod core;\n",
        "core/mod.rs": "pub mod a; pub mod b; pub mod c; pub mod d;\nuse self::a::A;\n",
        "core/a.rs": "use super::{b::B, d};\npub struct A;\n",
        "core/b.rs": "pub struct B;\nfn f() { crate::core::c::g(); }\n",
        "core/c.rs": "// use super::d; (a comment is no import)\npub fn g() { let _ = super::a::A; }\n",
        "core/d.rs": "use super::super::core;\n",
    }
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    graph = graph_of(tmp_path)
    assert graph["core::a"] == {"core::b", "core::d"}
    assert graph["core::c"] == {"core::a"}
    assert graph["core"] == set() and graph["core::d"] == set()
    assert module_cycles.cycles(graph) == [["core::a", "core::b", "core::c"]]
    (tmp_path / "core/c.rs").write_text("pub fn g() {}\n")
    assert module_cycles.cycles(graph_of(tmp_path)) == []
