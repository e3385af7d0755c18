//! What the closed-loop test programs share.

use robofmu::closed_loop::{LoopSpec, parse_loop_scenario};
use std::path::Path;

/// A scenario of scenarios/ in the expanded form the harness resolves it to (`cosim
/// check --expanded`, committed in tests/scenarios/expanded/ and checked against the
/// harness by tests/python/test_expanded.py).
pub fn scenario(name: &str) -> LoopSpec {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/scenarios/expanded")
        .join(name);
    parse_loop_scenario(&std::fs::read_to_string(path).unwrap()).unwrap()
}
