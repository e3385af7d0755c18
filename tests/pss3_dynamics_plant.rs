//! The plant API: inverse/forward dynamics, statics, linearisation, communication
//! steps, outputs and refused inputs.

use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use robofmu::pss3::dynamics::{
    DynamicsError, EndStops, Friction, Inertia, InputRamp, Method, Plant, PlantInputs,
    PlantParamError, PlantParams, PlantState, StateVector, StepSettings, StopContact,
};
use robofmu::pss3::rotation::euler_from_rotation;
use robofmu::pss3::{KinematicsError, ParamError, assemble, jacobian};

fn tilted_state() -> PlantState {
    PlantState {
        euler: Vector3::new(0.06, -0.04, 2.35),
        omega: Vector3::new(0.4, -0.9, 1.3),
    }
}

fn loads() -> PlantInputs {
    PlantInputs {
        forces: Vector3::new(25.0, -8.0, 14.0),
        disturbance_torque: Vector3::new(0.3, -0.2, 0.5),
        commanded_torque: Vector3::new(-1.0, 0.5, 2.0),
        generalized_force: Vector3::zeros(),
    }
}

fn rough_plant() -> Plant {
    Plant::new(PlantParams {
        friction: Friction {
            slider: 12.0,
            pivot: 0.15,
        },
        ..PlantParams::default()
    })
    .unwrap()
}

#[test]
fn inverse_then_forward_dynamics_returns_the_acceleration() {
    // Truth: the requested omega_dot; friction and a disturbance act in both directions.
    let plant = rough_plant();
    let state = tilted_state();
    let wanted = Vector3::new(3.0, -1.5, 7.0);
    let disturbance = Vector3::new(0.3, -0.2, 0.5);
    let forces = plant
        .inverse_dynamics(&state, &wanted, &disturbance)
        .unwrap();
    let inputs = PlantInputs {
        forces,
        disturbance_torque: disturbance,
        commanded_torque: Vector3::zeros(),
        generalized_force: Vector3::zeros(),
    };
    let got = plant.derivative(&state, &inputs).unwrap().omega_dot;
    println!("forces {forces:?}, error {:.1e}", (got - wanted).amax());
    assert!((got - wanted).amax() < 1e-12 * wanted.amax());
}

#[test]
fn static_forces_balance_gravity_through_the_statics() {
    // Truth: the gravity moment as the derivative of the total potential energy with
    // respect to a small rotation of the platform about each axis of {A} (central
    // differences, Richardson-extrapolated), mapped to forces by f = J^-T tau.
    let plant = Plant::new(PlantParams::default()).unwrap();
    let model = plant.model();
    let euler = Vector3::new(0.09, -0.07, 2.3);
    let potential = |axis: usize, angle: f64| {
        let turn = Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::ith(axis, 1.0)), angle);
        let rotated = euler_from_rotation(
            &(turn.matrix()
                * model
                    .terms(&euler, &Vector3::zeros())
                    .unwrap()
                    .assembly
                    .rotation),
        );
        model.potential_energy(&assemble(&model.geometry, &rotated).unwrap())
    };
    let slope = |axis: usize, h: f64| (potential(axis, h) - potential(axis, -h)) / (2.0 * h);
    let moment = Vector3::from_fn(|k, _| (4.0 * slope(k, 5e-4) - slope(k, 1e-3)) / 3.0);
    let asm = assemble(&model.geometry, &euler).unwrap();
    let expected = jacobian(&model.geometry, &asm)
        .unwrap()
        .forces(&moment)
        .unwrap();

    let rest = PlantState {
        euler,
        omega: Vector3::zeros(),
    };
    let holding = plant
        .inverse_dynamics(&rest, &Vector3::zeros(), &Vector3::zeros())
        .unwrap();
    println!("holding forces {holding:?} N, from the potential {expected:?} N");
    assert!((holding - expected).amax() < 1e-7 * expected.amax());
    // And they do hold: zero acceleration at rest.
    let inputs = PlantInputs {
        forces: holding,
        ..PlantInputs::default()
    };
    assert!(plant.derivative(&rest, &inputs).unwrap().omega_dot.amax() < 1e-12);
}

