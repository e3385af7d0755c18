//! Packager of this FMU: `target/release/examples/robofmu-planner-fmu-package package [--out DIR]` writes the .fmu from the cdylib
//! built beside this binary; `... model-description [--out DIR]` writes the XML.

fn main() -> std::process::ExitCode {
    robofmu_fmi_build::package::packager_main::<robofmu_planner_fmu::Planner>(env!(
        "CARGO_PKG_NAME"
    ))
}
