//! The closed loop with the controller sampled at 1 ms (output held between ticks)
//! against the exact zero-order-hold recursion of the linearised loop, the tick times
//! against their decimal values, and the tracking requirement.

mod common;

use common::scenario;
use nalgebra::Vector3;
use robofmu::closed_loop::{
    Controller, LoopSpec, design_gains, simulate, simulate_sampled, tracking,
};
use robofmu::computed_torque::{ComputedTorque, pole_placement};
use robofmu::control::trajectory::{Boundary, Order, Polynomial};
use robofmu::pss3::dynamics::{Plant, PlantParams};

const BANDWIDTH: f64 = 30.0;
const PERIOD: f64 = 1e-3;

fn hold(target: Vector3<f64>, stop: f64) -> [Polynomial; 3] {
    std::array::from_fn(|i| {
        let b = Boundary {
            q0: target[i],
            qf: target[i],
            ..Boundary::default()
        };
        Polynomial::new(Order::Quintic, 0.0, stop, &b).unwrap()
    })
}

/// Regulation to `target` from `target + offset` with `controller`, sampled every 1 ms
/// over 0.4 s.
fn regulation(target: Vector3<f64>, offset: Vector3<f64>, controller: Controller) -> LoopSpec {
    LoopSpec {
        name: "regulation".into(),
        aliases: ["planner".into(), "pid".into(), "plant".into()],
        start_time: 0.0,
        stop_time: 0.4,
        step_size: 0.001,
        trajectories: hold(target, 0.4),
        later_segments: Vec::new(),
        controller,
        plant: PlantParams::default(),
        theta0: target + offset,
        omega0: Vector3::zeros(),
    }
}

/// The exact zero-order-hold recursion of one linearised axis, x'' = c_k - kappa x with
/// the controller's command c_k = (law output) / m held over each tick plus the gravity
/// change the held feedforward misses, kappa (x_k - x), kappa = G'/M (G' the slope of
/// the axis's generalized gravity force, M the axis's inertia), and the sampled law on
/// the rate path without filter (e = -x, rate error = -v):
///   law_k = -Kp x_k + Ki I_k - Kd v_k,  I_k+1 = I_k - Ts x_k,
///   x_k+1 = C x_k + S v_k + P f_k,  v_k+1 = -kappa S x_k + C v_k + S f_k,
///   f_k = law_k / m + kappa x_k,
/// with C = cos(w Ts), S = sin(w Ts)/w, P = (1 - C)/w^2, w^2 = kappa (their power series,
/// valid for either sign of kappa). Returns x_k for k = 0..=n from x_0 = x0 at rest.
fn linear_recursion(axis: &Axis, x0: f64, n: usize) -> Vec<f64> {
    let ts = PERIOD;
    let (mut c, mut s, mut p) = (0.0, 0.0, 0.0);
    let mut term = 1.0;
    for j in 0..12 {
        // term = (-kappa)^j ts^(2j) / (2j)!
        c += term;
        s += term * ts / (2 * j + 1) as f64;
        p += term * ts * ts / ((2 * j + 1) * (2 * j + 2)) as f64;
        term *= -axis.kappa * ts * ts / ((2 * j + 1) * (2 * j + 2)) as f64;
    }
    let (mut x, mut v, mut integral) = (x0, 0.0, 0.0);
    let mut out = vec![x];
    for _ in 0..n {
        let law = -axis.kp * x + axis.ki * integral - axis.kd * v;
        let f = law / axis.m + axis.kappa * x;
        integral -= ts * x;
        (x, v) = (c * x + s * v + p * f, -axis.kappa * s * x + c * v + s * f);
        out.push(x);
    }
    out
}

/// One axis of the linearised loop: the law's inertia m (the design inertia for the
/// PID, 1 for computed torque, whose gains are accelerations), kappa and the gains.
struct Axis {
    m: f64,
    kappa: f64,
    kp: f64,
    ki: f64,
    kd: f64,
}

/// kappa = G'_aa / M_aa at the target for each axis: the slope of the generalized
/// gravity force (central differences, step 1e-6 rad, error ~1e-12 relative) over the
/// diagonal of M_x.
fn gravity_stiffness(target: &Vector3<f64>) -> Vector3<f64> {
    let plant = Plant::new(PlantParams::default()).unwrap();
    let mass = plant
        .model()
        .euler_angle_form(target, &Vector3::zeros())
        .unwrap()
        .mass;
    Vector3::from_fn(|a, _| {
        let h = 1e-6;
        let at = |d: f64| {
            let mut pose = *target;
            pose[a] += d;
            plant.gravity_compensation(&pose).unwrap()[a]
        };
        (at(h) - at(-h)) / (2.0 * h) / mass[(a, a)]
    })
}

/// Decimal time of tick k at 1 ms, read by the correctly rounding float parser.
fn decimal_ms(k: usize) -> f64 {
    format!("{}.{:03}", k / 1000, k % 1000).parse().unwrap()
}

