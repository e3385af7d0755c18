//! The sampled PID and its tick clock against independent truths: closed forms of the
//! zero-order-hold recursion, a second implementation (the difference equation of the
//! law's transfer function), and decimal parsing for the tick times.

use robofmu_control::pid::{PidGains, PidInputs};
use robofmu_control::sampled::{SampleClock, SampledError, SampledPid};

fn gains() -> PidGains {
    PidGains {
        kp: 2.0,
        ki: 0.5,
        kd: 0.3,
        tf: 0.05,
        limits: None,
        use_rate_inputs: false,
    }
}

fn error_input(e: f64) -> PidInputs {
    PidInputs {
        setpoint: e,
        ..PidInputs::default()
    }
}

#[test]
fn constant_error_gives_the_closed_form_of_the_recursion() {
    // Truth: e_k = 1 from zero state: I_k = k Ts, x_k = 1 - a^k (a = exp(-Ts/Tf)), so
    // u_k = Kp + Ki k Ts + (Kd/Tf) a^k. Between ticks the output is held.
    let g = gains();
    let ts = 0.001;
    let a = (-ts / g.tf).exp();
    let mut law = SampledPid::new(g, ts).unwrap();
    assert_eq!(law.held(), None);
    for k in 0..2000 {
        let u = law.tick(&error_input(1.0)).u;
        let want = g.kp + g.ki * k as f64 * ts + g.kd / g.tf * a.powi(k);
        assert!((u - want).abs() < 1e-12, "tick {k}: {u} vs {want}");
        assert_eq!(law.held().unwrap().u, u);
    }
}

#[test]
fn ramp_error_gives_the_closed_form_of_the_recursion() {
    // Truth: e_k = k Ts from zero state: I_k = Ts^2 k (k - 1) / 2 and the filter
    // x_k+1 = a x_k + (1 - a) k Ts has x_k = Ts (k - (1 - a^k) / (1 - a)) (particular
    // solution Ts (k - 1/(1 - a)) plus the homogeneous one that makes x_0 = 0).
    let g = gains();
    let ts = 0.002;
    let a = (-ts / g.tf).exp();
    let mut law = SampledPid::new(g, ts).unwrap();
    for k in 0..1500 {
        let kf = k as f64;
        let e = kf * ts;
        let u = law.tick(&error_input(e)).u;
        let integral = ts * ts * kf * (kf - 1.0) / 2.0;
        let filter = ts * (kf - (1.0 - a.powi(k)) / (1.0 - a));
        let want = g.kp * e + g.ki * integral + g.kd * (e - filter) / g.tf;
        assert!((u - want).abs() < 1e-12, "tick {k}: {u} vs {want}");
    }
}

/// A deterministic input sequence with steps and oscillation (no random crate).
fn signal(k: usize) -> (f64, f64, f64) {
    let t = k as f64 * 1e-3;
    let setpoint = (7.0 * t).sin() + if k % 97 < 40 { 0.3 } else { -0.2 };
    let measurement = 0.5 * (3.0 * t).cos() - 0.1 * ((k * 7919) % 13) as f64 / 13.0;
    let feedforward = 0.25 * (11.0 * t).sin();
    (setpoint, measurement, feedforward)
}

fn signal_inputs(k: usize) -> PidInputs {
    let (setpoint, measurement, feedforward) = signal(k);
    PidInputs {
        setpoint,
        measurement,
        feedforward,
        ..PidInputs::default()
    }
}

