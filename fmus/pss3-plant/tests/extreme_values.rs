//! Extreme finite values (issue 12): a parameter of 1e308 is refused where it is set,
//! naming it; an input that makes a step overflow discards that step.

use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::Host;
use robofmu_pss3_plant_fmu::Pss3Plant;

type H = Host<Pss3Plant>;

#[test]
fn a_leg_mass_of_1e308_is_refused_where_it_is_set() {
    // Truth: 1e308 exceeds the layer's limit 1e150 (m g alone would be 1e309).
    let h = H::with_logging(FMI2_CO_SIMULATION, false);
    assert_eq!(h.set_real("legMass", 1e308), Fmi2Status::Error);
    assert!(
        h.last_message().contains("\"legMass\" = 1e308"),
        "{}",
        h.last_message()
    );
}

#[test]
fn an_input_that_overflows_a_step_discards_it_with_the_state_unchanged() {
    // Truth: an actuator force of 1e150 N on a platform of a few kg accelerates it by
    // ~1e149 rad/s2: within 1 ms the pose leaves every assembly; the step is rejected
    // and the state stays the one before the step.
    let h = H::new(FMI2_CO_SIMULATION);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    let theta = h.vector("theta");
    assert_eq!(h.set_real("actuatorForce[1]", 1e150), Fmi2Status::Ok);
    assert_eq!(h.step(0.0, 1e-3), Fmi2Status::Discard);
    assert_eq!(h.vector("theta"), theta);
}
