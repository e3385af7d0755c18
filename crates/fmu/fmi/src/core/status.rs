//! The status codes of a standard as the version-neutral core sees them: FMI 2.0's
//! `fmi2Status` and FMI 3.0's `fmi3Status` both implement [`StatusCode`].

/// The return status of a standard's functions, as far as the layer sets it.
pub trait StatusCode: Copy + Eq + PartialOrd {
    const OK: Self;
    const WARNING: Self;
    const DISCARD: Self;
    const ERROR: Self;
    const FATAL: Self;
}
