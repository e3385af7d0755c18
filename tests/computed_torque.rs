//! The computed-torque law against independent truths: Lagrange's equations (a second
//! formulation of the dynamics, exact dual-number derivatives), the plant's forward
//! dynamics, and the saturation and anti-windup rules.

use nalgebra::Vector3;
use robofmu::computed_torque::{AxisGains, ComputedTorque, ControllerError, Inputs};
use robofmu::pss3::dynamics::lagrange::{AppliedLoads, lagrange_form, lagrange_generalized_force};
use robofmu::pss3::dynamics::{Friction, Inertia, Plant, PlantInputs, PlantParams, PlantState};
use robofmu::pss3::rotation::{euler_accelerations, euler_rate_matrix};

fn deg(v: [f64; 3]) -> Vector3<f64> {
    Vector3::from(v).map(f64::to_radians)
}

/// The spec's robot with viscous friction, so that the friction terms are exercised.
fn rough_robot() -> PlantParams {
    PlantParams {
        friction: Friction {
            slider: 25.0,
            pivot: 0.08,
        },
        ..PlantParams::default()
    }
}

fn gains(limits: Option<(f64, f64)>) -> [AxisGains; 3] {
    [0, 1, 2].map(|k| AxisGains {
        kp: 2700.0 + 100.0 * k as f64,
        kd: 90.0 - k as f64,
        ki: 27000.0,
        limits,
    })
}

/// States inside the stroke box (end stops idle) with fast, mixed motion.
fn motions() -> [(Vector3<f64>, Vector3<f64>, Vector3<f64>); 3] {
    [
        (deg([0.0, 0.0, 138.0]), Vector3::zeros(), Vector3::zeros()),
        (
            deg([6.0, -5.0, 137.0]),
            Vector3::new(0.8, -1.1, 0.6),
            Vector3::new(3.0, -7.0, 11.0),
        ),
        (
            deg([-4.0, 3.0, 141.0]),
            Vector3::new(-2.0, 0.4, -1.5),
            Vector3::new(-20.0, 5.0, 2.0),
        ),
    ]
}

#[test]
fn on_the_planned_motion_the_output_is_the_lagrange_inverse_dynamics() {
    // Truth: Lagrange's equations M_L q_ddot + (velocity terms) + dV/dq = Q_L, with the
    // friction's generalized force by virtual work; with e = 0 and I = 0 the law's
    // output must be the force that realises the planned acceleration exactly.
    let law = ComputedTorque::new(rough_robot(), gains(None)).unwrap();
    let model = law.model().model();
    for (q, qdot, qddot) in motions() {
        let inputs = Inputs {
            setpoint: q,
            setpoint_rate: qdot,
            setpoint_acceleration: qddot,
            measurement: q,
            measured_rate: qdot,
        };
        let out = law.output(&Vector3::zeros(), &inputs).unwrap();
        assert_eq!(out.acceleration, qddot);
        let form = lagrange_form(model, &q, &qdot).unwrap();
        let friction = AppliedLoads {
            slider_friction: 25.0,
            pivot_friction: 0.08,
            ..AppliedLoads::default()
        };
        let losses = lagrange_generalized_force(model, &q, &qdot, &friction).unwrap();
        let expected = form.mass * qddot + form.velocity + form.gravity - losses;
        let scale = expected.amax().max(1.0);
        assert!(
            (out.u - expected).amax() < 1e-10 * scale,
            "{q}: {} vs {}",
            out.u,
            expected
        );
    }
}

