//! Illegal call orders: from each state of the FMI 2.0 state machines, every call
//! the standard does not allow there (the tables in `calls`). Expected: fmi2Error
//! and a log line saying the call sequence is illegal (FMI 2.0 sections 3.2.3 and
//! 4.2.4; calling a function of the other interface is included).

use super::calls::calls;
use super::{Case, Expect, with_args};
use crate::Loaded;
use crate::host::{Interface, State};

const WHY: &str = "call not allowed in this state by the FMI 2.0 state tables (3.2.3 ME, 4.2.4 CS): fmi2Error and a log line";

/// StepFailed is reached with a discarded step, which needs a force input.
fn reachable(loaded: &Loaded, m: usize, state: State) -> bool {
    state != State::StepFailed
        || loaded.fmus[m]
            .description
            .variables
            .iter()
            .any(|v| v.name == "actuatorForce[1]")
}

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    for interface in Interface::BOTH {
        for state in State::ALL {
            if !state.exists_for(interface) || !reachable(loaded, m, state) {
                continue;
            }
            for call in calls() {
                if (call.legal)(interface, state) {
                    continue;
                }
                let invoke = call.invoke;
                cases.push(Case {
                    class: "illegal call order",
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
        }
    }
    cases
}
