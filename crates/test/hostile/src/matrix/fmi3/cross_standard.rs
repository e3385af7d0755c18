//! A class only FMI 3.0 has: the live FMU state of an FMI 2.0 instance of the
//! same FMU, in the same loaded binary, set into an FMI 3.0 instance. Accepted
//! like one of another instance (the model state is the same; project choice,
//! fmus/pid/tests/handles.rs); the outputs are then the FMI 2.0 instance's, bit
//! for bit. Also the hook of the bad-handle class that passes a live FMI 2.0
//! instance of the same FMU to the FMI 3.0 functions (`with_fmi2_instance`).

use crate::Loaded;
use crate::binary::{Binary, OK, Status};
use crate::fmi3::host::{Instance, Interface3};
use crate::host::{Instance as Instance2, Interface};
use crate::matrix::{Case, Expect, Observed};
use std::ffi::c_void;

const WHY_FMI2: &str = "live FMU state of an FMI 2.0 instance of the same FMU: accepted like one of another instance (project choice, fmus/pid/tests/handles.rs); outputs those of the FMI 2.0 instance, bit for bit";

/// Runs `call` with a live FMI 2.0 instance of model `m` opened from the FMI 3.0
/// archive's binary (same path: same handle), then checks that it still answers.
pub fn with_fmi2_instance(
    l: &Loaded,
    m: usize,
    interface: Interface3,
    call: &mut dyn FnMut(*mut c_void) -> Status,
) -> Result<Status, String> {
    let fmi2 = Binary::open(&l.fmus3[m].library)?;
    let fmi2_interface = if interface.is_me() {
        Interface::ModelExchange
    } else {
        Interface::CoSimulation
    };
    let fmi2_instance = Instance2::new(&fmi2, &l.fmus[m].description, fmi2_interface);
    let status = call(fmi2_instance.c);
    fmi2_instance
        .reach(crate::host::State::InitializationMode)
        .map_err(|e| format!("the FMI 2.0 instance no longer answers: {e}"))?;
    Ok(status)
}

/// An FMI 2.0 CS instance of model `m` in the FMU's own binary, one step taken;
/// its state set into an FMI 3.0 instance; outputs compared by variable name
/// (FMI 2.0 names elements "theta[1]", FMI 3.0 reads the array "theta").
fn fmi2_state(l: &Loaded, m: usize, interface: Interface3) -> Observed {
    let fmi2 = match Binary::open(&l.fmus3[m].library) {
        Ok(b) => b,
        Err(e) => return Observed::broken(e),
    };
    let d2 = &l.fmus[m].description;
    let source = Instance2::new(&fmi2, d2, Interface::CoSimulation);
    if let Err(e) = source.reach(crate::host::State::StepComplete) {
        return Observed::broken(e);
    }
    if source.do_step(0.0, 1e-3) != OK {
        return Observed::broken(format!("fmi2DoStep: {}", source.take_log()));
    }
    let (_, state) = source.get_state();
    let inst = Instance::new(&l.binaries3[m], &l.fmus3[m].description, interface);
    if let Err(e) = inst.reach(crate::fmi3::host::State3::InitializationMode) {
        return Observed::broken(e);
    }
    // SAFETY: a live state of the same model (the probe's point).
    let status = unsafe { (inst.binary.set_fmu_state)(inst.c, state) };
    let log = inst.take_log();
    source.free_state(state);
    if status != OK {
        return Observed::of(status, log);
    }
    let mut compared = 0;
    for v in inst.description.of_type(crate::description::VarType::Real) {
        if v.causality == "independent" {
            continue;
        }
        let (s, x) = inst.get_float64(&[v.vr]);
        if s != OK {
            return Observed::broken(format!(
                "fmi3GetFloat64({}) after the restore: {}",
                v.name,
                crate::binary::status_name(s)
            ));
        }
        for (k, value) in x.iter().enumerate() {
            let name = if v.size > 1 {
                format!("{}[{}]", v.name, k + 1)
            } else {
                v.name.clone()
            };
            let Some(v2) = d2.variables.iter().find(|w| w.name == name) else {
                continue;
            };
            let (_, y) = source.get_reals(&[v2.vr]);
            compared += 1;
            if value.to_bits() != y[0].to_bits() {
                return Observed::broken(format!(
                    "{name}: {value} after the restore, {} in the FMI 2.0 instance",
                    y[0]
                ));
            }
        }
    }
    if compared == 0 {
        return Observed::broken("no Float64 element matched an FMI 2.0 variable by name".into());
    }
    Observed::of(status, log)
}

pub fn cases(_: &Loaded, m: usize) -> Vec<Case> {
    Interface3::ALL
        .into_iter()
        .map(|interface| {
            Case::new(
                ("cross-standard state", m, interface),
                "fmi3SetFMUState(live state of an FMI 2.0 instance of this FMU)".into(),
                (Expect::ok(), WHY_FMI2),
                move |l| fmi2_state(l, m, interface),
            )
        })
        .collect()
}
