//! robofmu-fmi-build: what turns a model of the runtime layer
//! ([`robofmu_fmi`]) into files, at build time only. An FMU's cdylib never links it.
//!
//! - [`fmi2::model_description`] and [`fmi3::model_description`]: modelDescription.xml
//!   of each standard from the model's `ModelInfo` and variable table, with the parts
//!   both share in [`common`] (units from [`units`], log categories, default experiment),
//!   (and [`fmi3::scalar_model_description`], the scalar-only FMI 3.0 variant),
//!   and [`drift::check_checked_in`], the drift test of the checked-in descriptions;
//! - documentation/index.html from [`documentation`];
//! - [`package`]: the FMU archive and the packager entry point an FMU crate's
//!   `examples/package.rs` calls ([`package::packager_main`]), with the platform
//!   folder names of [`platform`].

pub mod common;
pub mod documentation;
pub mod drift;
pub mod fmi2;
pub mod fmi3;
pub mod package;
pub mod platform;
pub mod units;
