//! The checked-in modelDescription/ComputedTorque.xml and
//! modelDescription/fmi3/ComputedTorque.xml must equal what the code generates.
//! Regenerate both with `UPDATE_MODEL_DESCRIPTION=1 cargo test --release -p
//! robofmu-computed-torque-fmu --test model_description`.

use robofmu_computed_torque_fmu::ComputedTorqueFmu;
use robofmu_fmi_build::fmi2::{model_description, unknowns_in_section as unknowns};

#[test]
fn checked_in_model_descriptions_match_the_code() {
    robofmu_fmi_build::drift::check_checked_in::<ComputedTorqueFmu>(env!("CARGO_MANIFEST_DIR"))
        .unwrap();
}

#[test]
fn model_structure_lists_exactly_the_outputs_and_derivatives() {
    // Expected values: counted from the variable table (3 outputs u[i]; 3 states, the
    // error integral per axis; initial unknowns: outputs and derivatives).
    let xml = model_description::<ComputedTorqueFmu>().unwrap();
    assert_eq!(unknowns(&xml, "Outputs"), 3);
    assert_eq!(unknowns(&xml, "Derivatives"), 3);
    assert_eq!(unknowns(&xml, "InitialUnknowns"), 6);
}
