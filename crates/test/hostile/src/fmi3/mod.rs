//! The FMI 3.0 side of the hostile importer: the binary's fmi3 functions, the
//! importer's instance and state machine, sequences and lifecycle (the cycles and
//! threads tests take the FMI 3.0 simulations from here). Its tables for the one
//! matrix are in `matrix::fmi3`.

/// The FMI 3.0 function table and types (shared with the platform-test host).
pub use robofmu_fmi_host::fmi3 as binary;
pub mod host;
pub mod lifecycle;
pub mod resized;
pub mod sequences;
