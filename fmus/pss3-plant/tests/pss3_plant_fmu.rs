//! The Pss3Plant binding through the FMI layer's entry points: outputs against the
//! library, the input mappings against the statics, parameter refusal, Discard,
//! Model Exchange events and derivatives, directional derivatives, FMU state.

use nalgebra::{Matrix3, Vector3};
use robofmu_dynamics::pss3::dynamics::{Plant, PlantInputs, PlantParams, PlantState};
use robofmu_dynamics::pss3::rotation::euler_rate_matrix;
use robofmu_dynamics::pss3::{assemble, jacobian};
use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::Host;
use robofmu_pss3_plant_fmu::Pss3Plant;

type H = Host<Pss3Plant>;
const CS: i32 = FMI2_CO_SIMULATION;
const ME: i32 = FMI2_MODEL_EXCHANGE;

/// A tilted, moving state inside the stroke (l about 47, 73, 95 mm).
const THETA: [f64; 3] = [0.05, -0.04, 2.35];
const OMEGA: [f64; 3] = [0.3, -0.5, 0.8];

fn tilted(kind: i32) -> H {
    let h = H::new(kind);
    h.set_vector("theta0", THETA);
    h.set_vector("omega0", OMEGA);
    h
}

fn library_state() -> PlantState {
    PlantState {
        euler: Vector3::from(THETA),
        omega: Vector3::from(OMEGA),
    }
}

fn close(a: [f64; 3], b: Vector3<f64>, tol: f64) -> bool {
    (Vector3::from(a) - b).amax() <= tol * (1.0 + b.amax())
}

#[test]
fn outputs_equal_the_library_outputs() {
    // Truth: Plant::outputs/derivative of the dynamics library for the same state and
    // inputs (the binding only routes them).
    let h = tilted(CS);
    let forces = [20.0, -5.0, 12.0];
    let disturbance = [0.2, -0.1, 0.3];
    h.set_vector("actuatorForce", forces);
    h.set_vector("disturbanceTorque", disturbance);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    let plant = Plant::new(PlantParams::default()).unwrap();
    let inputs = PlantInputs {
        forces: Vector3::from(forces),
        disturbance_torque: Vector3::from(disturbance),
        ..PlantInputs::default()
    };
    let o = plant.outputs(&library_state(), &inputs).unwrap();
    let d = plant.derivative(&library_state(), &inputs).unwrap();
    assert_eq!(Vector3::from(h.vector("theta")), o.euler);
    assert_eq!(Vector3::from(h.vector("omega")), o.omega);
    assert_eq!(Vector3::from(h.vector("omegaDot")), o.omega_dot);
    assert_eq!(Vector3::from(h.vector("thetaDot")), d.euler_rates);
    assert_eq!(Vector3::from(h.vector("l")), o.actuator_displacements);
    assert_eq!(Vector3::from(h.vector("lDot")), o.actuator_velocities);
    assert_eq!(Vector3::from(h.vector("force")), o.actuator_forces);
    assert_eq!(Vector3::from(h.vector("stopForce")), o.end_stop_forces);
    assert_eq!(h.real("detJ"), o.jacobian_det);
    assert_eq!(h.real("condJ"), o.jacobian_cond);
    assert_eq!(h.real("kineticEnergy"), o.kinetic_energy);
    assert_eq!(
        h.real("potentialEnergy"),
        o.potential_energy + o.end_stop_energy
    );
    assert_eq!(h.real("yaw"), THETA[0]);
    assert_eq!(h.real("pitch"), -THETA[1]);
    assert_eq!(h.real("roll"), THETA[2]);
    let l = h.vector("l");
    assert!(l.iter().all(|&li| (0.002..0.152).contains(&li)), "{l:?}");
    assert_eq!(
        [1, 2, 3].map(|i| h.integer(&format!("atStop[{i}]"))),
        [0; 3]
    );
}

#[test]
fn commands_map_through_the_statics() {
    // Truth: f = J^-T tau with J from the core kinematics, and tau = E^-T Q with E^-T
    // from nalgebra's general matrix inverse of E^T (not the closed form the library
    // uses).
    let h = tilted(CS);
    let tau = [1.5, -0.8, 2.2];
    let q = [-0.6, 1.1, 0.4];
    h.set_vector("torqueCommand", tau);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    let geometry = Plant::new(PlantParams::default())
        .unwrap()
        .model()
        .geometry
        .clone();
    let j = jacobian(
        &geometry,
        &assemble(&geometry, &Vector3::from(THETA)).unwrap(),
    )
    .unwrap();
    let j_inv_t: Matrix3<f64> = j.matrix.transpose().try_inverse().unwrap();
    let expected = j_inv_t * Vector3::from(tau);
    assert!(close(h.vector("force"), expected, 1e-12), "{expected}");

    let h = tilted(CS);
    h.set_vector("generalizedForceCommand", q);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    let e_inv_t = euler_rate_matrix(&Vector3::from(THETA))
        .transpose()
        .try_inverse()
        .unwrap();
    let expected = j_inv_t * (e_inv_t * Vector3::from(q));
    assert!(close(h.vector("force"), expected, 1e-12), "{expected}");
}

