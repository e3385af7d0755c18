//! FMU states the FMU never issued: a zeroed and a random block owned by the
//! importer, a state already freed, another FMU's state and the instance handle
//! itself, passed to every function that takes a state (`seam::Tables::state_uses`).
//! Both standards leave this undefined; the project checks a tag and a registry of
//! live states and answers an error with a log line (issue 12 item 4), and the
//! instance stays usable as its standard requires
//! (`StandardInterface::usable_after`).
//!
//! Also issue 12 item 6: the serialized state of each interface restores an
//! instance of each other interface of the same FMU (the model state is the same
//! for all: time, parameters, inputs, continuous states), so the project accepts
//! it: OK and the outputs of the other instance, bit for bit.

use super::seam::{Standard, Use};
use super::serialized::{reference, restore};
use super::{Case, Expect, Observed};
use crate::Loaded;
use crate::host::{Probed, take};
use std::ffi::c_void;

#[derive(Clone, Copy, Debug)]
enum BadState {
    ZeroedBlock,
    RandomBlock,
    Freed,
    OtherFmuState,
    InstanceHandle,
}

const BAD_STATES: [BadState; 5] = [
    BadState::ZeroedBlock,
    BadState::RandomBlock,
    BadState::Freed,
    BadState::OtherFmuState,
    BadState::InstanceHandle,
];

/// A block of 1024 bytes from calloc, random when `seed` is given.
fn block(seed: Option<u64>) -> *mut u8 {
    // SAFETY: calloc of a fixed size; filled within bounds.
    let p = unsafe { libc::calloc(1, 1024) } as *mut u8;
    if let Some(seed) = seed {
        let mut rng = crate::rng::SplitMix64::new(seed);
        (0..1024).for_each(|i| unsafe { *p.add(i) = rng.next_u64() as u8 });
    }
    p
}

fn probe<I: Standard>(
    l: &Loaded,
    m: usize,
    interface: I,
    (bad, seed): (BadState, u64),
    use_it: Use<I>,
) -> Observed {
    let inst = interface.instance(l, m);
    if let Err(e) = I::reach(&inst, I::INITIALIZATION_MODE) {
        return Observed::broken(e);
    }
    let other = interface.instance(l, (m + 1) % crate::fmu::models().len());
    let mut owned_block = None;
    let state = match bad {
        BadState::ZeroedBlock | BadState::RandomBlock => {
            let p = block(matches!(bad, BadState::RandomBlock).then_some(seed));
            owned_block = Some(p);
            p as *mut c_void
        }
        BadState::Freed => {
            let (_, s) = inst.new_state();
            inst.release_state(s);
            s
        }
        BadState::OtherFmuState => other.new_state().1,
        BadState::InstanceHandle => I::raw(&inst).1.into(),
    };
    take(inst.log());
    let status = use_it(&inst, state);
    let log = take(inst.log());
    if let Some(p) = owned_block {
        // SAFETY: our block; a crash here means the FMU freed it.
        unsafe { libc::free(p as *mut c_void) };
    }
    if matches!(bad, BadState::OtherFmuState) {
        other.release_state(state);
    }
    if let Err(e) = I::usable_after(&inst, status) {
        return Observed::broken(e);
    }
    Observed::of(status, log)
}

/// Every bad state passed to every function that takes a state, on every
/// interface.
fn bad_state_cases<I: Standard>(m: usize) -> Vec<Case> {
    let tables = I::tables();
    let seed = tables.state_seed;
    let mut cases = Vec::new();
    for &interface in I::INTERFACES {
        for bad in BAD_STATES {
            for (name, use_it) in (tables.state_uses)() {
                cases.push(Case::new(
                    ("bad FMU state", m, interface),
                    format!("{name}({bad:?})"),
                    (
                        Expect::error("not a live FMU state"),
                        tables.reasons.bad_state,
                    ),
                    move |l| probe(l, m, interface, (bad, seed), use_it),
                ));
            }
        }
    }
    cases
}

/// The serialized state of each interface restoring an instance of each other.
fn cross_interface_cases<I: Standard>(l: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    for &from in I::INTERFACES {
        let (bytes, outputs) = reference(l, m, from);
        for &to in I::INTERFACES {
            if to == from {
                continue;
            }
            let (bytes, outputs) = (bytes.clone(), outputs.clone());
            cases.push(Case::new(
                ("cross-interface state", m, to),
                format!(
                    "state serialized by a {} instance in {:?}",
                    from.short(),
                    from.reference_state()
                ),
                (Expect::ok(), I::tables().reasons.cross_interface),
                move |l| restore(l, m, to, &bytes, &outputs),
            ));
        }
    }
    cases
}

pub fn cases<I: Standard>(l: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = bad_state_cases::<I>(m);
    cases.extend(cross_interface_cases::<I>(l, m));
    cases
}
