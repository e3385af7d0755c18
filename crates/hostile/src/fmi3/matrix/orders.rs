//! Illegal call orders: from each state of the FMI 3.0 state machines, every call
//! the standard does not allow there (the table in `calls`), including the other
//! interface's functions. Expected: fmi3Error and a log line saying the call
//! sequence is illegal (FMI 3.0 sections 3.3 and 4.3), and the instance recovers
//! with fmi3Reset. Also the functions of capabilities the models lack, in every
//! state: fmi3Error with a log line naming the function.

use super::calls::{calls, unsupported};
use super::{Case, with_args};
use crate::Loaded;
use crate::fmi3::host::{Interface3, State3};
use crate::matrix::Expect;

const WHY: &str = "call not allowed in this state by the FMI 3.0 state machines (3.3 ME, 4.3 CS): fmi3Error and a log line; fmi3Reset recovers (2.3.1)";
const WHY_LACKING: &str = "function of a capability the model lacks (variable type, clocks, structural parameters, Scheduled Execution): fmi3Error and a log line naming the function in every state";

/// StepDiscarded is reached with a discarded step, which needs a force input.
pub fn reachable(loaded: &Loaded, m: usize, interface: Interface3, state: State3) -> bool {
    state.exists_for(interface)
        && (state != State3::StepDiscarded
            || loaded.fmus3[m]
                .description
                .variables
                .iter()
                .any(|v| v.name == "actuatorForce"))
}

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    for interface in Interface3::ALL {
        for state in State3::ALL {
            if !reachable(loaded, m, interface, state) {
                continue;
            }
            for call in calls() {
                if (call.legal)(interface, state) {
                    continue;
                }
                let invoke = call.invoke;
                cases.push(Case {
                    class: "fmi3 illegal call order",
                    model: m,
                    interface: Some(interface.short()),
                    name: format!("{} in {state:?}", call.name),
                    expect: Expect::error("illegal call sequence"),
                    why: WHY,
                    probe: Box::new(move |l| {
                        with_args(l, m, interface, state, |inst, a| unsafe {
                            invoke(inst.binary, inst.c, a)
                        })
                    }),
                });
            }
            for (name, invoke) in unsupported() {
                cases.push(Case {
                    class: "fmi3 lacking capability",
                    model: m,
                    interface: Some(interface.short()),
                    name: format!("{name} in {state:?}"),
                    expect: Expect::error(name),
                    why: WHY_LACKING,
                    probe: Box::new(move |l| {
                        with_args(l, m, interface, state, |inst, a| unsafe {
                            invoke(inst.binary, inst.c, a)
                        })
                    }),
                });
            }
        }
    }
    cases
}