#[test]
fn state_recursion_agrees_with_the_convolution_sum() {
    // Truth: the closed-form solution of the zero-order-hold recursion from zero state,
    // term by term (no recursion, rounding grows only with the number of terms):
    //   u_k = ff_k + Kp e_k + Ki Ts sum_{j<k} e_j
    //         + (Kd/Tf) (e_k - (1 - a) sum_{j<k} a^(k-1-j) e_j).
    for ts in [1e-3, 0.01, 0.07] {
        let g = gains();
        let a = (-ts / g.tf).exp();
        let n = 2000;
        let errors: Vec<f64> = (0..n)
            .map(|k| {
                let i = signal_inputs(k);
                i.setpoint - i.measurement
            })
            .collect();
        let mut law = SampledPid::new(g, ts).unwrap();
        let mut worst: f64 = 0.0;
        for k in 0..n {
            let inputs = signal_inputs(k);
            let u = law.tick(&inputs).u;
            let integral: f64 = errors[..k].iter().sum::<f64>() * ts;
            let filter: f64 = (0..k)
                .map(|j| a.powi((k - 1 - j) as i32) * errors[j])
                .sum::<f64>()
                * (1.0 - a);
            let e = errors[k];
            let want = inputs.feedforward + g.kp * e + g.ki * integral + g.kd / g.tf * (e - filter);
            worst = worst.max((u - want).abs());
        }
        assert!(worst < 1e-12, "Ts = {ts}: worst difference {worst:e}");
    }
}

#[test]
fn state_recursion_agrees_with_the_difference_equation() {
    // Second implementation: the transfer function from e to v = u - ff,
    //   Kp + Ki Ts/(z - 1) + (Kd/Tf)(z - 1)/(z - a),
    // over the common denominator (z - 1)(z - a) is the difference equation
    //   v_k = (1 + a) v_k-1 - a v_k-2 + b0 e_k + b1 e_k-1 + b2 e_k-2,
    //   b0 = Kp + Kd/Tf, b1 = -Kp (1 + a) + Ki Ts - 2 Kd/Tf, b2 = a (Kp - Ki Ts) + Kd/Tf,
    // with zero history (zero state before tick 0). This form amplifies rounding (poles
    // at 1 and at a, near 1 for Ts << Tf; b0 + b1 + b2 = Ki Ts (1 - a) cancels): its own
    // error reaches 1.5e-11 over 5000 ticks at 1 ms, hence 1e-10 here; the convolution
    // sum above is the 1e-12 check.
    for ts in [1e-3, 0.01, 0.07] {
        let g = gains();
        let a = (-ts / g.tf).exp();
        let d = g.kd / g.tf;
        let b = [
            g.kp + d,
            -g.kp * (1.0 + a) + g.ki * ts - 2.0 * d,
            a * (g.kp - g.ki * ts) + d,
        ];
        let mut law = SampledPid::new(g, ts).unwrap();
        let (mut v1, mut v2, mut e1, mut e2) = (0.0, 0.0, 0.0, 0.0);
        let mut worst: f64 = 0.0;
        for k in 0..5000 {
            let inputs = signal_inputs(k);
            let u = law.tick(&inputs).u;
            let e = inputs.setpoint - inputs.measurement;
            let v = (1.0 + a) * v1 - a * v2 + b[0] * e + b[1] * e1 + b[2] * e2;
            worst = worst.max((u - inputs.feedforward - v).abs());
            (v2, v1, e2, e1) = (v1, v, e1, e);
        }
        assert!(worst < 1e-10, "Ts = {ts}: worst difference {worst:e}");
    }
}

#[test]
fn rate_path_samples_the_rate_error() {
    // Truth: unfiltered (Tf = 0), D_k = Kd r_k at each tick; filtered, a constant rate
    // error r gives x_k = r (1 - a^k) and D_k = Kd x_k.
    let r = 0.75;
    let inputs = PidInputs {
        setpoint_rate: 0.25,
        measured_rate: -0.5,
        ..PidInputs::default()
    };
    let rate = PidGains {
        kp: 0.0,
        ki: 0.0,
        use_rate_inputs: true,
        ..gains()
    };
    let mut unfiltered = SampledPid::new(PidGains { tf: 0.0, ..rate }, 0.01).unwrap();
    let mut filtered = SampledPid::new(rate, 0.01).unwrap();
    let a = (-0.01f64 / 0.05).exp();
    for k in 0..200 {
        assert_eq!(unfiltered.tick(&inputs).u, 0.3 * r);
        let want = 0.3 * r * (1.0 - a.powi(k));
        assert!((filtered.tick(&inputs).u - want).abs() < 1e-15, "tick {k}");
    }
}

