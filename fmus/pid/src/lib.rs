//! The pid FMU: one cdylib with exactly one set of fmi2* symbols, all forwarding to
//! the generic FMI 2.0 layer for `robofmu::fmus::pid::Pid`.

robofmu::export_fmi2!(robofmu::fmus::pid::Pid);
