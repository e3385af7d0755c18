//! The generic FMI 2.0 layer: everything an FMU needs except the model.
//!
//! A model implements [`Model`] with a table of [`Variable`]s (safe Rust, no FFI);
//! an FMU crate calls [`export_fmi2!`](crate::export_fmi2) once to get the 44 C
//! functions of Model Exchange and Co-Simulation. modelDescription.xml is generated
//! from the same table by [`description::model_description`].

pub mod api;
pub mod description;
pub mod documentation;
mod export;
pub mod host;
pub mod instance;
pub mod logging;
pub mod mode;
pub mod model;
pub mod package;
pub mod serialize;
pub mod types;
pub mod units;
pub mod variables;

pub use logging::{LogCategory, Logger};
pub use model::{DefaultExperiment, Model, ModelInfo, StepOutcome};
pub use variables::{Variability, Variable};
