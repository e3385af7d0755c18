//! fmi2SetRealInputDerivatives on the plant through the layer's entry points: the
//! hostile-importer argument checks, the calls' legality, and the derivatives as part
//! of the FMU state (get/set, serialize, reset). The accuracy gained by them is shown
//! in tests/python/test_input_derivatives.py.

use robofmu_fmi::fmi2::api;
use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::{Host, vr};
use robofmu_pss3_plant_fmu::Pss3Plant;
use std::ptr::null;

type H = Host<Pss3Plant>;
/// One hostile call on an instance.
type Call = Box<dyn Fn(&H) -> Fmi2Status>;
const CS: i32 = FMI2_CO_SIMULATION;

/// A tilted, moving start (as in pss3_plant_fmu.rs) with constant forces.
fn moving(kind: i32) -> H {
    let h = H::new(kind);
    h.set_vector("theta0", [0.05, -0.04, 2.35]);
    h.set_vector("omega0", [0.3, -0.5, 0.8]);
    h.set_vector("actuatorForce", [20.0, -5.0, 12.0]);
    h
}

/// Slopes and curvatures of two inputs.
fn set_ramps(h: &H) {
    for (name, order, value) in [
        ("actuatorForce[1]", 1, 400.0),
        ("actuatorForce[3]", 2, -3.0e4),
        ("disturbanceTorque[2]", 1, 2.5),
    ] {
        let s = h.set_input_derivative(name, order, value);
        assert_eq!(s, Fmi2Status::Ok, "{}", h.last_message());
    }
}

/// theta and omega after each of `n` steps of 1 ms from t0.
fn run(h: &H, t0: f64, n: usize) -> Vec<[[f64; 3]; 2]> {
    (0..n)
        .map(|k| {
            let t = t0 + k as f64 * 1e-3;
            assert_eq!(h.step(t, 1e-3), Fmi2Status::Ok, "{}", h.last_message());
            [h.vector("theta"), h.vector("omega")]
        })
        .collect()
}

#[test]
fn bad_arguments_are_refused_with_a_line_naming_the_variable_and_order() {
    let force = vr::<Pss3Plant>("actuatorForce[1]");
    let cases: [(&str, Call, &str); 9] = [
        (
            "null vr",
            Box::new(|h| unsafe {
                api::set_real_input_derivatives::<Pss3Plant>(h.c, null(), 1, &1, &0.0)
            }),
            "vr[] is a null pointer",
        ),
        (
            "null order",
            Box::new(move |h| unsafe {
                api::set_real_input_derivatives::<Pss3Plant>(h.c, &force, 1, null(), &0.0)
            }),
            "order[] is a null pointer",
        ),
        (
            "null value",
            Box::new(move |h| unsafe {
                api::set_real_input_derivatives::<Pss3Plant>(h.c, &force, 1, &1, null())
            }),
            "value[] is a null pointer",
        ),
        (
            "unknown vr",
            Box::new(|h| unsafe {
                api::set_real_input_derivatives::<Pss3Plant>(h.c, &99_999, 1, &1, &0.0)
            }),
            "unknown value reference 99999",
        ),
        (
            "an output",
            Box::new(|h| h.set_input_derivative("theta[1]", 1, 1.0)),
            "\"theta[1]\" (value reference 101) is a continuous Real output, not a continuous Real input",
        ),
        (
            "a parameter",
            Box::new(|h| h.set_input_derivative("g", 1, 1.0)),
            "Real parameter, not a continuous Real input",
        ),
        (
            "order 0",
            Box::new(|h| h.set_input_derivative("actuatorForce[2]", 0, 1.0)),
            "order 0 for \"actuatorForce[2]\" is not a derivative order",
        ),
        (
            "order 3",
            Box::new(|h| h.set_input_derivative("torqueCommand[1]", 3, 1.0)),
            "order 3 for \"torqueCommand[1]\" is above 2",
        ),
        (
            "NaN",
            Box::new(|h| h.set_input_derivative("disturbanceTorque[3]", 2, f64::NAN)),
            "derivative of order 2 of \"disturbanceTorque[3]\" = NaN is not a finite number",
        ),
    ];
    for (what, call, expected) in cases {
        let h = moving(CS);
        assert_eq!(h.initialize(), Fmi2Status::Ok);
        assert_eq!(call(&h), Fmi2Status::Error, "{what}");
        let line = h.last_message();
        assert!(
            line.starts_with("fmi2SetRealInputDerivatives: ") && line.contains(expected),
            "{what}: {line}"
        );
    }
    for value in [f64::INFINITY, 1e151] {
        let h = moving(CS);
        let s = h.set_input_derivative("actuatorForce[1]", 1, value);
        assert_eq!(s, Fmi2Status::Error, "{value}: {}", h.last_message());
    }
}

