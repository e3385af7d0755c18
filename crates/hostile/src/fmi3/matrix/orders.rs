//! Illegal call orders: from each state of the FMI 3.0 state machines, every call
//! the standard does not allow there (the table in `calls`), including the other
//! interface's functions. Expected: fmi3Error and a log line saying the call
//! sequence is illegal (FMI 3.0 sections 3.3 and 4.3), and the instance recovers
//! with fmi3Reset. Also the functions of capabilities the models lack, in every
//! state: fmi3Error with a log line naming the function.

use super::Case;
use super::calls::{calls, unsupported};
use crate::Loaded;
use crate::fmi3::host::Interface3;
use crate::matrix::Expect;
use crate::matrix::orders::{each_reachable, illegal_calls, invoke_probe};

const WHY: &str = "call not allowed in this state by the FMI 3.0 state machines (3.3 ME, 4.3 CS): fmi3Error and a log line; fmi3Reset recovers (2.3.1)";
const WHY_LACKING: &str = "function of a capability the model lacks (variable type, clocks, structural parameters, Scheduled Execution): fmi3Error and a log line naming the function in every state";

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    each_reachable(loaded, m, |interface: Interface3, state| {
        cases.extend(illegal_calls(
            m,
            interface,
            state,
            calls(),
            ("fmi3 illegal call order", WHY),
        ));
        for (name, invoke) in unsupported() {
            cases.push(Case {
                class: "fmi3 lacking capability",
                model: m,
                interface: Some(interface.short()),
                name: format!("{name} in {state:?}"),
                expect: Expect::error(name),
                why: WHY_LACKING,
                probe: invoke_probe(m, interface, state, invoke),
            });
        }
    });
    cases
}
