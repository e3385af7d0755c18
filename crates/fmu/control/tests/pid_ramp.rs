//! The PID step for inputs that follow a quadratic over the step (`pid_ramp`) against
//! truths computed another way: Simpson's rule (exact for the quadratic error), the
//! convolution integral of the filter by fine quadrature, and the closed-form response
//! to a linear error.

use robofmu_control::pid::{self, PidGains, PidInputs, PidState};
use robofmu_control::pid_ramp::{PidInputRamp, output_slope, step_with_ramp};

fn gains(tf: f64) -> PidGains {
    PidGains {
        kp: 2.0,
        ki: 0.5,
        kd: 0.3,
        tf,
        limits: None,
        use_rate_inputs: false,
    }
}

/// Error 0.4 - (-0.2) = 0.6, rate 1.5, second derivative -4.
fn quadratic_error() -> (PidInputs, PidInputRamp) {
    let start = PidInputs {
        setpoint: 0.4,
        measurement: -0.2,
        ..PidInputs::default()
    };
    let ramp = PidInputRamp {
        rate: PidInputs {
            setpoint: 1.0,
            measurement: -0.5,
            ..PidInputs::default()
        },
        acceleration: PidInputs {
            measurement: 4.0,
            ..PidInputs::default()
        },
    };
    (start, ramp)
}

fn error_at(s: f64) -> f64 {
    0.6 + 1.5 * s - 4.0 * s * s / 2.0
}

/// Composite Simpson's rule of f over [0, h] with n (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, h: f64, n: usize) -> f64 {
    let dx = h / n as f64;
    let inner: f64 = (1..n)
        .map(|k| f(k as f64 * dx) * if k % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (f(0.0) + inner + f(h)) * dx / 3.0
}

#[test]
fn the_integral_takes_the_whole_quadratic_error() {
    // Truth: Simpson's rule with two intervals is exact for a quadratic.
    let (start, ramp) = quadratic_error();
    let s0 = PidState {
        integral: 0.3,
        filter: -0.1,
    };
    for h in [1e-3, 0.05, 0.7] {
        let stepped = step_with_ramp(&gains(0.05), &s0, &start, &ramp, h);
        let want = 0.3 + simpson(error_at, h, 2);
        assert!((stepped.integral - want).abs() < 1e-15, "h = {h}");
    }
}

#[test]
fn the_filter_state_is_the_convolution_of_the_quadratic_input() {
    // Truth: x(h) = x0 exp(-h/Tf) + (1/Tf) int_0^h exp(-(h - s)/Tf) w(s) ds, the
    // integral by Simpson's rule with 20000 intervals (error below 1e-14 here), over
    // filter time constants from z = h/Tf = 2e-5 (series branch) to z = 50 (expm1
    // branch), the boundary z = 1 included.
    let (start, ramp) = quadratic_error();
    let x0 = -0.1;
    let s0 = PidState {
        integral: 0.0,
        filter: x0,
    };
    let h = 0.01;
    for tf in [500.0, 0.5, 0.01, 0.004, 2e-4] {
        let stepped = step_with_ramp(&gains(tf), &s0, &start, &ramp, h);
        let kernel = |s: f64| (-(h - s) / tf).exp() * error_at(s) / tf;
        let want = x0 * (-h / tf).exp() + simpson(kernel, h, 20_000);
        let scale = want.abs().max(1e-3);
        assert!(
            (stepped.filter - want).abs() < 1e-12 * scale,
            "Tf = {tf}: {} vs {want}",
            stepped.filter
        );
    }
}

#[test]
fn steps_with_slopes_follow_a_linear_error_exactly_at_any_step_size() {
    // Truth: e(t) = a + b t from zero state: I(t) = a t + b t^2/2 and
    // x(t) = a (1 - exp(-t/Tf)) + b (t - Tf + Tf exp(-t/Tf)) (Laplace inverse of
    // 1/(Tf s + 1) on a step and a ramp); bound 1e-12: rounding of 2000 additions.
    let (a, b, tf) = (0.25, -0.8, 0.05);
    let g = gains(tf);
    for h in [1e-3, 0.01, 0.1, 0.37] {
        let mut s = PidState::default();
        let mut t = 0.0;
        for _ in 0..(2.0 / h) as usize {
            let inputs = PidInputs {
                setpoint: a + b * t,
                ..PidInputs::default()
            };
            let ramp = PidInputRamp {
                rate: PidInputs {
                    setpoint: b,
                    ..PidInputs::default()
                },
                ..PidInputRamp::default()
            };
            s = step_with_ramp(&g, &s, &inputs, &ramp, h);
            t += h;
            let decay = (-t / tf).exp();
            let integral = a * t + b * t * t / 2.0;
            let filter = a * (1.0 - decay) + b * (t - tf + tf * decay);
            assert!((s.integral - integral).abs() < 1e-12, "h = {h}, t = {t}");
            assert!((s.filter - filter).abs() < 1e-12, "h = {h}, t = {t}");
        }
    }
}

