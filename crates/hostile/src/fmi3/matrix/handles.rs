//! Instance handles the FMU never issued (or no longer owns), passed to every FMI
//! 3.0 function that takes one: null, a zeroed and a random heap block owned by
//! the importer, a live FMI 3.0 instance of another FMU, an instance already freed,
//! and a live FMI 2.0 instance of the same FMU in the same loaded binary. FMI 3.0
//! leaves this undefined; the layer checks every handle against its registry of
//! live instances (keyed by standard) and answers fmi3Error. No log text is
//! required (there is no logger the FMU could trust). Afterwards the block is
//! intact, and the other instances still answer.

use super::calls::{Invoke, calls, unsupported};
use super::{Case, Observed};
use crate::Loaded;
use crate::binary::{Binary, OK, status_name};
use crate::fmi3::host::{Instance, Interface3};
use crate::host::{Instance as Instance2, Interface};
use crate::matrix::handles::{Scene, bad_handle_cases, block, call_with_bad_handle};

const WHY_NULL: &str = "null instance: undefined in FMI 3.0; fmi3Error (fmi3FreeInstance: ignored)";
const WHY_FOREIGN: &str = "handle not issued by this FMU's FMI 3.0 interface, or freed: undefined in FMI 3.0; refused with fmi3Error after a registry check (fmi3FreeInstance: ignored)";

#[derive(Clone, Copy, Debug)]
enum Handle {
    Null,
    ZeroedBlock,
    RandomBlock,
    OtherFmuInstance,
    FreedInstance,
    Fmi2InstanceOfThisFmu,
}

const HANDLES: [Handle; 6] = [
    Handle::Null,
    Handle::ZeroedBlock,
    Handle::RandomBlock,
    Handle::OtherFmuInstance,
    Handle::FreedInstance,
    Handle::Fmi2InstanceOfThisFmu,
];

fn probe(
    l: &Loaded,
    m: usize,
    interface: Interface3,
    handle: Handle,
    invoke: Option<Invoke>,
) -> Observed {
    let Scene {
        own,
        state,
        args,
        other,
    } = match Scene::new(l, m, interface) {
        Ok(scene) => scene,
        Err(e) => return Observed::broken(e),
    };
    // The FMI 2.0 view of the very binary `own` lives in (same path: same handle).
    let fmi2 = match Binary::open(&l.fmus3[m].library) {
        Ok(b) => b,
        Err(e) => return Observed::broken(e),
    };
    let fmi2_interface = if interface.is_me() {
        Interface::ModelExchange
    } else {
        Interface::CoSimulation
    };
    let fmi2_instance = Instance2::new(&fmi2, &l.fmus[m].description, fmi2_interface);
    let c = match handle {
        Handle::Null => std::ptr::null_mut(),
        Handle::ZeroedBlock => block(false),
        Handle::RandomBlock => block(true),
        Handle::OtherFmuInstance => other.c,
        Handle::FreedInstance => {
            let gone = Instance::new(&l.binaries3[m], &l.fmus3[m].description, interface);
            let c = gone.c;
            drop(gone);
            c
        }
        Handle::Fmi2InstanceOfThisFmu => fmi2_instance.c,
    };
    let owned = matches!(handle, Handle::ZeroedBlock | Handle::RandomBlock);
    // SAFETY: null, our block, or a live (or just freed) instance.
    let status = unsafe { call_with_bad_handle::<Interface3>((&own, &args), c, owned, invoke) };
    let (s, values) = other.get_float64(&[other.description.real_vrs()[1]]);
    if s != OK || values.iter().any(|v| !v.is_finite()) {
        return Observed::broken(format!(
            "the other FMU's instance no longer answers: {} ({})",
            status_name(s),
            other.take_log()
        ));
    }
    if let Err(e) = fmi2_instance.reach(crate::host::State::InitializationMode) {
        return Observed::broken(format!("the FMI 2.0 instance no longer answers: {e}"));
    }
    own.free_state(state);
    let log = format!("{} {}", own.take_log(), other.take_log());
    Observed::of(status, log)
}

pub fn cases(_: &Loaded, m: usize) -> Vec<Case> {
    bad_handle_cases::<Interface3, Handle>(
        m,
        ("fmi3 bad instance handle", "fmi3FreeInstance"),
        (&HANDLES, |h| {
            if matches!(h, Handle::Null) {
                WHY_NULL
            } else {
                WHY_FOREIGN
            }
        }),
        calls()
            .into_iter()
            .map(|c| (c.name, c.invoke))
            .chain(unsupported())
            .collect(),
        probe,
    )
}