#[test]
fn gravity_compensation_holds_the_pose_at_rest() {
    // Truth: statics. At rest the generalized force G_x = E^T g(theta) balances gravity,
    // so feeding it back as generalizedForceCommand gives zero acceleration, while
    // without it the platform accelerates.
    let h = H::new(CS);
    h.set_vector("theta0", THETA);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    let g = h.vector("gravityCompensation");
    let falling = h.vector("omegaDot");
    assert!(Vector3::from(falling).amax() > 0.01, "{falling:?}");
    h.set_vector("generalizedForceCommand", g);
    let held = h.vector("omegaDot");
    assert!(Vector3::from(held).amax() < 1e-12, "{held:?}");
    // G depends on the state only: unchanged by the input just set.
    assert_eq!(h.vector("gravityCompensation"), g);
}

#[test]
fn invalid_parameters_are_refused_naming_the_parameter() {
    // Truth: the physical domain of each parameter (spec: SI values, positive lengths
    // and masses, a realisable inertia, a non-empty stroke, a pose that assembles).
    let cases: [(&str, f64, &str); 7] = [
        ("lp", 0.0, "parameter lp = 0 must be positive"),
        ("strokeMin", 0.2, "strokeMin"),
        ("a", 2.5, "parameter a"),
        ("platformInertia[1,1]", 0.001, "platformInertia"),
        ("endStopStiffness", 0.0, "endStopStiffness"),
        ("tolerance", 0.0, "tolerance"),
        ("theta0[2]", 1.2, "theta0"),
    ];
    for (name, value, expected) in cases {
        let h = H::new(CS);
        assert_eq!(h.set_real(name, value), Fmi2Status::Ok, "{name}");
        assert_eq!(h.initialize(), Fmi2Status::Error, "{name} = {value}");
        let message = h.last_message();
        assert!(message.contains(expected), "{name}: {message}");
    }
    // l0 outside the stroke, used only with initFromActuators.
    let h = H::new(CS);
    assert_eq!(h.set_real("l0[1]", 0.3), Fmi2Status::Ok);
    assert_eq!(h.set_boolean("initFromActuators", true), Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Error);
    assert!(h.last_message().contains("l0"), "{}", h.last_message());
    // endStopMode is 1 or 2.
    let h = H::new(CS);
    assert_eq!(h.set_integer("endStopMode", 3), Fmi2Status::Error);
    // A value below a declared min is refused by the set itself, naming the range
    // (the modelDescription's min = 0 of the masses, stiffness and tolerance).
    for name in [
        "platformMass",
        "legMass",
        "endStopStiffness",
        "tolerance",
        "sliderFriction",
    ] {
        let h = H::new(CS);
        assert_eq!(h.set_real(name, -1.0), Fmi2Status::Error, "{name}");
        let message = h.last_message();
        assert!(
            message.contains(name) && message.contains("outside [0,"),
            "{message}"
        );
    }
}

#[test]
fn initial_pose_from_actuators_matches_theta0_default() {
    // Truth: the default theta0 is defined as the pose with every actuator at mid-stroke,
    // 77 mm (thx = thy = 0 by symmetry; thz = 139.79 deg by `robofmu pss3 fk`); forward
    // kinematics from l0 = 77 mm must find it and the inverse kinematics (output l) must
    // return 77 mm.
    let h = H::new(CS);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    let theta = h.vector("theta");
    assert!(
        theta[0].abs() < 1e-12 && theta[1].abs() < 1e-12,
        "{theta:?}"
    );
    assert!((theta[2].to_degrees() - 139.7893).abs() < 5e-5, "{theta:?}");
    assert!(close(h.vector("l"), Vector3::repeat(0.077), 1e-13));
    let k = H::new(CS);
    assert_eq!(k.set_boolean("initFromActuators", true), Fmi2Status::Ok);
    assert_eq!(k.initialize(), Fmi2Status::Ok);
    assert!(close(k.vector("theta"), Vector3::from(theta), 1e-13));
}