#[test]
fn the_rate_path_filters_the_ramped_rate_error() {
    // Truth: rate error r(s) = r0 + r1 s from filter state 0 with Tf:
    // x(h) = r0 (1 - exp(-z)) + r1 Tf (z - 1 + exp(-z)), z = h/Tf (as above).
    let g = PidGains {
        use_rate_inputs: true,
        ..gains(0.02)
    };
    let start = PidInputs {
        setpoint_rate: 0.3,
        measured_rate: -0.1,
        ..PidInputs::default()
    };
    let ramp = PidInputRamp {
        rate: PidInputs {
            measured_rate: 2.0,
            ..PidInputs::default()
        },
        ..PidInputRamp::default()
    };
    let h = 0.03;
    let z: f64 = h / 0.02;
    let stepped = step_with_ramp(&g, &PidState::default(), &start, &ramp, h);
    let want = 0.4 * (1.0 - (-z).exp()) - 2.0 * 0.02 * (z - 1.0 + (-z).exp());
    assert!((stepped.filter - want).abs() < 1e-15);
}

#[test]
fn held_inputs_step_bit_identically_and_a_frozen_integral_stays_frozen() {
    let (start, ramp) = quadratic_error();
    let s0 = PidState {
        integral: 0.3,
        filter: -0.1,
    };
    let g = gains(0.05);
    // A held ramp is the zero-order-hold step itself, bit for bit.
    let held = step_with_ramp(&g, &s0, &start, &PidInputRamp::default(), 0.01);
    assert_eq!(held, pid::step(&g, &s0, &start, 0.01));
    // At the upper limit with a positive error the integral stops for the whole step,
    // ramp or not (the decision is the step start's).
    let limited = PidGains {
        limits: Some((-1.0, 1.0)),
        ..g
    };
    let stepped = step_with_ramp(&limited, &s0, &start, &ramp, 0.01);
    assert_eq!(stepped.integral, 0.3);
}

#[test]
fn order_mut_names_the_rates_and_the_accelerations() {
    // Expected: order 1 is the field `rate`, order 2 `acceleration` (the module's
    // q(s) = q + q' s + q'' s^2/2), any other order none.
    let (_, mut ramp) = quadratic_error();
    let expected = ramp;
    assert_eq!(ramp.order_mut(1).map(|r| *r), Some(expected.rate));
    assert_eq!(ramp.order_mut(2).map(|a| *a), Some(expected.acceleration));
    assert!(ramp.order_mut(0).is_none() && ramp.order_mut(3).is_none());
    ramp.order_mut(2).expect("order 2").setpoint = 7.0;
    assert_eq!(
        (ramp.acceleration.setpoint, ramp.rate),
        (7.0, expected.rate)
    );
}

