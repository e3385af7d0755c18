//! robofmu-fmi: the generic FMI layer, with no robot code.
//!
//! A model implements [`core::Model`] in safe Rust; an FMU crate calls
//! [`export_fmi2!`] and [`export_fmi3!`] once each to get the exported FMI 2.0 and
//! FMI 3.0 C functions from one cdylib.

pub mod core;
pub mod ffi;
pub mod fmi2;
pub mod fmi3;
