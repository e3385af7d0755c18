//! The checked-in modelDescription/PID.xml and modelDescription/fmi3/PID.xml must
//! equal what the code generates (the variable table is the single source of truth).
//! Regenerate both with
//! `UPDATE_MODEL_DESCRIPTION=1 cargo test --release -p robofmu-pid-fmu --test model_description`.

use robofmu_fmi_build::fmi2::{model_description, unknowns_in_section as unknowns};
use robofmu_pid_fmu::Pid;

#[test]
fn checked_in_model_descriptions_match_the_code() {
    robofmu_fmi_build::drift::check_checked_in::<Pid>(env!("CARGO_MANIFEST_DIR")).unwrap();
}

#[test]
fn model_structure_lists_exactly_the_outputs_and_derivatives() {
    // Expected values: counted from the variable table (3 outputs u[i]; 6 states:
    // integral and filter state per channel; initial unknowns: outputs and derivatives).
    let xml = model_description::<Pid>().unwrap();
    assert_eq!(unknowns(&xml, "Outputs"), 3);
    assert_eq!(unknowns(&xml, "Derivatives"), 6);
    assert_eq!(unknowns(&xml, "InitialUnknowns"), 9);
}
