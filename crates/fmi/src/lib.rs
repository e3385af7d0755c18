//! robofmu-fmi: the runtime FMI layer, with no robot code and nothing of packaging
//! (no zip, XML or serde: modelDescription.xml and the archive are written by
//! `robofmu-fmi-build`, the in-process test host lives in `robofmu-fmi-testing`).
//!
//! # Writing an FMU
//! Everything a model author needs is in the [`prelude`]:
//!
//! 1. describe the FMU once in a `static` [`ModelInfo`](prelude::ModelInfo) (names,
//!    instantiation token, default experiment, state and event-indicator counts,
//!    capabilities, log categories);
//! 2. declare the variables once, in a `static` slice of
//!    [`Declaration`](prelude::Declaration)s: scalars and arrays (`.array(n)`), each
//!    with its getter and setter (`fn` pointers taking the element index), causality,
//!    [`Variability`](prelude::Variability), unit, start, bounds and hooks (output
//!    derivatives, input-derivative slots); value references are pinned with `.at(vr)`
//!    or assigned by the layer (see [`core::declare`]);
//! 3. implement [`Model`](prelude::Model) for the model type: `declarations()` returns
//!    that slice; the step returns a [`StepOutcome`](prelude::StepOutcome), Model
//!    Exchange events an [`EventUpdate`](prelude::EventUpdate); partial derivatives
//!    name their variables as [`Element`](prelude::Element)s; messages go to the
//!    [`Log`](prelude::Log) in one of the model's [`LogCategory`](prelude::LogCategory)s;
//! 4. end the crate with [`export_fmu!`]`(Type);` it exports the FMI 2.0 and the
//!    FMI 3.0 C functions from the same cdylib.
//!
//! The modules below are the layer itself: [`core`] (the version-neutral core: model
//! trait, variable table, instance, FMU states, handles, the entry wrapper),
//! [`fmi2`] and [`fmi3`] (each standard's C types, state machine and C functions) and
//! [`ffi`] (checked reads of the host's pointers).

pub mod core;
pub mod ffi;
pub mod fmi2;
pub mod fmi3;

/// The names a model author uses: `use robofmu_fmi::prelude::*;`.
pub mod prelude {
    pub use crate::core::{
        Declaration, DefaultExperiment, Element, EventUpdate, Log, LogCategory, Model, ModelInfo,
        OutputDerivativeError, StepOutcome, Variability, Variable,
    };
    pub use crate::export_fmu;
}

/// Exports one model as an FMU of both standards: the FMI 2.0 functions
/// ([`export_fmi2!`]) and the FMI 3.0 functions ([`export_fmi3!`]) from one cdylib.
/// Call it once per FMU crate, at the crate root: `robofmu_fmi::export_fmu!(Planner);`.
#[macro_export]
macro_rules! export_fmu {
    ($model:ty) => {
        $crate::export_fmi2!($model);
        $crate::export_fmi3!($model);
    };
}
