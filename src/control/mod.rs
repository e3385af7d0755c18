//! Control math without any FMI: polynomial trajectories and a PID law with an exact
//! discretisation. The FMU bindings in `crate::fmus` translate variables to these calls.

pub mod pid;
pub mod trajectory;
