//! The checked-in modelDescription/Planner.xml must equal what the code generates (the
//! variable table is the single source of truth). Regenerate with
//! `UPDATE_MODEL_DESCRIPTION=1 cargo test --release -p robofmu-planner-fmu --test model_description`.

use robofmu_fmi::fmi2::description::{check_checked_in, model_description};
use robofmu_planner_fmu::Planner;

#[test]
fn checked_in_model_description_matches_the_code() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../modelDescription");
    check_checked_in::<Planner>(&dir).unwrap();
}

/// Number of `<Unknown>` entries in one ModelStructure section.
fn unknowns(xml: &str, section: &str) -> usize {
    match (
        xml.find(&format!("<{section}>")),
        xml.find(&format!("</{section}>")),
    ) {
        (Some(start), Some(end)) => xml[start..end].matches("<Unknown ").count(),
        _ => 0,
    }
}

#[test]
fn model_structure_lists_exactly_the_outputs() {
    // Expected values: counted from the variable table (q, qdot, qddot per axis:
    // 9 outputs; no continuous states).
    let xml = model_description::<Planner>().unwrap();
    assert_eq!(unknowns(&xml, "Outputs"), 9);
    assert_eq!(unknowns(&xml, "Derivatives"), 0);
}
