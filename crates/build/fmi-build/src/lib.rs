//! robofmu-fmi-build: what turns the [`Description`](robofmu_fmi::description::Description)
//! an FMU's cdylib gives of itself into files, at build time only. An FMU's cdylib
//! never links it; the workspace packager (`crates/build/packager`) does.
//!
//! - [`fmi2::model_description`], [`fmi3::model_description`] and
//!   [`fmi3::scalar_model_description`]: modelDescription.xml of each standard (and
//!   of the scalar-only FMI 3.0 variant), with what both write alike in [`common`]
//!   (the root element), [`variable`] (a variable's attributes) and [`sections`]
//!   (units from [`units`], log categories, default experiment);
//! - documentation/index.html from [`documentation`];
//! - [`lsref`]: the experiments and results every FMU carries (FMI-LS-REF), from the
//!   test cases of `tests/references/`;
//! - [`package`]: the three FMU archives of a model ([`package::Variant`]), with the
//!   platform folder names of [`platform`];
//! - [`drift`]: the check of the checked-in descriptions, and their regeneration.

pub mod common;
pub mod documentation;
pub mod drift;
pub mod fmi2;
pub mod fmi3;
pub mod lsref;
pub mod package;
pub mod platform;
pub mod sections;
pub mod units;
pub mod variable;
