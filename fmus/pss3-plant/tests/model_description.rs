//! The ModelStructure of the generated FMI 2.0 modelDescription.xml of Pss3Plant. The
//! checked-in descriptions are compared with the code by the workspace packager
//! (`robofmu-packager --check`, the test in crates/build/packager/tests/).

use robofmu_fmi::description::describe;
use robofmu_fmi_build::fmi2::{model_description, unknowns_in_section as unknowns};
use robofmu_pss3_plant_fmu::Pss3Plant;

#[test]
fn model_structure_lists_exactly_the_outputs_and_derivatives() {
    // Expected values: every variable of causality "output" (37, counted in the
    // table) is an Output; 6 states (Euler angles and omega) have derivatives; the
    // initial unknowns are the outputs and the derivatives.
    let xml = model_description(&describe::<Pss3Plant>().unwrap()).unwrap();
    let outputs = xml.matches("causality=\"output\"").count();
    assert_eq!(outputs, 37);
    assert_eq!(unknowns(&xml, "Outputs"), outputs);
    assert_eq!(unknowns(&xml, "Derivatives"), 6);
    assert_eq!(unknowns(&xml, "InitialUnknowns"), outputs + 6);
}
