//! robofmu-fmi: the generic FMI layer, with no robot code.
//!
//! A model implements [`core::Model`] in safe Rust; an FMU crate calls
//! [`export_fmi2!`] once to get the exported FMI 2.0 C functions.

pub mod core;
pub mod fmi2;
