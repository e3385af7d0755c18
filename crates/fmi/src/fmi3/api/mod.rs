//! Generic implementations of the FMI 3.0 functions, called by the `export_fmi3!`
//! macro from the FMU crate's `#[unsafe(no_mangle)]` symbols.
//!
//! Every function here has the contract of its FMI 3.0 namesake: pointers are null or
//! valid for the lengths given, and an `Fmi3Instance` is null or was returned by an
//! instantiate function for the same model type and not yet freed. Within that
//! contract nothing can crash (and handles are looked up in the core's registry
//! before use, keyed by the FMI 3.0 instance type, so that an FMI 2.0 instance of the
//! same model is refused too): null pointers, bad value references, wrong types or
//! lengths, non-finite values and calls in the wrong state return fmi3Error with a log
//! line (and move the instance to the Error state, as the standard prescribes); a panic
//! is caught, logged and returns fmi3Fatal.
#![allow(clippy::missing_safety_doc)]

mod co_simulation;
mod common;
mod dependencies;
mod derivatives;
mod fmu_state;
mod model_exchange;
mod unsupported;
mod values;

pub use co_simulation::*;
pub use common::*;
pub use dependencies::*;
pub use derivatives::*;
pub use fmu_state::*;
pub use model_exchange::*;
pub use unsupported::*;
pub use values::*;

use crate::ffi::{check_finite, input_slice, output_ref, output_slice};

use super::instance::Instance;
use super::mode::{Call, Mode};
use super::types::{Fmi3Instance, Fmi3Status};
use crate::core::handles::{self, HandleKind};
use crate::core::model::Model;
use crate::ffi::panic_message;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Runs `body` on the instance behind `c` after checking that `call` is legal in its
/// state; turns errors into fmi3Error (+ Error state) and panics into fmi3Fatal
/// (+ Fatal state), both with a log line naming `function`.
unsafe fn with_instance<M: Model>(
    c: Fmi3Instance,
    function: &str,
    call: Call,
    body: impl FnOnce(&mut Instance<M>) -> Result<Fmi3Status, String>,
) -> Fmi3Status {
    // Not a live FMI 3.0 instance of this FMU (null, garbage, freed, another FMU's, or
    // an FMI 2.0 instance of the same model): no logger to report through.
    if !handles::is_live::<Instance<M>>(c as usize, HandleKind::Instance) {
        return Fmi3Status::Error;
    }
    let instance = c as *mut Instance<M>;
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: by the contract above, `c` points to a live Instance<M>.
        let inst = unsafe { &mut *instance };
        if !call.is_legal(inst.mode, inst.interface) {
            return Err(format!(
                "illegal call sequence: not allowed in state {:?} ({:?})",
                inst.mode, inst.interface
            ));
        }
        crate::core::logging::Log::debug(&inst.log, "logCalls", function);
        body(inst)
    }));
    // SAFETY: as above; the closure's borrow has ended.
    let inst = unsafe { &mut *instance };
    match outcome {
        Ok(Ok(status)) => status,
        Ok(Err(message)) => {
            inst.log
                .status(Fmi3Status::Error, &format!("{function}: {message}"));
            if inst.mode != Mode::Fatal {
                inst.mode = Mode::Error;
            }
            Fmi3Status::Error
        }
        Err(payload) => {
            let message = panic_message(payload.as_ref());
            inst.mode = Mode::Fatal;
            inst.log.status(
                Fmi3Status::Fatal,
                &format!("{function}: internal error (panic): {message}"),
            );
            Fmi3Status::Fatal
        }
    }
}
