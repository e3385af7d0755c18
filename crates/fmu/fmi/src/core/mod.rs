//! The version-neutral core of the FMI layer: what a model implements and what every
//! front-end (FMI 2.0, FMI 3.0) shares.
//!
//! A model implements [`Model`] with a table of [`Variable`]s in safe Rust, without any
//! FFI or front-end type; [`Instance`] holds one model with its time and stop time,
//! [`Snapshot`] is an FMU state ([`fmu_states`] keeps it behind the host's pointer) and
//! [`serialize`] its checked byte format; [`handles`] registers the live instances and
//! states so that every handle is checked before use.
//!
//! A front-end is a [`frontend::Frontend`] (its status codes, state machine, logger
//! callback and extra instance state); an instance of either standard is one type,
//! [`frontend::FmuInstance`]`<F, M>`; [`entry`] wraps every C entry point
//! of both standards (handle, mode, logCalls, errors and panics) and holds the bodies
//! they share, with [`fmu_state_calls`] and [`model_exchange_calls`].

pub mod attributes;
pub mod callback;
pub mod clocks;
pub mod declare;
pub mod directional;
pub mod entry;
pub mod family;
pub mod flatten;
pub mod fmu_state_calls;
pub mod fmu_states;
pub mod frontend;
pub mod handles;
pub mod hooks;
pub mod input_derivatives;
pub mod instance;
pub mod log;
pub mod logging;
pub mod model;
pub mod model_exchange_calls;
pub mod output_derivatives;
pub mod serialize;
pub mod shared;
pub mod sizes;
pub mod status;
pub mod structural;
pub mod tables;
pub mod value_check;
pub mod variables;
pub mod view;

pub use declare::Declaration;
pub use family::Family;
pub use hooks::{Element, Var};
pub use instance::{Instance, Snapshot, Standard};
pub use log::{Log, LogCategory};
pub use model::{
    DefaultExperiment, EventUpdate, Jacobian, Model, ModelInfo, OutputDerivativeError, StepOutcome,
};
pub use variables::{Variability, Variable};