/// Runs the regulation from an offset x0 (rad) on each axis in turn and returns the
/// worst deviation from the linear recursion and from the continuous triple-pole closed
/// form, both relative to x0.
fn regulation_deviation(
    controller: impl Fn() -> Controller,
    axis_of: impl Fn(usize, f64) -> Axis,
    x0: f64,
) -> (f64, f64) {
    let target = Vector3::new(0.0, 0.0, 138f64.to_radians());
    let kappa = gravity_stiffness(&target);
    let (mut worst, mut from_continuous): (f64, f64) = (0.0, 0.0);
    for axis in 0..3 {
        let offset = Vector3::from_fn(|i, _| if i == axis { x0 } else { 0.0 });
        let spec = regulation(target, offset, controller());
        let samples = simulate_sampled(&spec, PERIOD, 1e-12).unwrap();
        let truth = linear_recursion(&axis_of(axis, kappa[axis]), x0, samples.len() - 1);
        for (k, s) in samples.iter().enumerate() {
            assert_eq!(s.time, decimal_ms(k), "tick {k}");
            let error = s.theta - target;
            worst = worst.max((error[axis] - truth[k]).abs() / x0);
            let wt = BANDWIDTH * s.time;
            let continuous = x0 * (1.0 + wt - wt * wt) * (-wt).exp();
            from_continuous = from_continuous.max((error[axis] - continuous).abs() / x0);
            for other in (0..3).filter(|&i| i != axis) {
                assert!(error[other].abs() < 1e-4 * x0, "axis {other} coupled");
            }
        }
    }
    (worst, from_continuous)
}

/// The deviations (relative to x0) from the recursion at x0 = 1e-6 and 1e-5 rad: below
/// 1e-6 x0 and shrinking with x0 (a second-order residual, 1.6e-7 and 2.3e-9 measured
/// at 1e-6 for the PID and computed torque; a first-order error, such as a missing
/// gravity term (2.2e-6) or a tick off by one, would not shrink); the continuous
/// closed form is 1.1e-2 x0 away, so the test tells sampled from continuous.
fn assert_linear_part_exact(small: (f64, f64), large: (f64, f64)) {
    assert!(small.0 < 1e-6, "worst deviation {:e} x0", small.0);
    assert!(
        small.0 < 0.2 * large.0,
        "{:e} vs {:e}: not second order",
        small.0,
        large.0
    );
    assert!(small.1 > 1e-3, "{:e} x0 from the continuous loop", small.1);
}

#[test]
fn sampled_pid_regulation_follows_the_zero_order_hold_recursion() {
    // Truth: at the flat pose M_x is diagonal and the feedforward cancels gravity, so
    // each axis is m x'' = u (as in tests/closed_loop.rs); with the output held between
    // ticks the motion at the ticks is exactly `linear_recursion` (with the gravity
    // change within a tick). The nonlinear loop differs by terms of order x0^2.
    let plant = Plant::new(PlantParams::default()).unwrap();
    let target = Vector3::new(0.0, 0.0, 138f64.to_radians());
    let design = design_gains(&plant, &[target], BANDWIDTH).unwrap();
    let g = design.gains;
    let run = |x0| {
        regulation_deviation(
            || Controller::Pid(g),
            |axis, kappa| Axis {
                m: design.inertia[axis],
                kappa,
                kp: g[axis].kp,
                ki: g[axis].ki,
                kd: g[axis].kd,
            },
            x0,
        )
    };
    assert_linear_part_exact(run(1e-6), run(1e-5));
}

#[test]
fn sampled_computed_torque_regulation_follows_the_zero_order_hold_recursion() {
    // Truth: with a perfect model the law commands the acceleration a_k at each tick
    // (unit inertia in the error dynamics), held between ticks up to the model's change
    // over a tick, so each axis's error follows `linear_recursion` with m = 1 and the
    // law's own gains.
    let gains = pole_placement(BANDWIDTH, true).unwrap();
    let law = ComputedTorque::new(PlantParams::default(), [gains; 3]).unwrap();
    let run = |x0| {
        regulation_deviation(
            || Controller::ComputedTorque(Box::new(law.clone())),
            |_, kappa| Axis {
                m: 1.0,
                kappa,
                kp: gains.kp,
                ki: gains.ki,
                kd: gains.kd,
            },
            x0,
        )
    };
    assert_linear_part_exact(run(1e-6), run(1e-5));
}

#[test]
fn sampled_controllers_at_1_ms_meet_the_tracking_requirement() {
    // Requirement of the closed-loop issue (RMS error below 0.05 deg), met by the
    // sampled PID and computed torque at 1 ms as by the continuous laws; the sampled
    // loop stays within 1e-4 deg of the continuous one (1e-5 and 2e-7 deg measured).
    for name in ["three_axis_quintic.toml", "path1_cubic_ct.toml"] {
        let spec = scenario(name);
        let sampled = simulate_sampled(&spec, PERIOD, 1e-10).unwrap();
        let continuous = simulate(&spec, 1e-10).unwrap();
        let t = tracking(&sampled);
        assert!(t.rms_error.to_degrees() < 0.05, "{name}: {t:?}");
        let apart = sampled
            .iter()
            .zip(&continuous)
            .map(|(s, c)| (s.theta - c.theta).amax())
            .fold(0.0, f64::max);
        assert!(
            apart.to_degrees() < 5e-3,
            "{name}: {} deg",
            apart.to_degrees()
        );
        assert!(apart > 0.0);
    }
}

#[test]
fn a_step_size_off_the_ticks_or_a_bad_period_is_refused() {
    let spec = scenario("regulation.toml");
    let e = simulate_sampled(&spec, 3e-4, 1e-10)
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a whole number of sample periods"), "{e}");
    for p in [0.0, -1e-3, f64::NAN] {
        let e = simulate_sampled(&spec, p, 1e-10).unwrap_err().to_string();
        assert!(e.contains("sample period"), "{p}: {e}");
    }
}
