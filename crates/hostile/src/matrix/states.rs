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

use super::bad_states::{self, BadStateClass};
use super::serialized::{deserialize, reference, reference_state};
use super::{Case, Expect, Observed};
use crate::Loaded;
use crate::binary::{OK, status_name};
use crate::host::{Instance, Interface};
use std::ffi::c_char;

const WHY_BAD: &str = "FMU state not issued by this FMU instance or already freed: undefined in FMI 2.0; fmi2Error and a log line after a tag/registry check (issue 12 item 4)";
const BAD: BadStateClass = BadStateClass {
    class: "bad FMU state",
    why: WHY_BAD,
    seed: 0xbad,
};
const WHY_CROSS: &str = "issue 12 item 6: the state of a ME instance restores a CS instance of the same FMU (and back); project choice: accepted, outputs bit for bit";

type Use = bad_states::Use<Interface>;

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
    let mut cases = bad_states::cases::<Interface>(m, &BAD, &uses());
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
