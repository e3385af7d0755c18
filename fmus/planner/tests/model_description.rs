//! The ModelStructure of the generated FMI 2.0 modelDescription.xml of Planner. The
//! checked-in descriptions are compared with the code by the workspace packager
//! (`robofmu-packager --check`, the test in crates/build/packager/tests/).

use robofmu_fmi::description::describe;
use robofmu_fmi_build::fmi2::{model_description, unknowns_in_section as unknowns};
use robofmu_planner_fmu::Planner;

#[test]
fn model_structure_lists_exactly_the_outputs() {
    // Expected values: counted from the variable table (q, qdot, qddot per axis:
    // 9 outputs; no continuous states).
    let xml = model_description(&describe::<Planner>().unwrap()).unwrap();
    assert_eq!(unknowns(&xml, "Outputs"), 9);
    assert_eq!(unknowns(&xml, "Derivatives"), 0);
}