#[test]
fn the_plant_driven_by_the_output_accelerates_as_commanded() {
    // Truth: the plant's forward dynamics (Plant::derivative, which realises u through
    // tau = E^-T u and f = J^-T tau): with the controller's model equal to the plant's,
    // the Euler-angle accelerations equal the commanded a = q_ddot + Kd e_dot + Kp e +
    // Ki I, also away from the planned motion.
    let plant = Plant::new(rough_robot()).unwrap();
    let law = ComputedTorque::new(rough_robot(), gains(None)).unwrap();
    let integral = Vector3::new(1e-4, -2e-4, 3e-4);
    for (theta, theta_dot, qddot) in motions() {
        let inputs = Inputs {
            setpoint: theta + deg([0.3, -0.2, 0.5]),
            setpoint_rate: theta_dot + Vector3::new(0.05, 0.02, -0.04),
            setpoint_acceleration: qddot,
            measurement: theta,
            measured_rate: theta_dot,
        };
        let out = law.output(&integral, &inputs).unwrap();
        let state = PlantState {
            euler: theta,
            omega: euler_rate_matrix(&theta) * theta_dot,
        };
        let command = PlantInputs {
            generalized_force: out.u,
            ..PlantInputs::default()
        };
        let d = plant.derivative(&state, &command).unwrap();
        let achieved = euler_accelerations(&theta, &theta_dot, &d.omega_dot).unwrap();
        assert!(
            (achieved - out.acceleration).amax() < 1e-9 * out.acceleration.amax(),
            "{achieved} vs {}",
            out.acceleration
        );
    }
}

#[test]
fn a_saturated_axis_is_clamped_and_stops_integrating_outward() {
    // Truth: the rules of the law (as the PID's): u = clamp(u_raw); the integral of an
    // axis stops while its output is at a limit and Ki e pushes it further out, and runs
    // on every other axis and when the error pulls back.
    let limited = |lo, hi| {
        let mut g = gains(None);
        g[0].limits = Some((lo, hi));
        g
    };
    let robot = PlantParams::default();
    let (q, qdot, _) = motions()[1];
    let mut inputs = Inputs {
        setpoint: q + deg([0.5, 0.1, -0.1]),
        setpoint_rate: qdot,
        setpoint_acceleration: Vector3::zeros(),
        measurement: q,
        measured_rate: qdot,
    };
    let free = ComputedTorque::new(robot, gains(None)).unwrap();
    let raw = free.output(&Vector3::zeros(), &inputs).unwrap().u_raw;
    assert!(raw[0] > 1.0, "the error pushes axis 1 up: {raw}");
    let law = ComputedTorque::new(robot, limited(-1.0, raw[0] - 1.0)).unwrap();
    let out = law.output(&Vector3::zeros(), &inputs).unwrap();
    assert_eq!(out.u_raw, raw);
    assert_eq!(out.u[0], raw[0] - 1.0);
    assert_eq!((out.u[1], out.u[2]), (raw[1], raw[2]));
    let rate = law.integral_rate(&out);
    assert_eq!(rate[0], 0.0);
    assert_eq!((rate[1], rate[2]), (out.error[1], out.error[2]));
    // The same saturation with an error that pulls back: the integral runs.
    inputs.setpoint[0] = q[0] - 0.5f64.to_radians();
    inputs.setpoint_acceleration[0] = 4000.0;
    let out = law.output(&Vector3::zeros(), &inputs).unwrap();
    assert!(out.u_raw[0] > raw[0] - 1.0 && out.error[0] < 0.0);
    assert_eq!(law.integral_rate(&out)[0], out.error[0]);
    // Unsaturated: the integral is the error.
    let out = free.output(&Vector3::zeros(), &inputs).unwrap();
    assert_eq!(free.integral_rate(&out), out.error);
}

#[test]
fn invalid_gains_and_models_are_refused_by_name() {
    let mut bad = gains(None);
    bad[1].kd = f64::NAN;
    let e = ComputedTorque::new(PlantParams::default(), bad).unwrap_err();
    assert_eq!(e, ControllerError::NonFinite(2, "Kd"));
    let e = ComputedTorque::new(PlantParams::default(), gains(Some((2.0, 2.0)))).unwrap_err();
    assert!(
        e.to_string()
            .contains("axis 1: the output limits are empty"),
        "{e}"
    );
    let negative = PlantParams {
        inertia: Inertia {
            leg_mass: -1.0,
            ..Inertia::default()
        },
        ..PlantParams::default()
    };
    let e = ComputedTorque::new(negative, gains(None)).unwrap_err();
    assert!(e.to_string().contains("leg_mass"), "{e}");
    let law = ComputedTorque::new(PlantParams::default(), gains(None)).unwrap();
    let (q, qdot, _) = motions()[0];
    let nan = Vector3::new(f64::NAN, 0.0, 0.0);
    assert!(law.inverse_dynamics(&q, &qdot, &nan).is_err());
}
