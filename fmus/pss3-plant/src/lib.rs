//! The Pss3Plant FMU: one cdylib with exactly one set of fmi2* symbols, all forwarding
//! to the generic FMI 2.0 layer for `robofmu::fmus::pss3_plant::Pss3Plant`.

robofmu::export_fmi2!(robofmu::fmus::pss3_plant::Pss3Plant);
