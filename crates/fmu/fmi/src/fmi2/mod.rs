//! The FMI 2.0 front-end: C types, the 2.0 state machine, the 44 C functions of Model
//! Exchange and Co-Simulation, around the
//! version-neutral [`core`](crate::core).
//!
//! A model implements [`core::Model`](crate::core::Model); an FMU crate calls
//! [`export_fmu!`](crate::export_fmu) once, which expands to
//! [`export_fmi2!`](crate::export_fmi2) (the C functions), `export_fmi3!` and
//! [`share_index!`](crate::share_index) (the model's index cell the instantiate
//! functions take the index from). modelDescription.xml
//! is generated from the same variable table by the build crate (`robofmu-fmi-build`).

pub mod api;
mod export;
pub mod instance;
pub mod logging;
pub mod mode;
pub mod types;

pub use logging::Logger;
