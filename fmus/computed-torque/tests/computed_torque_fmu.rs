//! The ComputedTorque FMU through its FMI 2.0 entry points: its output is the
//! library's law for the parameters set through the FMU, the plant's forward dynamics
//! driven by it accelerate as commanded (a second formulation), the integral steps
//! exactly with the PID's anti-windup, and a wrong model is refused by its FMU name.

use nalgebra::Vector3;
use robofmu_computed_torque_fmu::ComputedTorqueFmu;
use robofmu_dynamics::computed_torque::{AxisGains, ComputedTorque, Inputs};
use robofmu_dynamics::pss3::dynamics::{
    EndStopMode, Friction, Plant, PlantInputs, PlantParams, PlantState,
};
use robofmu_dynamics::pss3::rotation::{euler_accelerations, euler_rate_matrix};
use robofmu_fmi::fmi2::types::{FMI2_CO_SIMULATION, FMI2_MODEL_EXCHANGE, Fmi2Status};
use robofmu_fmi_testing::{Host, vr};

type Fmu = Host<ComputedTorqueFmu>;

/// A reproducible uniform sequence in [0, 1) (64-bit LCG, Knuth's MMIX constants).
struct Uniform(u64);

impl Uniform {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn vector(&mut self, centre: [f64; 3], half_width: f64) -> Vector3<f64> {
        Vector3::from(centre).map(|c| c + half_width * (2.0 * self.next() - 1.0))
    }
}

/// A random controller state: inputs inside the workspace with fast motion and
/// errors of up to a degree, and an error integral.
fn random_state(r: &mut Uniform) -> (Inputs, Vector3<f64>) {
    // Inside the stroke box (the plant's end stops idle, the controller ignores them).
    let theta = r.vector([0.0, 0.0, 138f64.to_radians()], 3f64.to_radians());
    let theta_dot = r.vector([0.0; 3], 1.0);
    let inputs = Inputs {
        setpoint: theta + r.vector([0.0; 3], 1f64.to_radians()),
        setpoint_rate: theta_dot + r.vector([0.0; 3], 0.1),
        setpoint_acceleration: r.vector([0.0; 3], 10.0),
        measurement: theta,
        measured_rate: theta_dot,
    };
    (inputs, r.vector([0.0; 3], 1e-3))
}

fn set_inputs(h: &Fmu, i: &Inputs) {
    h.set_vector("setpoint", i.setpoint.into());
    h.set_vector("setpointRate", i.setpoint_rate.into());
    h.set_vector("setpointAcceleration", i.setpoint_acceleration.into());
    h.set_vector("measurement", i.measurement.into());
    h.set_vector("measuredRate", i.measured_rate.into());
}

/// The plant's parameters with viscous friction (so the friction terms count).
fn rough_robot() -> PlantParams {
    PlantParams {
        friction: Friction {
            slider: 25.0,
            pivot: 0.08,
        },
        ..PlantParams::default()
    }
}

/// A Model Exchange instance with gains per axis and the model `rough_robot` with the
/// leg mass scaled by `leg_mass_factor`, in continuous-time mode.
fn model_exchange(gains: &[AxisGains; 3], leg_mass_factor: f64) -> Fmu {
    let h = Fmu::new(FMI2_MODEL_EXCHANGE);
    for (k, g) in gains.iter().enumerate() {
        for (name, v) in [("Kp", g.kp), ("Kd", g.kd), ("Ki", g.ki)] {
            assert_eq!(h.set_real(&format!("{name}[{}]", k + 1), v), Fmi2Status::Ok);
        }
    }
    let nominal = rough_robot();
    let leg_mass = nominal.inertia.leg_mass * leg_mass_factor;
    for (name, v) in [
        ("legMass", leg_mass),
        ("sliderFriction", 25.0),
        ("pivotFriction", 0.08),
    ] {
        assert_eq!(h.set_real(name, v), Fmi2Status::Ok);
    }
    assert_eq!(h.initialize(), Fmi2Status::Ok, "{}", h.last_message());
    h.enter_continuous_time_mode();
    h
}

fn gains() -> [AxisGains; 3] {
    [0, 1, 2].map(|k| AxisGains {
        kp: 2700.0 + 150.0 * k as f64,
        kd: 90.0 - 3.0 * k as f64,
        ki: 27000.0 - 1000.0 * k as f64,
        limits: None,
    })
}

