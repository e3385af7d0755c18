//! Illegal call orders: from each state of the standard's state machines, every
//! call the standard does not allow there (the call table of `seam::Tables`,
//! calling a function of the other interface included). Expected: an error and a
//! log line saying the call sequence is illegal, and the instance usable as its
//! standard requires. Also the functions of capabilities the models lack, in
//! every state: an error with a log line naming the function.

use super::seam::Standard;
use super::{Case, Expect, Observed, with_args};
use crate::Loaded;
use crate::standard_interface::{Call, Invoke, StandardInterface};

/// Calls `f` with every interface of the standard and every state reachable with
/// it on model `m`.
fn each_reachable<I: StandardInterface>(loaded: &Loaded, m: usize, mut f: impl FnMut(I, I::State)) {
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
) -> impl Fn(&Loaded) -> Observed + 'static {
    move |l| {
        with_args(l, m, interface, state, |inst, a| {
            let (binary, handle) = I::raw(inst);
            // SAFETY: a live instance of this binary and well-formed arguments.
            unsafe { invoke(binary, handle, a) }
        })
    }
}

/// One case per call of `calls` that the standard does not allow in `state`:
/// refused with an error and a log line saying the call sequence is illegal.
pub fn illegal_calls<I>(
    m: usize,
    interface: I,
    state: I::State,
    calls: Vec<Call<I>>,
    (class, why): (&'static str, &'static str),
) -> Vec<Case>
where
    I: Standard,
{
    calls
        .into_iter()
        .filter(|call| !(call.legal)(interface, state))
        .map(|call| {
            Case::new(
                (class, m, interface),
                format!("{} in {state:?}", call.name),
                (Expect::error("illegal call sequence"), why),
                invoke_probe(m, interface, state, call.invoke),
            )
        })
        .collect()
}

pub fn cases<I: Standard>(loaded: &Loaded, m: usize) -> Vec<Case> {
    let tables = I::tables();
    // A model with structural parameters serves Configuration Mode and UInt64
    // (FMI 3.0): the class `structural` tests them; they lack for the others.
    let serves = |name: &str| {
        !I::description(loaded, m).structural.is_empty()
            && (name.contains("ConfigurationMode") || name.contains("UInt64"))
    };
    let mut cases = Vec::new();
    each_reachable(loaded, m, |interface: I, state| {
        cases.extend(illegal_calls(
            m,
            interface,
            state,
            (tables.calls)(),
            ("illegal call order", tables.reasons.illegal_order),
        ));
        for (name, invoke) in (tables.lacking)() {
            if serves(name) {
                continue;
            }
            cases.push(Case::new(
                ("lacking capability", m, interface),
                format!("{name} in {state:?}"),
                (Expect::error(name), tables.reasons.lacking),
                invoke_probe(m, interface, state, invoke),
            ));
        }
    });
    cases
}
