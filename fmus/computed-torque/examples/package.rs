//! Packager of this FMU: `target/release/examples/robofmu-computed-torque-fmu-package package [--out DIR]` writes the .fmu from the cdylib
//! built beside this binary; `... model-description [--out DIR]` writes the XML.

fn main() -> std::process::ExitCode {
    robofmu_fmi_build::package::packager_main::<robofmu_computed_torque_fmu::ComputedTorqueFmu>(
        env!("CARGO_PKG_NAME"),
    )
}