#[test]
fn conditional_integration_freezes_the_integral_one_tick_past_the_limit() {
    // Truth: Kp = 1, Ki = 2, e = 1, u_max = 3: u_raw_k = 1 + 2 k Ts reaches the limit
    // at the first tick with k Ts >= 1, where the integral (k Ts) then stays. With
    // Ts = 0.3 that is tick 4 (I = 1.2, u_raw = 3.4, u = 3), not I = 1 as in continuous
    // time: the decision is taken at ticks. A reversed error integrates again at once.
    let g = PidGains {
        kp: 1.0,
        ki: 2.0,
        kd: 0.0,
        tf: 0.0,
        limits: Some((-3.0, 3.0)),
        use_rate_inputs: false,
    };
    for (ts, frozen) in [(0.3, 1.2), (0.125, 1.0), (0.7, 1.4)] {
        let mut law = SampledPid::new(g, ts).unwrap();
        for _ in 0..40 {
            law.tick(&error_input(1.0));
        }
        assert!((law.state().integral - frozen).abs() < 1e-14, "Ts = {ts}");
        assert_eq!(law.held().unwrap().u, 3.0);
        let back = law.tick(&error_input(-1.0));
        assert!((back.u - (-1.0 + 2.0 * frozen)).abs() < 1e-14);
        assert!((law.state().integral - (frozen - ts)).abs() < 1e-14);
    }
}

#[test]
fn bad_periods_and_gains_are_refused() {
    for p in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let e = SampledPid::new(gains(), p).unwrap_err();
        assert!(matches!(e, SampledError::Period(_)), "{p}: {e}");
        assert!(SampleClock::from_period(0.0, p).is_err());
    }
    let e = SampledPid::new(PidGains { tf: 0.0, ..gains() }, 1e-3).unwrap_err();
    assert!(e.to_string().contains("derivative filter"), "{e}");
    let e = SampleClock::new(0.0, 0, 1000).unwrap_err();
    assert!(e.to_string().contains("0/1000"), "{e}");
    assert!(SampleClock::new(f64::NAN, 1, 1000).is_err());
    // 1e-19 s needs 19 decimal places.
    assert!(matches!(
        SampleClock::from_period(0.0, 1e-19),
        Err(SampledError::PeriodTooFine(_))
    ));
}

#[test]
fn tick_times_do_not_drift_over_a_million_ticks() {
    // Truth: the decimal time of tick k at 1 ms is "k/1000 s", and Rust's float parser
    // rounds a decimal string correctly: every tick time must be that double exactly.
    // Summing the period instead drifts (1.7e-8 s after 10^6 ticks), which this test
    // would catch.
    let clock = SampleClock::from_period(0.0, 0.001).unwrap();
    assert_eq!(clock.interval(), (1, 1000));
    for k in 0..=1_000_000u64 {
        let decimal: f64 = format!("{}.{:03}", k / 1000, k % 1000).parse().unwrap();
        assert_eq!(clock.tick_time(k), decimal, "tick {k}");
    }
    assert_eq!(clock.tick_time(1_000_000), 1000.0);
    let summed = (0..1_000_000).fold(0.0f64, |t, _| t + 0.001);
    assert!((summed - 1000.0).abs() > 1e-9);
    // Other periods read as the decimals they print as.
    for (period, interval) in [
        (0.01, (1, 100)),
        (2.5e-4, (25, 100_000)),
        (0.125, (125, 1000)),
        (2.0, (2, 1)),
        (1e-18, (1, 1_000_000_000_000_000_000)),
    ] {
        let clock = SampleClock::from_period(1.5, period).unwrap();
        assert_eq!(clock.interval(), interval, "{period}");
        assert_eq!(clock.period(), period);
        assert_eq!(clock.tick_time(0), 1.5);
    }
    // 1 tick of 0.25 ms after 10^6: exactly 250.00025 s after the start.
    let clock = SampleClock::from_period(0.0, 2.5e-4).unwrap();
    assert_eq!(
        clock.tick_time(1_000_001),
        "250.00025".parse::<f64>().unwrap()
    );
}