#[test]
fn the_output_is_the_library_law_for_the_parameters_set() {
    // Truth: robofmu_dynamics::computed_torque::ComputedTorque built here with the same model
    // (leg mass 20 % above the spec's, friction) and gains; the FMU must reproduce it
    // at random states to rounding (the same arithmetic: 1e-12 relative).
    let h = model_exchange(&gains(), 1.2);
    let mut model = rough_robot();
    model.inertia.leg_mass *= 1.2;
    let law = ComputedTorque::new(model, gains()).unwrap();
    let mut r = Uniform(23);
    for _ in 0..40 {
        let (inputs, integral) = random_state(&mut r);
        set_inputs(&h, &inputs);
        assert_eq!(h.set_states(integral.as_slice()), Fmi2Status::Ok);
        let expected = law.output(&integral, &inputs).unwrap().u;
        let u = Vector3::from(h.vector("u"));
        let scale = expected.amax().max(1.0);
        assert!((u - expected).amax() <= 1e-12 * scale, "{u} vs {expected}");
        let (s, dx) = h.derivatives();
        assert_eq!(s, Fmi2Status::Ok);
        let error = inputs.setpoint - inputs.measurement;
        assert_eq!(dx, error.as_slice(), "unlimited: the integral's rate is e");
    }
}

#[test]
fn the_plant_driven_by_the_fmu_output_accelerates_as_commanded() {
    // Truth: the plant's forward dynamics (Plant::derivative, the plant FMU's
    // equations) driven by u with the controller's model equal to the plant's: the
    // Euler-angle accelerations are the commanded a = q_ddot + Kd e_dot + Kp e + Ki I,
    // written out here from the gains. Tolerance: the mass matrix solve in forward
    // dynamics against its product in the law, 1e-9 of |a|.
    let h = model_exchange(&gains(), 1.0);
    // End stops as errors: a state outside the stroke fails instead of adding a stop
    // force the controller does not model.
    let mut robot = rough_robot();
    robot.end_stops.mode = EndStopMode::Error;
    let plant = Plant::new(robot).unwrap();
    let mut r = Uniform(5);
    for _ in 0..20 {
        let (i, integral) = random_state(&mut r);
        set_inputs(&h, &i);
        assert_eq!(h.set_states(integral.as_slice()), Fmi2Status::Ok);
        let commanded = Vector3::from_fn(|k, _| {
            let g = gains()[k];
            i.setpoint_acceleration[k]
                + g.kd * (i.setpoint_rate[k] - i.measured_rate[k])
                + g.kp * (i.setpoint[k] - i.measurement[k])
                + g.ki * integral[k]
        });
        let theta = i.measurement;
        let state = PlantState {
            euler: theta,
            omega: euler_rate_matrix(&theta) * i.measured_rate,
        };
        let command = PlantInputs {
            generalized_force: Vector3::from(h.vector("u")),
            ..PlantInputs::default()
        };
        let d = plant.derivative(&state, &command).unwrap();
        let achieved = euler_accelerations(&theta, &i.measured_rate, &d.omega_dot).unwrap();
        assert!(
            (achieved - commanded).amax() < 1e-9 * commanded.amax(),
            "{achieved} vs {commanded}"
        );
    }
}

/// An initialized instance of `kind` whose axis 1 is at its upper limit (0.5 N m, far
/// below the output its positive error asks for), with the inputs it was given.
fn limited_on_axis_1(kind: i32) -> (Fmu, Inputs) {
    let h = Fmu::new(kind);
    let (mut inputs, _) = random_state(&mut Uniform(7));
    inputs.setpoint = inputs.measurement + Vector3::new(0.01, -0.004, 0.002);
    assert_eq!(h.set_boolean("limitOutput[1]", true), Fmi2Status::Ok);
    assert_eq!(h.set_real("uMin[1]", -0.5), Fmi2Status::Ok);
    assert_eq!(h.set_real("uMax[1]", 0.5), Fmi2Status::Ok);
    set_inputs(&h, &inputs);
    assert_eq!(h.initialize(), Fmi2Status::Ok, "{}", h.last_message());
    assert_eq!(h.real("u[1]"), 0.5);
    (h, inputs)
}

#[test]
fn a_step_integrates_the_held_error_and_stops_at_a_limit_pushing_out() {
    // Truth: with the inputs held over a step of h the error e is constant, so the
    // integral grows by e h exactly; an axis whose output is at its limit while Ki e
    // pushes further out keeps its integral (the PID's conditional integration).
    let (h, inputs) = limited_on_axis_1(FMI2_CO_SIMULATION);
    let step = 1e-3;
    assert_eq!(h.step(0.0, step), Fmi2Status::Ok);
    let integral = h.vector("integral");
    let error = inputs.setpoint - inputs.measurement;
    assert_eq!(integral[0], 0.0);
    assert_eq!(integral[1], error[1] * step);
    assert_eq!(integral[2], error[2] * step);
}

