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
use super::mode::Call;
use super::types::{Fmi2Component, Fmi2Status};
use crate::core::entry;
use crate::core::model::Model;
use crate::ffi::{input_slice, output_ref, output_slice};

/// [`entry::with_instance`] for FMI 2.0: runs `body` on the instance behind `c` after
/// checking that `call` is legal in its mode; errors become fmi2Error, panics fmi2Fatal.
unsafe fn with_instance<M: Model>(
    c: Fmi2Component,
    function: &str,
    call: Call,
    body: impl FnOnce(&mut Instance<M>) -> Result<Fmi2Status, String>,
) -> Fmi2Status {
    unsafe { entry::with_instance(c, function, call, body) }
}
