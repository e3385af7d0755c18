//! The bad-input matrix for the FMI 3.0 interface of the packaged FMUs: the same
//! cases, judge and report as the FMI 2.0 matrix (`crate::matrix`), with the FMI
//! 3.0 functions, states and arguments. Besides the status and the log line, every
//! case in which a live instance refuses a call (fmi3Error: the instance is in the
//! Error state, FMI 3.0 section 2.3.1) checks that it is usable afterwards:
//! fmi3Reset, initialization and a read of every Float64 succeed with finite values.

pub mod arrays;
pub mod calls;
pub mod handles;
pub mod instantiate;
pub mod orders;
pub mod pointers;
pub mod pose;
pub mod serialized;
pub mod standard;
pub mod states;
pub mod values;
pub mod variability;

use crate::Loaded;
pub use crate::matrix::{Case, Observed, on_instance, with_args};

/// Every FMI 3.0 case of the matrix.
pub fn all_cases(loaded: &Loaded) -> Vec<Case> {
    crate::matrix::per_model(
        loaded,
        &[
            pointers::cases,
            arrays::cases,
            values::cases,
            variability::cases,
            serialized::cases,
            orders::cases,
            handles::cases,
            states::cases,
            pose::cases,
            instantiate::cases,
        ],
    )
}