#[test]
fn a_model_that_is_no_robot_is_refused_by_its_fmu_name() {
    let h = Fmu::with_logging(FMI2_CO_SIMULATION, false);
    // Below the declared min: refused by the set, naming the range.
    assert_eq!(h.set_real("legMass", -1.0), Fmi2Status::Error);
    let message = h.last_message();
    assert!(
        message.contains("\"legMass\" = -1 is outside [0, inf]"),
        "{message}"
    );
    // Within the declared range but no robot (legs too short to reach the platform):
    // refused at initialization by the model, naming the geometry.
    let h = Fmu::with_logging(FMI2_CO_SIMULATION, false);
    assert_eq!(h.set_real("a", 0.35), Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Error);
    let message = h.last_message();
    assert!(
        message.contains("parameter a") || message.contains("lp, ld"),
        "{message}"
    );
}

/// At thx = 80 deg the legs cannot reach the platform joints (the workspace is |thx|,
/// |thy| < 12 deg or so): the controller's model has no inverse dynamics there.
const OUTSIDE: [f64; 3] = [80f64.to_radians(), 0.0, 2.13];

/// The reason the FMU must give at `OUTSIDE`: the pose in degrees and the library's own
/// refusal of it (its inverse dynamics evaluated apart from the FMU).
fn reason_outside() -> String {
    let gains = robofmu_dynamics::computed_torque::pole_placement(30.0, true).unwrap();
    let law = ComputedTorque::new(PlantParams::default(), [gains; 3]).unwrap();
    let inputs = Inputs {
        measurement: OUTSIDE.into(),
        ..Inputs::default()
    };
    let refusal = law.output(&Vector3::zeros(), &inputs).unwrap_err();
    format!(
        "measurement = (80.0000, 0.0000, 122.0400) deg: the controller's model (the \
         geometry lp, ld, gamma, lb, alpha, beta, a) cannot be evaluated at this pose: \
         {refusal}"
    )
}

#[test]
fn outside_the_models_workspace_every_getter_discards_with_the_pose_and_the_reason() {
    // Truth: issue 20's rule, one status for a value the model cannot evaluate: Discard
    // with the model's reason from every getter, derivatives included.
    let h = Fmu::new(FMI2_MODEL_EXCHANGE);
    assert_eq!(h.initialize(), Fmi2Status::Ok, "{}", h.last_message());
    h.enter_continuous_time_mode();
    h.set_vector("measurement", OUTSIDE);
    assert_eq!(
        h.real_at(vr::<ComputedTorqueFmu>("u[2]")).0,
        Fmi2Status::Discard
    );
    let reason = format!("at t = 0 s: {}", reason_outside());
    assert_eq!(h.last_message(), format!("fmi2GetReal: {reason}"));
    assert_eq!(h.derivatives().0, Fmi2Status::Discard);
    assert_eq!(h.last_message(), format!("fmi2GetDerivatives: {reason}"));
    // Back inside, the law acts again.
    h.set_vector("measurement", [0.0, 0.0, 2.13]);
    assert_ne!(h.real("u[1]"), 0.0);
    assert_eq!(h.derivatives().0, Fmi2Status::Ok);
}

#[test]
fn outside_the_models_workspace_at_the_start_initialization_is_refused_naming_it() {
    // Truth: the layer's rule for the start (computed values must exist when
    // initialization ends, docs/reliability.md): Error with the same reason.
    let h = Fmu::new(FMI2_MODEL_EXCHANGE);
    h.set_vector("measurement", OUTSIDE);
    assert_eq!(h.initialize(), Fmi2Status::Error);
    assert!(
        h.last_message().ends_with(&reason_outside()),
        "{}",
        h.last_message()
    );
}

#[test]
fn outside_the_models_workspace_a_step_is_discarded_with_the_reason_and_terminates() {
    // Truth: as above for Co-Simulation; a smaller step cannot help with held inputs,
    // so the FMU asks to terminate (fmi2Terminated) and its integral stays as it was.
    let h = Fmu::new(FMI2_CO_SIMULATION);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(h.step(0.0, 1e-3), Fmi2Status::Ok);
    let integral = h.vector("integral");
    h.set_vector("measurement", OUTSIDE);
    assert_eq!(
        h.real_at(vr::<ComputedTorqueFmu>("u[1]")).0,
        Fmi2Status::Discard
    );
    assert_eq!(h.step(1e-3, 1e-3), Fmi2Status::Discard);
    let logged = h.messages(Fmi2Status::Discard);
    assert!(
        logged.last().unwrap().ends_with(&reason_outside()),
        "{logged:?}"
    );
    assert!(h.terminated());
    assert_eq!(h.vector("integral"), integral);
}

/// The knowns of the directional derivatives: each input array, and the state.
const KNOWN_INPUTS: [&str; 5] = [
    "setpoint",
    "setpointRate",
    "setpointAcceleration",
    "measurement",
    "measuredRate",
];

