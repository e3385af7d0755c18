//! The bad-input matrix for the FMI 3.0 interface of the packaged FMUs: the same
//! cases, judge and report as the FMI 2.0 matrix (`crate::matrix`), with the FMI
//! 3.0 functions, states and arguments. Besides the status and the log line, every
//! case in which a live instance refuses a call (fmi3Error: the instance is in the
//! Error state, FMI 3.0 section 2.3.1) checks that it is usable afterwards:
//! fmi3Reset, initialization and a read of every Float64 succeed with finite values.

pub mod arrays;
pub mod calls;
pub mod handles;
pub mod instantiate;
pub mod orders;
pub mod pointers;
pub mod pose;
pub mod serialized;
pub mod states;
pub mod values;
pub mod variability;

use crate::Loaded;
use crate::binary::{ERROR, Status};
use crate::fmi3::host::{Instance, Interface3, State3};
use crate::host::unlogged;
use crate::matrix::{Case, Observed};

/// A fresh instance of model `m` brought into `state`, then `call` on it; after a
/// refusal, the instance must recover with fmi3Reset.
pub fn on_instance(
    loaded: &Loaded,
    m: usize,
    interface: Interface3,
    state: State3,
    call: impl Fn(&Instance) -> Status,
) -> Observed {
    let inst = Instance::new(
        &loaded.binaries3[m],
        &loaded.fmus3[m].description,
        interface,
    );
    if let Err(e) = inst.reach(state) {
        return Observed::broken(format!("could not reach {state:?}: {e}"));
    }
    let status = call(&inst);
    let log = inst.take_log();
    if status == ERROR
        && let Err(e) = inst.recovers()
    {
        return Observed::broken(format!("not usable after the refusal: {e}"));
    }
    Observed::of(status, log)
}

/// Like `on_instance`, with well-formed arguments that include a valid FMU state
/// of the instance (taken after reaching `state`, freed after the call).
pub fn with_args(
    loaded: &Loaded,
    m: usize,
    interface: Interface3,
    state: State3,
    call: impl Fn(&Instance, &calls::Args) -> Status,
) -> Observed {
    on_instance(loaded, m, interface, state, |inst| {
        let (_, fmu_state) = unlogged(inst, || inst.get_state());
        let status = call(inst, &calls::Args::new(inst.description, fmu_state));
        unlogged(inst, || inst.free_state(fmu_state));
        status
    })
}

/// Every FMI 3.0 case of the matrix.
pub fn all_cases(loaded: &Loaded) -> Vec<Case> {
    let mut cases = Vec::new();
    for m in 0..loaded.fmus3.len() {
        cases.extend(pointers::cases(loaded, m));
        cases.extend(arrays::cases(loaded, m));
        cases.extend(values::cases(loaded, m));
        cases.extend(variability::cases(loaded, m));
        cases.extend(serialized::cases(loaded, m));
        cases.extend(orders::cases(loaded, m));
        cases.extend(handles::cases(loaded, m));
        cases.extend(states::cases(loaded, m));
        cases.extend(pose::cases(loaded, m));
        cases.extend(instantiate::cases(loaded, m));
    }
    cases
}
