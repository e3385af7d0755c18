//! Illegal call orders: from each state of the FMI 2.0 state machines, every call
//! the standard does not allow there (the tables in `calls`). Expected: fmi2Error
//! and a log line saying the call sequence is illegal (FMI 2.0 sections 3.2.3 and
//! 4.2.4; calling a function of the other interface is included). The loop over
//! interfaces, states and calls serves both standards (`illegal_calls`).

use super::calls::calls;
use super::{Case, Expect, Probe, with_args};
use crate::Loaded;
use crate::host::Interface;
use crate::standard_interface::{Call, Invoke, StandardInterface};

const WHY: &str = "call not allowed in this state by the FMI 2.0 state tables (3.2.3 ME, 4.2.4 CS): fmi2Error and a log line";

/// Calls `f` with every interface of the standard and every state reachable with
/// it on model `m`.
pub fn each_reachable<I: StandardInterface>(
    loaded: &Loaded,
    m: usize,
    mut f: impl FnMut(I, I::State),
) {
    for &interface in I::INTERFACES {
        for &state in I::STATES {
            if interface.reachable(loaded, m, state) {
                f(interface, state);
            }
        }
    }
}

/// A probe that brings a fresh instance into `state` and makes one call with
/// well-formed arguments.
pub fn invoke_probe<I: StandardInterface>(
    m: usize,
    interface: I,
    state: I::State,
    invoke: Invoke<I>,
) -> Probe {
    Box::new(move |l| {
        with_args(l, m, interface, state, |inst, a| {
            let (binary, handle) = I::raw(inst);
            // SAFETY: a live instance of this binary and well-formed arguments.
            unsafe { invoke(binary, handle, a) }
        })
    })
}

/// One case per call of `calls` that the standard does not allow in `state`:
/// refused with an error and a log line saying the call sequence is illegal.
pub fn illegal_calls<I: StandardInterface>(
    m: usize,
    interface: I,
    state: I::State,
    calls: Vec<Call<I>>,
    (class, why): (&'static str, &'static str),
) -> Vec<Case> {
    calls
        .into_iter()
        .filter(|call| !(call.legal)(interface, state))
        .map(|call| Case {
            class,
            model: m,
            interface: Some(interface.short()),
            name: format!("{} in {state:?}", call.name),
            expect: Expect::error("illegal call sequence"),
            why,
            probe: invoke_probe(m, interface, state, call.invoke),
        })
        .collect()
}

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    each_reachable(loaded, m, |interface: Interface, state| {
        cases.extend(illegal_calls(
            m,
            interface,
            state,
            calls(),
            ("illegal call order", WHY),
        ));
    });
    cases
}
