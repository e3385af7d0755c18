//! The FMI 3.0 front-end: everything an FMU needs for FMI 3.0 beyond the core.
//!
//! A model implements [`core::Model`](crate::core::Model) once; an FMU crate calls
//! [`export_fmi3!`](crate::export_fmi3) beside `export_fmi2!` to export the FMI 3.0
//! functions of Model Exchange and Co-Simulation from the same cdylib.
//! The table's `x[1]`..`x[n]` scalars are one array `x` here ([`table`]); the build
//! crate (`robofmu-fmi-build`) writes modelDescription.xml (FMI 3.0) from the same view.

pub mod api;
pub mod clocks;
pub mod declared;
mod export;
pub mod extra;
pub mod instance;
pub mod intermediate;
pub mod logging;
pub mod mode;
pub mod scalar;
pub mod table;
pub mod types;
