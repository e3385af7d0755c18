//! The checked-in modelDescription/Planner.xml must equal what the code generates (the
//! variable table is the single source of truth). Regenerate with
//! `UPDATE_MODEL_DESCRIPTION=1 cargo test --release -p robofmu-planner-fmu --test model_description`.

use robofmu_fmi_build::fmi2::{
    check_checked_in, model_description, unknowns_in_section as unknowns,
};
use robofmu_planner_fmu::Planner;

#[test]
fn checked_in_model_description_matches_the_code() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../modelDescription");
    check_checked_in::<Planner>(&dir).unwrap();
}

#[test]
fn model_structure_lists_exactly_the_outputs() {
    // Expected values: counted from the variable table (q, qdot, qddot per axis:
    // 9 outputs; no continuous states).
    let xml = model_description::<Planner>().unwrap();
    assert_eq!(unknowns(&xml, "Outputs"), 9);
    assert_eq!(unknowns(&xml, "Derivatives"), 0);
}