/// The value of `unknown` ("u[k]" or "der(integral[k])") at the instance's point.
fn unknown_value(h: &Fmu, unknown: &str) -> f64 {
    match unknown.strip_prefix("der(integral[") {
        Some(k) => {
            let (s, dx) = h.derivatives();
            assert_eq!(s, Fmi2Status::Ok, "{}", h.last_message());
            dx[k[..1].parse::<usize>().unwrap() - 1]
        }
        None => h.real(unknown),
    }
}

/// d(unknown)/d(known) by central differences through fmi2SetReal (or
/// fmi2SetContinuousStates for "integral[k]") with one Richardson extrapolation,
/// step 1e-4 (1 + |value|): the independent truth of the directional derivatives.
fn finite_difference(h: &Fmu, unknown: &str, known: &str) -> f64 {
    let state = known
        .strip_prefix("integral[")
        .map(|k| k[..1].parse::<usize>().unwrap() - 1);
    let x0 = match state {
        Some(k) => h.states()[k],
        None => h.real(known),
    };
    let at = |x: f64| {
        match state {
            Some(k) => {
                let mut states = h.states();
                states[k] = x;
                assert_eq!(h.set_states(&states), Fmi2Status::Ok);
            }
            None => assert_eq!(h.set_real(known, x), Fmi2Status::Ok),
        }
        unknown_value(h, unknown)
    };
    let step = 1e-4 * (1.0 + x0.abs());
    let central = |d: f64| (at(x0 + d) - at(x0 - d)) / (2.0 * d);
    let derivative = (4.0 * central(0.5 * step) - central(step)) / 3.0;
    at(x0);
    derivative
}

/// Every (unknown, known) pair of the instance's Jacobian: the directional
/// derivative against `finite_difference`; returns the largest error relative to
/// 1 + |difference| (asserted below 1e-8; measured 1.2e-10).
fn jacobian_error(h: &Fmu, unknowns: &[&str], states_are_known: bool) -> f64 {
    let mut knowns: Vec<String> = KNOWN_INPUTS
        .iter()
        .flat_map(|n| (1..=3).map(move |k| format!("{n}[{k}]")))
        .collect();
    if states_are_known {
        knowns.extend((1..=3).map(|k| format!("integral[{k}]")));
    }
    let mut worst: f64 = 0.0;
    for unknown in unknowns {
        for known in &knowns {
            let analytic = h.directional(unknown, known);
            let expected = finite_difference(h, unknown, known);
            let error = (analytic - expected).abs() / (1.0 + expected.abs());
            assert!(
                error < 1e-8,
                "d {unknown} / d {known}: {analytic} vs differences {expected}"
            );
            worst = worst.max(error);
        }
    }
    worst
}

const OUTPUTS: [&str; 3] = ["u[1]", "u[2]", "u[3]"];
const ALL_UNKNOWNS: [&str; 6] = [
    "u[1]",
    "u[2]",
    "u[3]",
    "der(integral[1])",
    "der(integral[2])",
    "der(integral[3])",
];

#[test]
fn directional_derivatives_match_finite_differences() {
    // Truth: central differences (Richardson-extrapolated) of the FMU's own outputs
    // and state derivatives, moving one input or state at a time through the FMI
    // setters, at random states of a mismatched model (leg mass +20 %, friction).
    // Model Exchange: every output and derivative against every input and state.
    let h = model_exchange(&gains(), 1.2);
    let mut r = Uniform(31);
    let mut worst: f64 = 0.0;
    for _ in 0..4 {
        let (inputs, integral) = random_state(&mut r);
        set_inputs(&h, &inputs);
        assert_eq!(h.set_states(integral.as_slice()), Fmi2Status::Ok);
        worst = worst.max(jacobian_error(&h, &ALL_UNKNOWNS, true));
    }
    // Co-Simulation: the outputs against the inputs, at the defaults.
    let cs = Fmu::new(FMI2_CO_SIMULATION);
    assert_eq!(cs.initialize(), Fmi2Status::Ok, "{}", cs.last_message());
    worst = worst.max(jacobian_error(&cs, &OUTPUTS, false));
    println!("largest relative error against the differences: {worst:.1e}");
}

#[test]
fn directional_derivatives_of_a_limited_axis_and_a_stopped_integral_are_zero() {
    // Truth: the same differences; axis 1's output is at its upper limit (its raw
    // output far above it), so u[1] does not move with any known, and its integral is
    // stopped (Ki e pushes further out), so der(integral[1]) does not either.
    let (h, _) = limited_on_axis_1(FMI2_MODEL_EXCHANGE);
    h.enter_continuous_time_mode();
    jacobian_error(&h, &ALL_UNKNOWNS, true);
    for known in ["setpoint[1]", "measurement[2]", "integral[1]"] {
        assert_eq!(h.directional("u[1]", known), 0.0);
        assert_eq!(h.directional("der(integral[1])", known), 0.0);
    }
    assert_ne!(h.directional("u[2]", "setpoint[2]"), 0.0);
}
