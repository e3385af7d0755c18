//! The checked-in modelDescription/Planner.xml and modelDescription/fmi3/Planner.xml must
//! equal what the code generates (the variable table is the single source of truth).
//! Regenerate both with
//! `UPDATE_MODEL_DESCRIPTION=1 cargo test --release -p robofmu-planner-fmu --test model_description`.

use robofmu_fmi_build::fmi2::{model_description, unknowns_in_section as unknowns};
use robofmu_planner_fmu::Planner;

#[test]
fn checked_in_model_descriptions_match_the_code() {
    robofmu_fmi_build::drift::check_checked_in::<Planner>(env!("CARGO_MANIFEST_DIR")).unwrap();
}

#[test]
fn model_structure_lists_exactly_the_outputs() {
    // Expected values: counted from the variable table (q, qdot, qddot per axis:
    // 9 outputs; no continuous states).
    let xml = model_description::<Planner>().unwrap();
    assert_eq!(unknowns(&xml, "Outputs"), 9);
    assert_eq!(unknowns(&xml, "Derivatives"), 0);
}
