//! The ModelStructure of the generated FMI 2.0 modelDescription.xml of Pid. The
//! checked-in descriptions are compared with the code by the workspace packager
//! (`robofmu-packager --check`, the test in crates/build/packager/tests/).

use robofmu_fmi::description::describe;
use robofmu_fmi_build::fmi2::{model_description, unknowns_in_section as unknowns};
use robofmu_pid_fmu::Pid;

#[test]
fn model_structure_lists_exactly_the_outputs_and_derivatives() {
    // Expected values: counted from the variable table (3 outputs u[i]; 6 states:
    // integral and filter state per channel; initial unknowns: outputs and derivatives).
    let xml = model_description(&describe::<Pid>().unwrap()).unwrap();
    assert_eq!(unknowns(&xml, "Outputs"), 3);
    assert_eq!(unknowns(&xml, "Derivatives"), 6);
    assert_eq!(unknowns(&xml, "InitialUnknowns"), 9);
}