#[test]
fn commanded_torque_acts_like_the_forces_of_the_statics() {
    // Truth: f = J^-T tau from the core statics; both inputs give the same motion and
    // the outputs report the realised actuator forces.
    let plant = Plant::new(PlantParams::default()).unwrap();
    let state = tilted_state();
    let tau = Vector3::new(-1.0, 0.5, 2.0);
    let asm = assemble(&plant.model().geometry, &state.euler).unwrap();
    let f = jacobian(&plant.model().geometry, &asm)
        .unwrap()
        .forces(&tau)
        .unwrap();
    let commanded = PlantInputs {
        commanded_torque: tau,
        ..PlantInputs::default()
    };
    let direct = PlantInputs {
        forces: f,
        ..PlantInputs::default()
    };
    let a = plant.derivative(&state, &commanded).unwrap().omega_dot;
    let b = plant.derivative(&state, &direct).unwrap().omega_dot;
    assert!((a - b).amax() < 1e-12 * b.amax());
    let outputs = plant.outputs(&state, &commanded).unwrap();
    assert!((outputs.actuator_forces - f).amax() < 1e-12 * f.amax());
}

#[test]
fn linearization_matches_finite_differences() {
    // Truth: plain central differences of the derivative with a different step (1e-5),
    // accurate to about 1e-9 relative; the input block is exact (linear inputs).
    let plant = rough_plant();
    let (state, inputs) = (tilted_state(), loads());
    let lin = plant.linearize(&state, &inputs).unwrap();
    let rate = |s: &PlantState, u: &PlantInputs| {
        let d = plant.derivative(s, u).unwrap();
        StateVector::from_iterator(d.euler_rates.iter().chain(d.omega_dot.iter()).copied())
    };
    let h = 1e-5;
    let mut worst_state: f64 = 0.0;
    for k in 0..6 {
        let (mut plus, mut minus) = (state.to_vector(), state.to_vector());
        plus[k] += h;
        minus[k] -= h;
        let fd = (rate(&PlantState::from_vector(&plus), &inputs)
            - rate(&PlantState::from_vector(&minus), &inputs))
            / (2.0 * h);
        worst_state = worst_state.max((lin.state.column(k) - fd).amax() / lin.state.amax());
    }
    let mut worst_input: f64 = 0.0;
    for k in 0..9 {
        let shift = |sign: f64| {
            let mut u = inputs;
            let field = match k / 3 {
                0 => &mut u.forces,
                1 => &mut u.disturbance_torque,
                _ => &mut u.commanded_torque,
            };
            field[k % 3] += sign;
            rate(&state, &u)
        };
        let fd = (shift(1.0) - shift(-1.0)) / 2.0;
        worst_input = worst_input.max((lin.inputs.column(k) - fd).amax() / lin.inputs.amax());
    }
    println!("state block {worst_state:.1e}, input block {worst_input:.1e}");
    assert!(worst_state < 1e-7 && worst_input < 1e-10);
}

#[test]
fn communication_steps_land_on_their_end_and_compose() {
    // Truth: the flow property x(2h) = x(h) o x(h) and agreement of two different
    // Runge-Kutta pairs at tight tolerance.
    let plant = rough_plant();
    let (state, inputs) = (tilted_state(), loads());
    let tight = |method| StepSettings {
        method,
        tolerance: 1e-12,
        max_step: 1e-3,
        max_internal_steps: 100_000,
    };
    let one = plant
        .advance(&state, &inputs, 0.02, &tight(Method::Dop853))
        .unwrap();
    let half = plant
        .advance(&state, &inputs, 0.01, &tight(Method::Dop853))
        .unwrap();
    let two = plant
        .advance(&half, &inputs, 0.01, &tight(Method::Dop853))
        .unwrap();
    let dopri = plant
        .advance(&state, &inputs, 0.02, &tight(Method::Dopri5))
        .unwrap();
    let gap = |a: &PlantState, b: &PlantState| (a.to_vector() - b.to_vector()).amax();
    println!(
        "one vs two steps {:.1e}, Dop853 vs Dopri5 {:.1e}",
        gap(&one, &two),
        gap(&one, &dopri)
    );
    assert!(gap(&one, &two) < 1e-10 && gap(&one, &dopri) < 1e-9);
    assert!(gap(&one, &state) > 1e-3, "the state must move");
}

