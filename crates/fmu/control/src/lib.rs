//! Control math without any FMI: polynomial trajectories, a PID law with an exact
//! discretisation, its sampled form on a tick clock (`sampled`). The planner and PID FMU bindings (fmus/planner, fmus/pid) translate variables to these calls.

pub mod pid;
pub mod pid_jacobian;
pub mod pid_ramp;
pub mod sampled;
pub mod trajectory;