#[test]
fn a_step_into_an_error_stop_is_discarded_with_the_state_unchanged() {
    // Truth: FMI 2.0 fmi2Discard semantics; endStopMode 2 refuses leaving the stroke.
    // Pushing actuator 1 outwards hard (1 kN) drives it past 152 mm within 0.5 s.
    let h = tilted(CS);
    assert_eq!(h.set_integer("endStopMode", 2), Fmi2Status::Ok);
    h.set_vector("actuatorForce", [1000.0, 0.0, 0.0]);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(h.step(0.0, 0.01), Fmi2Status::Ok);
    let before = (h.vector("theta"), h.vector("omega"));
    assert_eq!(h.step(0.01, 0.5), Fmi2Status::Discard);
    assert_eq!((h.vector("theta"), h.vector("omega")), before);
    assert!(h.messages(Fmi2Status::Discard)[0].contains("stroke"));
    assert_eq!(h.last_successful_time(), 0.01);
    // A solver failure (a trial stage left the stroke) may pass with a smaller step.
    assert!(!h.terminated());
}

#[test]
fn model_exchange_derivatives_discard_where_the_pose_cannot_assemble() {
    // Truth: at thy = 1.2 rad (69 deg) the legs cannot reach the platform (spec
    // workspace |thy| < 12 deg); FMI 2.0 allows fmi2Discard from fmi2GetDerivatives.
    let h = tilted(ME);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    h.enter_continuous_time_mode();
    let (status, dx) = h.derivatives();
    assert_eq!(status, Fmi2Status::Ok);
    let plant = Plant::new(PlantParams::default()).unwrap();
    let d = plant
        .derivative(&library_state(), &PlantInputs::default())
        .unwrap();
    assert_eq!(dx[..3], *d.euler_rates.as_slice());
    assert_eq!(dx[3..], *d.omega_dot.as_slice());
    let mut x = h.states();
    x[1] = 1.2;
    assert_eq!(h.set_states(&x), Fmi2Status::Ok);
    assert_eq!(h.derivatives().0, Fmi2Status::Discard);
    assert_eq!(h.event_indicators().0, Fmi2Status::Discard);
    // The instance stays usable: back to a valid state.
    x[1] = THETA[1];
    assert_eq!(h.set_states(&x), Fmi2Status::Ok);
    assert_eq!(h.derivatives(), (Fmi2Status::Ok, dx));
    // A wrong array length is an error, not a Discard.
    let mut short = [0.0; 5];
    let s =
        unsafe { robofmu_fmi::fmi2::api::get_derivatives::<Pss3Plant>(h.c, short.as_mut_ptr(), 5) };
    assert_eq!(s, Fmi2Status::Error);
}

#[test]
fn stop_contacts_change_only_at_events() {
    // Truth: the stroke [2, 152] mm; indicators l - strokeMin and strokeMax - l (with
    // the 1 nm hysteresis) change sign where atStop must change, and discrete outputs
    // change only in event mode (FMI 2.0 ME).
    let h = tilted(ME);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    h.enter_continuous_time_mode();
    let l = h.vector("l");
    let (_, z) = h.event_indicators();
    assert!((z[0] - (l[0] - 0.002 + 1e-9)).abs() < 1e-15, "{z:?}");
    assert!((z[1] - (0.152 + 1e-9 - l[0])).abs() < 1e-15, "{z:?}");
    // Move the pose until actuator 1 is beyond its lower stop: find it by scanning roll.
    let mut x = h.states();
    let lower_roll = (0..2000)
        .map(|k| THETA[2] - 1e-3 * k as f64)
        .find(|&roll| {
            x[2] = roll;
            h.set_states(&x);
            h.vector("l")[0] < 0.001
        })
        .expect("actuator 1 reaches its lower stop by lowering the roll");
    x[2] = lower_roll;
    h.set_states(&x);
    assert!(h.event_indicators().1[0] < 0.0);
    assert!(h.vector("stopForce")[0] > 0.0);
    assert_eq!(h.integer("atStop[1]"), 0, "not before the event");
    h.handle_event();
    assert_eq!(h.integer("atStop[1]"), -1);
    assert!(
        h.event_indicators().1[0] < 0.0,
        "consistent after the event"
    );
}

