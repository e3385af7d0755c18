//! Packager of this FMU: `robofmu-pid-fmu package [--out DIR]` writes the .fmu from the cdylib
//! built beside this binary; `robofmu-pid-fmu model-description [--out DIR]` writes the XML.

fn main() -> std::process::ExitCode {
    robofmu_fmi_build::package::packager_main::<robofmu_pid_fmu::Pid>(env!("CARGO_PKG_NAME"))
}