#[test]
fn steps_with_an_input_ramp_compose_and_differ_from_held_inputs() {
    // Truth: the flow property of the time-varying system: one step of 20 ms along the
    // ramp equals two steps of 10 ms, the second starting from the ramp's value and
    // derivatives at 10 ms (u(10 ms), u' + u'' 10 ms, u''); both at tolerance 1e-12.
    let plant = rough_plant();
    let (state, inputs) = (tilted_state(), loads());
    let mut ramp = InputRamp::default();
    ramp.rate.forces = Vector3::new(300.0, -120.0, 50.0);
    ramp.acceleration.forces = Vector3::new(-2e4, 0.0, 8e3);
    ramp.rate.disturbance_torque = Vector3::new(0.0, 4.0, 0.0);
    ramp.rate.commanded_torque = Vector3::new(-10.0, 0.0, 5.0);
    ramp.acceleration.generalized_force = Vector3::new(0.0, 300.0, 0.0);
    let tight = StepSettings {
        method: Method::Dop853,
        tolerance: 1e-12,
        max_step: 1e-3,
        max_internal_steps: 100_000,
    };
    let step = |s: &PlantState, u: &PlantInputs, r: &InputRamp, h: f64| {
        plant.advance_with_ramp(s, u, r, h, &tight).unwrap()
    };
    let one = step(&state, &inputs, &ramp, 0.02);
    let half = step(&state, &inputs, &ramp, 0.01);
    let mut later = ramp;
    later.rate.forces += ramp.acceleration.forces * 0.01;
    later.rate.generalized_force += ramp.acceleration.generalized_force * 0.01;
    let two = step(&half, &ramp.inputs_at(&inputs, 0.01), &later, 0.01);
    let held = step(&state, &inputs, &InputRamp::default(), 0.02);
    let gap = |a: &PlantState, b: &PlantState| (a.to_vector() - b.to_vector()).amax();
    println!(
        "one vs two ramp steps {:.1e}, ramp vs held {:.1e}",
        gap(&one, &two),
        gap(&one, &held)
    );
    assert!(gap(&one, &two) < 1e-10);
    assert!(gap(&one, &held) > 1e-4);
    // A held ramp is `advance` itself, bit for bit.
    assert_eq!(held, plant.advance(&state, &inputs, 0.02, &tight).unwrap());
}

#[test]
fn outputs_are_consistent_with_the_kinematics() {
    // Truth: the core library's IK and Jacobian, and 1/2 omega.M omega.
    let plant = Plant::new(PlantParams::default()).unwrap();
    let (state, inputs) = (tilted_state(), loads());
    let o = plant.outputs(&state, &inputs).unwrap();
    let g = &plant.model().geometry;
    let asm = assemble(g, &state.euler).unwrap();
    let j = jacobian(g, &asm).unwrap();
    assert_eq!(o.actuator_displacements, asm.l);
    assert!((o.actuator_velocities - j.matrix * state.omega).amax() < 1e-15);
    assert_eq!((o.jacobian_det, o.jacobian_cond), (j.det(), j.cond()));
    let terms = plant.model().terms(&state.euler, &state.omega).unwrap();
    assert_eq!(
        o.kinetic_energy,
        0.5 * state.omega.dot(&(terms.mass * state.omega))
    );
    assert_eq!(o.end_stop_contacts, [StopContact::Free; 3]);
    assert_eq!(o.end_stop_energy, 0.0);
    assert_eq!(
        o.omega_dot,
        plant.derivative(&state, &inputs).unwrap().omega_dot
    );
}

