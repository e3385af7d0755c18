//! The checked-in modelDescription/Pss3Plant.xml and modelDescription/fmi3/Pss3Plant.xml must
//! equal what the code generates (the variable table is the single source of truth).
//! Regenerate both with
//! `UPDATE_MODEL_DESCRIPTION=1 cargo test --release -p robofmu-pss3-plant-fmu --test model_description`.

use robofmu_fmi_build::fmi2::{model_description, unknowns_in_section as unknowns};
use robofmu_pss3_plant_fmu::Pss3Plant;

#[test]
fn checked_in_model_descriptions_match_the_code() {
    robofmu_fmi_build::drift::check_checked_in::<Pss3Plant>(env!("CARGO_MANIFEST_DIR")).unwrap();
}

#[test]
fn model_structure_lists_exactly_the_outputs_and_derivatives() {
    // Expected values: every variable of causality "output" (37, counted in the
    // table) is an Output; 6 states (Euler angles and omega) have derivatives; the
    // initial unknowns are the outputs and the derivatives.
    let xml = model_description::<Pss3Plant>().unwrap();
    let outputs = xml.matches("causality=\"output\"").count();
    assert_eq!(outputs, 37);
    assert_eq!(unknowns(&xml, "Outputs"), outputs);
    assert_eq!(unknowns(&xml, "Derivatives"), 6);
    assert_eq!(unknowns(&xml, "InitialUnknowns"), outputs + 6);
}
