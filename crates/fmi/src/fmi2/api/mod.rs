//! Generic implementations of the 44 FMI 2.0 functions, one per function, called by
//! the `export_fmi2!` macro from the FMU crate's `#[unsafe(no_mangle)]` symbols.
//!
//! Every function here has the contract of its FMI 2.0 namesake: pointers are null or
//! valid for the lengths given. Instance and FMU-state handles are looked up in the
//! registry of live handles (`core::handles`) before they are dereferenced, so a
//! garbage, freed or foreign handle returns fmi2Error. Within that contract nothing
//! can crash: null pointers, bad value references, wrong types, non-finite
//! values and calls in the wrong mode return fmi2Error with a log line (and move the
//! instance to the Error mode, as the standard prescribes); a panic is caught, logged
//! and returns fmi2Fatal.
#![allow(clippy::missing_safety_doc)]

mod co_simulation;
mod common;
mod directional;
mod fmu_state;
mod model_exchange;
mod values;

pub use co_simulation::*;
pub use common::*;
pub use directional::*;
pub use fmu_state::*;
pub use model_exchange::*;
pub use values::*;

use super::instance::Instance;
use super::mode::{Call, Mode};
use super::types::{Fmi2Component, Fmi2Status};
use crate::core::handles::{self, HandleKind};
use crate::core::model::Model;
use crate::ffi::{check_finite, input_slice, output_ref, output_slice, panic_message};
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Runs `body` on the instance behind `c` after checking that `call` is legal in its
/// mode; turns errors into fmi2Error (+ Error mode) and panics into fmi2Fatal
/// (+ Fatal mode), both with a log line naming `function`.
unsafe fn with_instance<M: Model>(
    c: Fmi2Component,
    function: &str,
    call: Call,
    body: impl FnOnce(&mut Instance<M>) -> Result<Fmi2Status, String>,
) -> Fmi2Status {
    // Not an instance of this FMU that is still live (null, garbage, freed, another
    // FMU's): there is no logger to report through, only the status.
    if !handles::is_live::<M>(c as usize, HandleKind::Instance) {
        return Fmi2Status::Error;
    }
    let instance = c as *mut Instance<M>;
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: by the contract above, `c` points to a live Instance<M>.
        let inst = unsafe { &mut *instance };
        if !call.is_legal(inst.mode, inst.interface) {
            return Err(format!(
                "illegal call sequence: not allowed in mode {:?} ({:?})",
                inst.mode, inst.interface
            ));
        }
        inst.log.debug("logCalls", function);
        body(inst)
    }));
    // SAFETY: as above; the closure's borrow has ended.
    let inst = unsafe { &mut *instance };
    match outcome {
        Ok(Ok(status)) => status,
        Ok(Err(message)) => {
            inst.log
                .status(Fmi2Status::Error, &format!("{function}: {message}"));
            if inst.mode != Mode::Fatal {
                inst.mode = Mode::Error;
            }
            Fmi2Status::Error
        }
        Err(payload) => {
            let message = panic_message(payload.as_ref());
            inst.mode = Mode::Fatal;
            inst.log.status(
                Fmi2Status::Fatal,
                &format!("{function}: internal error (panic): {message}"),
            );
            Fmi2Status::Fatal
        }
    }
}
