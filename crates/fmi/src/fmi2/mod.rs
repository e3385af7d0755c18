//! The FMI 2.0 front-end: C types, the 2.0 state machine, the 44 C functions of Model
//! Exchange and Co-Simulation and the 2.0 modelDescription writer, around the
//! version-neutral [`core`](crate::core).
//!
//! A model implements [`core::Model`](crate::core::Model); an FMU crate calls
//! [`export_fmi2!`](crate::export_fmi2) once to get the C functions. modelDescription.xml
//! is generated from the same variable table by [`description::model_description`].

pub mod api;
pub mod description;
pub mod documentation;
mod export;
pub mod host;
pub mod instance;
pub mod logging;
pub mod mode;
pub mod package;
pub mod types;

pub use logging::Logger;
