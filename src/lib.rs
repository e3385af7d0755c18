//! robofmu: robot models as FMI 2.0 components.
//!
//! Layering: the robot libraries (`pss3`, `dexterity`, `dual_arm`, `control`) know
//! nothing of FMI; the generic FMI layer (`fmi2`) knows nothing of robots; each FMU
//! crate under `fmus/` is a thin binding between them.

pub mod closed_loop;
pub mod control;
pub mod dexterity;
pub mod dual_arm;
pub mod fmi2;
pub mod fmus;
pub mod plot;
pub mod pss3;
