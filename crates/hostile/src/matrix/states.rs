//! FMU states the instance never issued: a zeroed and a random block owned by the
//! importer, a state already freed, another FMU's state and the instance handle
//! itself, passed to every function that takes a state. FMI 2.0 leaves this
//! undefined; issue 12 item 4 asks for a tag in every state (and a registry of live
//! states to reject freed ones), answered with fmi2Error and a log line.
//!
//! Also item 6: a Co-Simulation instance given the state of a Model Exchange
//! instance of the same FMU, and back. The model state is the same for both
//! interfaces (time, parameters, inputs, continuous states), so the project accepts
//! it: fmi2OK and the outputs of the other instance, bit for bit.

use super::serialized::{deserialize, reference, reference_state};
use super::{Case, Expect, Observed};
use crate::Loaded;
use crate::binary::{FmuState, OK, Status, status_name};
use crate::host::{Instance, Interface, State};
use std::ffi::c_char;

const WHY_BAD: &str = "FMU state not issued by this FMU instance or already freed: undefined in FMI 2.0; fmi2Error and a log line after a tag/registry check (issue 12 item 4)";
const WHY_CROSS: &str = "issue 12 item 6: the state of a ME instance restores a CS instance of the same FMU (and back); project choice: accepted, outputs bit for bit";

#[derive(Clone, Copy, Debug)]
enum BadState {
    ZeroedBlock,
    RandomBlock,
    Freed,
    OtherFmuState,
    InstanceHandle,
}

type Use = fn(&Instance, FmuState) -> Status;

fn uses() -> [(&'static str, Use); 5] {
    [
        ("fmi2SetFMUstate", |i, s| unsafe {
            (i.binary.set_fmu_state)(i.c, s)
        }),
        ("fmi2FreeFMUstate", |i, s| {
            let mut slot = s;
            unsafe { (i.binary.free_fmu_state)(i.c, &mut slot) }
        }),
        ("fmi2SerializedFMUstateSize", |i, s| unsafe {
            (i.binary.serialized_size)(i.c, s, &mut 0)
        }),
        ("fmi2SerializeFMUstate", |i, s| unsafe {
            let mut bytes = vec![0 as c_char; 256];
            (i.binary.serialize)(i.c, s, bytes.as_mut_ptr(), bytes.len())
        }),
        ("fmi2GetFMUstate(slot holding it)", |i, s| {
            let mut slot = s;
            unsafe { (i.binary.get_fmu_state)(i.c, &mut slot) }
        }),
    ]
}

fn probe(l: &Loaded, m: usize, interface: Interface, bad: BadState, use_it: Use) -> Observed {
    let inst = Instance::new(&l.binaries[m], &l.fmus[m].description, interface);
    if let Err(e) = inst.reach(State::InitializationMode) {
        return Observed::broken(e);
    }
    let other_model = (m + 1) % l.fmus.len();
    let other = Instance::new(
        &l.binaries[other_model],
        &l.fmus[other_model].description,
        interface,
    );
    let mut owned_block = None;
    let state: FmuState = match bad {
        BadState::ZeroedBlock | BadState::RandomBlock => {
            // SAFETY: calloc of a fixed size; filled within bounds.
            let p = unsafe { libc::calloc(1, 1024) } as *mut u8;
            if matches!(bad, BadState::RandomBlock) {
                let mut rng = crate::rng::SplitMix64::new(0xbad);
                (0..1024).for_each(|i| unsafe { *p.add(i) = rng.next_u64() as u8 });
            }
            owned_block = Some(p);
            p as FmuState
        }
        BadState::Freed => {
            let (_, s) = inst.get_state();
            inst.free_state(s);
            s
        }
        BadState::OtherFmuState => other.get_state().1,
        BadState::InstanceHandle => inst.c,
    };
    inst.take_log();
    let status = use_it(&inst, state);
    let log = inst.take_log();
    if let Some(p) = owned_block {
        // SAFETY: our block; a crash here means the FMU freed it.
        unsafe { libc::free(p as *mut libc::c_void) };
    }
    if matches!(bad, BadState::OtherFmuState) {
        other.free_state(state);
    }
    let (s, x) = inst.get_reals(&inst.description.real_vrs());
    if status == crate::binary::ERROR && s == OK && x.iter().any(|v| !v.is_finite()) {
        return Observed::broken("outputs not finite after the refusal".into());
    }
    Observed::of(status, log)
}

fn cross_case(l: &Loaded, m: usize, from: Interface, to: Interface) -> Case {
    let (bytes, outputs) = reference(l, m, from);
    Case {
        class: "cross-interface state",
        model: m,
        interface: Some(to.short()),
        name: format!("state serialized by a {} instance", from.short()),
        expect: Expect::ok(),
        why: WHY_CROSS,
        probe: Box::new(move |l| {
            let inst = Instance::new(&l.binaries[m], &l.fmus[m].description, to);
            if let Err(e) = inst.reach(reference_state(to)) {
                return Observed::broken(e);
            }
            let (s, state) = deserialize(&inst, &bytes);
            if s != OK {
                return Observed::of(s, inst.take_log());
            }
            // SAFETY: a state this instance deserialized.
            let s = unsafe { (inst.binary.set_fmu_state)(inst.c, state) };
            inst.free_state(state);
            let (g, x) = inst.get_reals(&inst.description.real_vrs());
            let same = x.iter().map(|v| v.to_bits()).eq(outputs.iter().copied());
            if s == OK && (g != OK || !same) {
                return Observed::broken(format!("restored outputs differ ({})", status_name(g)));
            }
            Observed::of(s, inst.take_log())
        }),
    }
}

pub fn cases(l: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    for interface in Interface::BOTH {
        for bad in [
            BadState::ZeroedBlock,
            BadState::RandomBlock,
            BadState::Freed,
            BadState::OtherFmuState,
            BadState::InstanceHandle,
        ] {
            for (name, use_it) in uses() {
                cases.push(Case {
                    class: "bad FMU state",
                    model: m,
                    interface: Some(interface.short()),
                    name: format!("{name}({bad:?})"),
                    expect: Expect::error("not a live FMU state"),
                    why: WHY_BAD,
                    probe: Box::new(move |l| probe(l, m, interface, bad, use_it)),
                });
            }
        }
    }
    cases.push(cross_case(
        l,
        m,
        Interface::ModelExchange,
        Interface::CoSimulation,
    ));
    cases.push(cross_case(
        l,
        m,
        Interface::CoSimulation,
        Interface::ModelExchange,
    ));
    cases
}