#[test]
fn held_slopes_are_the_derivatives_of_the_closed_form_and_zero_at_a_limit() {
    // Expected values: the derivatives of the closed form of the step response
    // of a constant error from the zero state, u(t) = Kp + Ki t + Kd/Tf exp(-t/Tf): u' = Ki - Kd/Tf^2 exp(-t/Tf),
    // u'' = Kd/Tf^3 exp(-t/Tf), u''' = -Kd/Tf^4 exp(-t/Tf).
    let g = gains(0.05);
    let held = PidInputRamp::default();
    let inputs = PidInputs {
        setpoint: 1.0,
        ..PidInputs::default()
    };
    let mut s = PidState::default();
    for k in 0..20 {
        let t = k as f64 * 0.007;
        let a = 0.3 * (-t / 0.05).exp();
        let want = [
            0.5 - a / 0.05f64.powi(2),
            a / 0.05f64.powi(3),
            -a / 0.05f64.powi(4),
        ];
        for (n, w) in (1..=3).zip(want) {
            let got = output_slope(&g, &s, &inputs, &held, n);
            assert!((got - w).abs() <= 1e-12 * w.abs().max(1.0), "t={t} n={n}");
        }
        s = pid::step(&g, &s, &inputs, 0.007);
    }
    assert_eq!(
        output_slope(&g, &s, &inputs, &held, 0),
        pid::output(&g, &s, &inputs).u
    );
    // The rate path: D = Kd x, x' = (r - x)/Tf: u' = Kd (r - x)/Tf (+ Ki e, e = 0).
    let rate = PidGains {
        use_rate_inputs: true,
        ..g
    };
    let moving = PidInputs {
        setpoint_rate: 0.25,
        ..PidInputs::default()
    };
    let x = PidState {
        integral: 0.0,
        filter: 0.1,
    };
    let d1 = output_slope(&rate, &x, &moving, &held, 1);
    assert!((d1 - 0.3 * 0.15 / 0.05).abs() < 1e-15, "{d1}");
    // Beyond the upper limit, and at it pushing out: the output is the limit.
    let at = |integral: f64| PidState {
        integral,
        filter: 0.0,
    };
    // u_raw = 2 + 0.5 I + 6 (filter 0): about 1.5 at I = -13, the limit here.
    let edge = pid::output(&g, &at(-13.0), &inputs).u_raw;
    assert!((edge - 1.5).abs() < 1e-14);
    let limited = PidGains {
        limits: Some((-1.0, edge)),
        ..g
    };
    for n in 1..=2 {
        assert_eq!(output_slope(&limited, &at(0.0), &inputs, &held, n), 0.0);
    }
    // At the limit, u_raw' = 0.5 - 6/0.05 < 0: moving back inside, u_raw's.
    let inside = output_slope(&limited, &at(-13.0), &inputs, &held, 1);
    assert_eq!(inside, output_slope(&g, &at(-13.0), &inputs, &held, 1));
    assert!(inside < 0.0);
}

#[test]
fn ramped_slopes_are_the_derivatives_along_the_ramp() {
    // Expected values: central differences in tau of the output along the ramp, u(tau)
    // = output(step_with_ramp(s, i, ramp, tau), i + i' tau + i'' tau^2 / 2), the step
    // exact for the quadratic inputs (negative tau too), at tau = 0; truncation error
    // O(delta^2), about 1e-6 relative here. Both paths of the derivative term.
    let (start, ramp) = quadratic_error();
    let s = PidState {
        integral: 0.2,
        filter: -0.1,
    };
    for rates in [false, true] {
        let g = PidGains {
            use_rate_inputs: rates,
            ..gains(0.05)
        };
        let i = PidInputs {
            setpoint_rate: 0.3,
            measured_rate: -0.2,
            feedforward: 0.05,
            ..start
        };
        let ramp = PidInputRamp {
            rate: PidInputs {
                setpoint_rate: 2.0,
                feedforward: 0.5,
                ..ramp.rate
            },
            acceleration: PidInputs {
                measured_rate: -3.0,
                feedforward: 1.0,
                ..ramp.acceleration
            },
        };
        let at = |tau: f64| {
            let moved = |x: f64, r: f64, a: f64| x + r * tau + a * tau * tau / 2.0;
            let (r, a) = (&ramp.rate, &ramp.acceleration);
            let inputs = PidInputs {
                setpoint: moved(i.setpoint, r.setpoint, a.setpoint),
                measurement: moved(i.measurement, r.measurement, a.measurement),
                setpoint_rate: moved(i.setpoint_rate, r.setpoint_rate, a.setpoint_rate),
                measured_rate: moved(i.measured_rate, r.measured_rate, a.measured_rate),
                feedforward: moved(i.feedforward, r.feedforward, a.feedforward),
            };
            pid::output(&g, &step_with_ramp(&g, &s, &i, &ramp, tau), &inputs).u
        };
        let d = 1e-4;
        let first = (at(d) - at(-d)) / (2.0 * d);
        let second = (at(d) - 2.0 * at(0.0) + at(-d)) / (d * d);
        let got = [1, 2].map(|n| output_slope(&g, &s, &i, &ramp, n));
        assert!(
            (got[0] - first).abs() < 1e-6 * first.abs().max(1.0),
            "{rates}: {got:?} {first}"
        );
        assert!(
            (got[1] - second).abs() < 1e-5 * second.abs().max(1.0),
            "{rates}: {got:?} {second}"
        );
        // The ramp matters: the held slope differs.
        let held = output_slope(&g, &s, &i, &PidInputRamp::default(), 1);
        assert!((held - got[0]).abs() > 0.1, "{rates}");
    }
}
