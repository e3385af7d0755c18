//! robofmu-fmi: the generic FMI layer, with no robot code.
//!
//! A model implements [`fmi2::Model`] in safe Rust; an FMU crate calls
//! [`export_fmi2!`] once to get the exported C functions.

pub mod fmi2;
