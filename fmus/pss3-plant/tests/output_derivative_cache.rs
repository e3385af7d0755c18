//! Pss3Plant keeps the output derivatives it evaluated along the local motion for the
//! point they belong to (parameters, state, inputs). Whatever changes the point (an
//! input, a step, a restored FMU state, a parameter) must give the answer of an
//! instance that never evaluated anything before: a fresh instance restored to the same
//! FMU state. Asking again at the same point must give the same bits.

use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::Host;
use robofmu_pss3_plant_fmu::Pss3Plant;

type H = Host<Pss3Plant>;

/// Every Real output of the plant, from its variable table.
fn real_outputs() -> Vec<String> {
    robofmu_fmi_testing::real_outputs::<Pss3Plant>()
}

/// A tilted, moving plant driven by constant actuator forces, with `sliderMass` (kg;
/// default 0.26272).
fn moving_plant(slider_mass: f64) -> H {
    let h = H::with_logging(FMI2_CO_SIMULATION, false);
    h.set_vector("theta0", [0.05, -0.04, 2.35]);
    h.set_vector("omega0", [0.3, -0.5, 0.8]);
    h.set_vector("actuatorForce", [20.0, -5.0, 12.0]);
    assert_eq!(h.set_real("sliderMass", slider_mass), Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Ok, "{}", h.last_message());
    h
}

/// Orders 1 and 2 of every Real output, as bit patterns; the first order-2 request
/// comes after an order-1 request of gravityCompensation at the same point, as a
/// master asks them.
fn derivatives(h: &H) -> Vec<u64> {
    let names = real_outputs();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let mut bits = Vec::new();
    for order in [1, 2] {
        let (s, d) = h.output_derivatives(&refs, &vec![order; refs.len()]);
        assert_eq!(s, Fmi2Status::Ok, "{}", h.last_message());
        bits.extend(d.iter().map(|v| v.to_bits()));
    }
    bits
}

/// The derivatives of a fresh instance restored to `h`'s FMU state.
fn fresh(h: &H) -> Vec<u64> {
    let other = moving_plant(0.26272);
    assert_eq!(other.restore(&h.serialize()), Fmi2Status::Ok);
    derivatives(&other)
}

#[test]
fn every_change_of_the_point_gives_the_answer_of_a_fresh_instance() {
    let h = moving_plant(0.26272);
    assert_eq!(h.step(0.0, 0.02), Fmi2Status::Ok);
    let first = derivatives(&h);
    assert_eq!(derivatives(&h), first, "asked twice at the same point");
    assert_eq!(first, fresh(&h));
    let before = h.serialize();

    h.set_vector("actuatorForce", [-3.0, 8.0, 1.0]);
    let input = derivatives(&h);
    assert_ne!(input, first, "the input changes the derivatives");
    assert_eq!(input, fresh(&h), "after an input changed");

    assert_eq!(h.step(0.02, 0.01), Fmi2Status::Ok);
    let stepped = derivatives(&h);
    assert_ne!(stepped, input);
    assert_eq!(stepped, fresh(&h), "after a step");

    assert_eq!(h.restore(&before), Fmi2Status::Ok);
    assert_eq!(
        derivatives(&h),
        first,
        "after restoring the earlier FMU state"
    );
}

#[test]
fn a_changed_parameter_gives_the_answer_of_a_fresh_instance() {
    // Both at their initial state (the same theta0, omega0, inputs): only sliderMass
    // differs.
    let h = moving_plant(0.26272);
    let first = derivatives(&h);
    let heavier = moving_plant(0.4);
    let expected = derivatives(&heavier);
    assert_ne!(expected, first, "the parameter changes the derivatives");
    assert_eq!(h.restore(&heavier.serialize()), Fmi2Status::Ok);
    for name in ["theta", "omega"] {
        assert_eq!(h.vector(name), heavier.vector(name), "the same state");
    }
    assert_eq!(derivatives(&h), expected, "after a parameter changed");
}
