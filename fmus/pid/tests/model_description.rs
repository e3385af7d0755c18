//! The checked-in modelDescription/PID.xml must equal what the code generates (the
//! variable table is the single source of truth). Regenerate with
//! `UPDATE_MODEL_DESCRIPTION=1 cargo test --release -p robofmu-pid-fmu --test model_description`.

use robofmu_fmi_build::fmi2::{
    check_checked_in, model_description, unknowns_in_section as unknowns,
};
use robofmu_pid_fmu::Pid;

#[test]
fn checked_in_model_description_matches_the_code() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../modelDescription");
    check_checked_in::<Pid>(&dir).unwrap();
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
