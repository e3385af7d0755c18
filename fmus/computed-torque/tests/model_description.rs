//! The ModelStructure of the generated FMI 2.0 modelDescription.xml of ComputedTorqueFmu. The
//! checked-in descriptions are compared with the code by the workspace packager
//! (`robofmu-packager --check`, the test in crates/build/packager/tests/).

use robofmu_computed_torque_fmu::ComputedTorqueFmu;
use robofmu_fmi::description::describe;
use robofmu_fmi_build::fmi2::{model_description, unknowns_in_section as unknowns};

#[test]
fn model_structure_lists_exactly_the_outputs_and_derivatives() {
    // Expected values: counted from the variable table (3 outputs u[i]; 3 states, the
    // error integral per axis; initial unknowns: outputs and derivatives).
    let xml = model_description(&describe::<ComputedTorqueFmu>().unwrap()).unwrap();
    assert_eq!(unknowns(&xml, "Outputs"), 3);
    assert_eq!(unknowns(&xml, "Derivatives"), 3);
    assert_eq!(unknowns(&xml, "InitialUnknowns"), 6);
}