#[test]
fn directional_derivatives_match_finite_differences() {
    // Truth: plain central differences (step 1e-6) of fmi2GetDerivatives and fmi2GetReal
    // through the FMI interface itself, accurate to about 1e-8 relative.
    let h = tilted(ME);
    h.set_vector("actuatorForce", [20.0, -5.0, 12.0]);
    h.set_vector("generalizedForceCommand", [0.4, -0.2, 0.7]);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    h.enter_continuous_time_mode();
    let x0 = h.states();
    let step = 1e-6;
    let state_names = [
        "theta[1]", "theta[2]", "theta[3]", "omega[1]", "omega[2]", "omega[3]",
    ];
    let unknowns = [
        "der(theta[2])",
        "der(omega[1])",
        "der(omega[3])",
        "omegaDot[2]",
    ];
    let row = |name: &str| match name {
        "der(theta[2])" => 1,
        "der(omega[1])" => 3,
        "der(omega[3])" => 5,
        _ => 4,
    };
    let mut worst: f64 = 0.0;
    for (j, known) in state_names.iter().enumerate() {
        let mut plus = x0.clone();
        let mut minus = x0.clone();
        plus[j] += step;
        minus[j] -= step;
        h.set_states(&plus);
        let (_, dp) = h.derivatives();
        let lp = h.vector("l");
        h.set_states(&minus);
        let (_, dm) = h.derivatives();
        let lm = h.vector("l");
        h.set_states(&x0);
        for unknown in unknowns {
            let fd = (dp[row(unknown)] - dm[row(unknown)]) / (2.0 * step);
            let exact = h.directional(unknown, known);
            worst = worst.max((exact - fd).abs() / (1.0 + fd.abs()));
        }
        let fd = (lp[1] - lm[1]) / (2.0 * step);
        worst = worst.max((h.directional("l[2]", known) - fd).abs() / (1.0 + fd.abs()));
    }
    for known in [
        "actuatorForce[2]",
        "generalizedForceCommand[1]",
        "disturbanceTorque[3]",
    ] {
        let value = h.real(known);
        let (_, d0) = h.derivatives();
        assert_eq!(h.set_real(known, value + 1.0), Fmi2Status::Ok);
        let (_, d1) = h.derivatives();
        let f1 = h.vector("force");
        assert_eq!(h.set_real(known, value), Fmi2Status::Ok);
        let f0 = h.vector("force");
        for unknown in unknowns {
            // The state derivative is affine in the inputs: a unit step is exact.
            let fd = d1[row(unknown)] - d0[row(unknown)];
            worst = worst.max((h.directional(unknown, known) - fd).abs() / (1.0 + fd.abs()));
        }
        let fd = f1[0] - f0[0];
        worst = worst.max((h.directional("force[1]", known) - fd).abs() / (1.0 + fd.abs()));
    }
    println!("worst relative difference {worst:.2e}");
    assert!(worst < 1e-6, "{worst}");
}

#[test]
fn fmu_state_round_trip_is_bit_for_bit() {
    // Truth: determinism. get state, step, restore, step again: the same bits; the
    // serialized bytes of the restored state equal the saved ones.
    let h = tilted(CS);
    h.set_vector("actuatorForce", [20.0, -5.0, 12.0]);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(h.step(0.0, 0.05), Fmi2Status::Ok);
    let saved = h.serialize();
    let run = |h: &H| {
        assert_eq!(h.step(0.05, 0.05), Fmi2Status::Ok);
        assert_eq!(h.step(0.1, 0.05), Fmi2Status::Ok);
        (h.vector("theta"), h.vector("omega"), h.vector("l"))
    };
    let first = run(&h);
    assert_eq!(h.restore(&saved), Fmi2Status::Ok);
    assert_eq!(h.serialize(), saved);
    assert_eq!(run(&h), first);
    // Bytes of another model or corrupted bytes are refused.
    let mut corrupted = saved.clone();
    let last = corrupted.len() - 20;
    corrupted[last] ^= 1;
    assert_eq!(h.restore(&corrupted), Fmi2Status::Error);
}

#[test]
fn bad_arguments_and_sequences_are_errors() {
    // Truth: FMI 2.0 state machine and argument rules.
    let h = H::new(CS);
    assert_eq!(h.step(0.0, 0.01), Fmi2Status::Error, "doStep before init");
    let h = H::new(CS);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(h.set_real("lp", 0.7), Fmi2Status::Error, "fixed after init");
    let h = H::new(CS);
    assert_eq!(h.set_real("actuatorForce[1]", f64::NAN), Fmi2Status::Error);
    let h = H::new(ME);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(h.step(0.0, 0.01), Fmi2Status::Error, "doStep in ME");
}

#[test]
fn dependencies_name_only_inputs_and_states() {
    // Truth: FMI 2.0 ModelStructure, the knowns of outputs and derivatives are inputs
    // and continuous states; a dependency on a parameter is refused by the layer.
    use robofmu_fmi::core::flatten::flatten;
    use robofmu_fmi::core::instance::sorted_table;
    use robofmu_fmi::core::variables::check_table;
    use robofmu_fmi::core::{Declaration, Variability};
    assert_eq!(check_table(&sorted_table::<Pss3Plant>().unwrap()), Ok(()));
    const K: Declaration<()> = Declaration::real("k", "a parameter", |_, _| 1.0)
        .parameter(Variability::Fixed)
        .start_real(&[1.0])
        .set_real(|_, _, _| Ok(()));
    static TABLE: &[Declaration<()>] = &[
        K,
        Declaration::real("y", "an output", |_, _| 1.0)
            .output()
            .depends_on(&[K.var()]),
    ];
    let error = check_table(&flatten(TABLE)).unwrap_err();
    assert!(
        error.contains("neither an input nor a continuous state"),
        "{error}"
    );
}
