//! FMU states the FMU never issued, for both standards: a zeroed and a random
//! block owned by the importer, a state already freed, another FMU's state and the
//! instance handle itself, each passed to every function that takes a state
//! (the functions are per standard, in `matrix::states` and
//! `fmi3::matrix::states`). Both standards leave this undefined; the project
//! answers it with an error and a log line, and the instance stays usable as its
//! standard requires (`StandardInterface::usable_after`).

use super::{Case, Expect, Observed};
use crate::Loaded;
use crate::binary::Status;
use crate::host::{Probed, take};
use crate::standard_interface::StandardInterface;
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

/// A function that takes an FMU state, called on an instance.
pub type Use<I> = fn(&<I as StandardInterface>::Instance<'_>, *mut c_void) -> Status;

/// What the cases of one standard share: class, reason and the random block's seed.
pub struct BadStateClass {
    pub class: &'static str,
    pub why: &'static str,
    pub seed: u64,
}

/// Every bad state passed to every function of `uses`, on every interface.
pub fn cases<I: StandardInterface>(
    m: usize,
    kind: &BadStateClass,
    uses: &[(&'static str, Use<I>)],
) -> Vec<Case> {
    let mut cases = Vec::new();
    for &interface in I::INTERFACES {
        for bad in BAD_STATES {
            for &(name, use_it) in uses {
                let seed = kind.seed;
                cases.push(Case {
                    class: kind.class,
                    model: m,
                    interface: Some(interface.short()),
                    name: format!("{name}({bad:?})"),
                    expect: Expect::error("not a live FMU state"),
                    why: kind.why,
                    probe: Box::new(move |l| probe(l, m, interface, (bad, seed), use_it)),
                });
            }
        }
    }
    cases
}

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

fn probe<I: StandardInterface>(
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