#[test]
fn end_stops_push_back_into_the_stroke() {
    // Truth: thz = 110 deg needs every actuator below the 2 mm stop (the start pose
    // l = 2 mm is at 122.07 deg), so the lower stops push with k d - c l_dot > 0.
    let plant = Plant::new(PlantParams::default()).unwrap();
    let state = PlantState {
        euler: Vector3::new(0.0, 0.0, 110f64.to_radians()),
        omega: Vector3::zeros(),
    };
    let o = plant.outputs(&state, &PlantInputs::default()).unwrap();
    let k = EndStops::default().stiffness;
    for i in 0..3 {
        let depth = 0.002 - o.actuator_displacements[i];
        assert!(depth > 0.0);
        assert_eq!(o.end_stop_contacts[i], StopContact::Lower);
        assert_eq!(o.end_stop_contacts[i].code(), -1);
        assert!((o.end_stop_forces[i] - k * depth).abs() < 1e-9 * k * depth);
    }
    let depth = o.actuator_displacements.map(|l| 0.002 - l);
    let stored = 0.5 * k * depth.norm_squared();
    assert!((o.end_stop_energy - stored).abs() < 1e-12 * stored);
}

#[test]
fn invalid_parameters_and_inputs_are_refused() {
    // Truth: the validation rules of PlantParams (documented on each field).
    let with = |f: fn(&mut PlantParams)| {
        let mut p = PlantParams::default();
        f(&mut p);
        Plant::new(p).unwrap_err()
    };
    assert_eq!(
        with(|p| p.geometry.a = -1.0),
        PlantParamError::Geometry(ParamError::NotPositive("a", -1.0))
    );
    assert_eq!(
        with(|p| p.inertia.leg_mass = -0.1),
        PlantParamError::Negative("leg_mass", -0.1)
    );
    assert_eq!(
        with(|p| p.gravity.z = f64::NAN),
        PlantParamError::NotFinite("gravity")
    );
    assert_eq!(
        with(|p| p.friction.slider = -3.0),
        PlantParamError::Negative("slider_friction", -3.0)
    );
    assert_eq!(
        with(|p| p.end_stops.stiffness = 0.0),
        PlantParamError::NotPositive("end_stop_stiffness", 0.0)
    );
    assert_eq!(
        with(|p| p.inertia.leg_com_fraction = 1.5),
        PlantParamError::OutsideUnitInterval("leg_com_fraction", 1.5)
    );
    // A flat disc has I_zz = I_xx + I_yy; a larger I_zz cannot exist.
    assert!(matches!(
        with(|p| p.inertia.platform_inertia =
            Matrix3::from_diagonal(&Vector3::new(0.01, 0.01, 0.05))),
        PlantParamError::InertiaNotPhysical(_)
    ));
    // The default platform tensor is realisable about its centre of mass.
    assert!(Inertia::default().validate().is_ok());

    let plant = Plant::new(PlantParams::default()).unwrap();
    let state = tilted_state();
    let bad = PlantInputs {
        forces: Vector3::new(1.0, f64::INFINITY, 0.0),
        ..PlantInputs::default()
    };
    assert_eq!(
        plant.derivative(&state, &bad),
        Err(DynamicsError::NotFinite("actuator forces"))
    );
    let torn = PlantState {
        euler: Vector3::new(1.05, 0.0, 2.3),
        omega: Vector3::zeros(),
    };
    assert!(matches!(
        plant.derivative(&torn, &PlantInputs::default()),
        Err(DynamicsError::Kinematics(
            KinematicsError::CannotAssemble { .. }
        ))
    ));
    let settings = StepSettings {
        tolerance: 0.0,
        ..StepSettings::default()
    };
    assert_eq!(
        plant.advance(&state, &PlantInputs::default(), 0.01, &settings),
        Err(DynamicsError::InvalidSetting("tolerance", 0.0))
    );
}
