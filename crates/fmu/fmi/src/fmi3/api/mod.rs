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

mod clocks;
mod co_simulation;
mod common;
mod dependencies;
mod derivatives;
mod fmu_state;
mod intermediate_step;
mod model_exchange;
mod step;
mod structural;
mod unsupported;
mod values;

pub use clocks::*;
pub use co_simulation::*;
pub use common::*;
pub use dependencies::*;
pub use derivatives::*;
pub use fmu_state::*;
pub use model_exchange::*;
pub use step::StepResult;
pub use structural::*;
pub use unsupported::*;
pub use values::*;

use crate::ffi::{input_slice, output_ref, output_slice};

use super::instance::Instance;
use super::mode::Call;
use super::types::{Fmi3Instance, Fmi3Status};
use crate::core::entry;
use crate::core::model::Model;

/// [`entry::with_instance`] for FMI 3.0: runs `body` on the instance behind `c` after
/// checking that `call` is legal in its state; errors become fmi3Error, panics fmi3Fatal.
unsafe fn with_instance<M: Model>(
    c: Fmi3Instance,
    function: &str,
    call: Call,
    body: impl FnOnce(&mut Instance<M>) -> Result<Fmi3Status, String>,
) -> Fmi3Status {
    unsafe { entry::with_instance(c, function, call, body) }
}