#[test]
fn the_calls_are_legal_where_fmi2_set_real_is_and_only_in_co_simulation() {
    // FMI 2.0 section 4.2.1: the restrictions of fmi2SetReal apply (Instantiated,
    // InitializationMode, StepComplete); Model Exchange has no such function.
    let h = moving(CS);
    assert_eq!(
        h.set_input_derivative("actuatorForce[1]", 1, 1.0),
        Fmi2Status::Ok
    );
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(
        h.set_input_derivative("actuatorForce[1]", 2, 1.0),
        Fmi2Status::Ok
    );
    assert_eq!(h.step(0.0, 1e-3), Fmi2Status::Ok);
    assert_eq!(
        h.set_input_derivative("actuatorForce[1]", 1, 2.0),
        Fmi2Status::Ok
    );
    // Not after fmi2Terminate (nor in StepFailed, Error: the mode table's rule).
    assert_eq!(unsafe { api::terminate::<Pss3Plant>(h.c) }, Fmi2Status::Ok);
    let late = h.set_input_derivative("actuatorForce[1]", 1, 3.0);
    assert_eq!(late, Fmi2Status::Error);
    assert!(h.last_message().contains("not allowed in mode Terminated"));
    let me = moving(FMI2_MODEL_EXCHANGE);
    assert_eq!(
        me.set_input_derivative("actuatorForce[1]", 1, 1.0),
        Fmi2Status::Error
    );
    assert!(me.last_message().contains("illegal call sequence"));
}

#[test]
fn zero_derivatives_step_bit_identically_to_held_inputs_and_others_do_not() {
    // Truth: the held-input path itself (a zero ramp must not even round differently).
    let held = moving(CS);
    assert_eq!(held.initialize(), Fmi2Status::Ok);
    let zero = moving(CS);
    assert_eq!(zero.initialize(), Fmi2Status::Ok);
    for order in [1, 2] {
        for name in [
            "actuatorForce[1]",
            "torqueCommand[2]",
            "disturbanceTorque[3]",
        ] {
            assert_eq!(zero.set_input_derivative(name, order, 0.0), Fmi2Status::Ok);
        }
    }
    assert_eq!(run(&held, 0.0, 20), run(&zero, 0.0, 20));
    let ramped = moving(CS);
    assert_eq!(ramped.initialize(), Fmi2Status::Ok);
    set_ramps(&ramped);
    assert_ne!(run(&held, 0.02, 5), run(&ramped, 0.0, 5));
}

#[test]
fn derivatives_are_part_of_the_fmu_state() {
    // Truth: the run of the instance that took the state. Restoring it after the
    // derivatives were changed (get/set and serialized) or into a fresh instance must
    // repeat that run bit for bit; a reset clears them (a fresh instance's held run).
    let h = moving(CS);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    set_ramps(&h);
    let saved = h.serialize();
    let mut state: Fmi2FmuState = std::ptr::null_mut();
    assert_eq!(
        unsafe { api::get_fmu_state::<Pss3Plant>(h.c, &mut state) },
        Fmi2Status::Ok
    );
    let original = run(&h, 0.0, 10);

    assert_eq!(
        h.set_input_derivative("actuatorForce[1]", 1, -50.0),
        Fmi2Status::Ok
    );
    assert_eq!(
        unsafe { api::set_fmu_state::<Pss3Plant>(h.c, state) },
        Fmi2Status::Ok
    );
    assert_eq!(run(&h, 0.0, 10), original, "fmi2SetFMUstate");

    assert_eq!(
        h.set_input_derivative("actuatorForce[3]", 2, 0.0),
        Fmi2Status::Ok
    );
    assert_eq!(h.restore(&saved), Fmi2Status::Ok);
    assert_eq!(run(&h, 0.0, 10), original, "fmi2DeSerializeFMUstate");

    let fresh = H::new(CS);
    assert_eq!(fresh.initialize(), Fmi2Status::Ok);
    assert_eq!(fresh.restore(&saved), Fmi2Status::Ok);
    assert_eq!(run(&fresh, 0.0, 10), original, "into another instance");
    assert_eq!(
        unsafe { api::free_fmu_state::<Pss3Plant>(h.c, &mut state) },
        Fmi2Status::Ok
    );

    assert_eq!(unsafe { api::reset::<Pss3Plant>(h.c) }, Fmi2Status::Ok);
    let held = moving(CS);
    for one in [&h, &held] {
        one.set_vector("theta0", [0.05, -0.04, 2.35]);
        one.set_vector("omega0", [0.3, -0.5, 0.8]);
        one.set_vector("actuatorForce", [20.0, -5.0, 12.0]);
        assert_eq!(one.initialize(), Fmi2Status::Ok);
    }
    assert_eq!(run(&h, 0.0, 10), run(&held, 0.0, 10), "after fmi2Reset");
}
