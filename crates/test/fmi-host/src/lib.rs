//! The one FMI host of robofmu's tests: the FMI function tables of a binary,
//! [`fmi2::Binary`] (FMI 2.0) and [`fmi3::Binary3`] (FMI 3.0), each function looked up
//! by its standard name with its C signature in a library opened with the one loader
//! ([`Library`], of `crates/build/fmi-loader`), or filled in-process with the functions
//! of a model linked into the test; the importer's callbacks; the instances and their
//! calls. The hostile importer (`crates/test/hostile`), the in-process host of the FMU
//! crates' tests (`crates/test/fmi-testing`) and this crate's binary, the
//! platform-test host (`src/bin`, cross-built for Windows and aarch64 Linux), call FMUs
//! through the tables.

pub use robofmu_fmi_loader::Library;

pub mod callbacks;
pub mod fmi2;
pub mod fmi3;
pub mod instance;
