//! The checked-in modelDescription/<Model>.xml files must equal what the code
//! generates (the variable tables are the single source of truth).
//! Regenerate with `UPDATE_MODEL_DESCRIPTION=1 cargo test --release --test
//! model_descriptions` or `robofmu fmi write-model-descriptions`.

use std::path::PathBuf;

#[test]
fn checked_in_model_descriptions_match_the_code() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("modelDescription");
    let update = std::env::var_os("UPDATE_MODEL_DESCRIPTION").is_some();
    for fmu in robofmu::fmus::all() {
        let generated = (fmu.model_description)().expect("model description generates");
        let path = dir.join(format!("{}.xml", fmu.model_name));
        if update {
            std::fs::write(&path, &generated).expect("write model description");
        }
        let on_disk =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(
            on_disk == generated,
            "{} drifted from the code: run UPDATE_MODEL_DESCRIPTION=1 cargo test --release \
             --test model_descriptions",
            path.display()
        );
    }
}

#[test]
fn model_structure_lists_exactly_the_outputs_and_derivatives() {
    // Expected values: counted from the variable tables (PID: 3 outputs, 6 states;
    // Planner: 9 outputs, no states).
    let pid = (robofmu::fmus::all()[1].model_description)().unwrap();
    let section = |xml: &str, tag: &str| -> usize {
        let start = xml.find(&format!("<{tag}>")).map_or(0, |i| i);
        let end = xml.find(&format!("</{tag}>")).map_or(0, |i| i);
        xml[start..end].matches("<Unknown ").count()
    };
    assert_eq!(section(&pid, "Outputs"), 3);
    assert_eq!(section(&pid, "Derivatives"), 6);
    assert_eq!(section(&pid, "InitialUnknowns"), 9);
    let planner = (robofmu::fmus::all()[0].model_description)().unwrap();
    assert_eq!(section(&planner, "Outputs"), 9);
    assert!(!planner.contains("<Derivatives>"));
}
