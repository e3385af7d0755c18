//! The planner FMU: one cdylib with exactly one set of fmi2* symbols, all forwarding to
//! the generic FMI 2.0 layer for `robofmu::fmus::planner::Planner`.

robofmu::export_fmi2!(robofmu::fmus::planner::Planner);
